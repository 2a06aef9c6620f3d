// IES profiles, the file side (ies.h): the IESNA LM-63 parser (header, keywords, TILT data, the
// candela table), loadIes and the formats' and symmetries' names.
#include "ies.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

namespace rg {

namespace {

// No real profile comes near these; they keep a corrupt header from asking for absurd tables.
constexpr int kMaxAngles = 100000;
constexpr std::uintmax_t kMaxFileBytes = 64u << 20;

std::string_view trim(std::string_view s) {
    const auto blank = [](char c) {
        return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
    };
    while (!s.empty() && blank(s.front())) s.remove_prefix(1);
    while (!s.empty() && blank(s.back())) s.remove_suffix(1);
    return s;
}

bool startsWithNoCase(std::string_view s, std::string_view prefix) {
    if (s.size() < prefix.size()) return false;
    for (size_t i = 0; i < prefix.size(); ++i) {
        const auto up = [](char c) {
            return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
        };
        if (up(s[i]) != up(prefix[i])) return false;
    }
    return true;
}

bool equalsNoCase(std::string_view a, std::string_view b) {
    return a.size() == b.size() && startsWithNoCase(a, b);
}

// Lines with their 1-based numbers; "\r\n", "\r" and "\n" all end a line.
std::vector<std::string_view> splitLines(std::string_view text) {
    std::vector<std::string_view> lines;
    size_t start = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\n' || text[i] == '\r') {
            lines.push_back(text.substr(start, i - start));
            if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
            start = i + 1;
        }
    }
    if (start < text.size()) lines.push_back(text.substr(start));
    return lines;
}

// Blanks and commas both separate values (LM-63-2002 §3.1).
bool isSeparator(char c) { return c == ' ' || c == '\t' || c == ',' || c == '\f' || c == '\v'; }

struct Token {
    std::string_view text;
    int line = 0;
    bool firstOnLine = false;
    bool lastOnLine = false;
};

// A number as LM-63 writes it (optional sign, decimals, exponent); the whole token must be used,
// and it must fit the float the profile stores it in.
bool parseNumber(std::string_view s, double& out) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    if (s.empty()) return false;
    const auto [end, ec] =
        std::from_chars(s.data(), s.data() + s.size(), out, std::chars_format::general);
    return ec == std::errc() && end == s.data() + s.size() &&
           std::abs(out) <= std::numeric_limits<float>::max();
}

bool looksNumeric(std::string_view line) {
    bool any = false;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && isSeparator(line[i])) ++i;
        size_t j = i;
        while (j < line.size() && !isSeparator(line[j])) ++j;
        if (j > i) {
            double v;
            if (!parseNumber(line.substr(i, j - i), v)) return false;
            any = true;
        }
        i = j;
    }
    return any;
}

std::string shorten(std::string_view s) {
    constexpr size_t kMax = 60;
    return s.size() <= kMax ? std::string(s) : std::string(s.substr(0, kMax)) + "...";
}

std::string numberText(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

class Parser {
public:
    Parser(std::string_view text, const std::string& fileName)
        : m_fileName(fileName), m_lines(splitLines(text)) {
        // A UTF-8 byte order mark is not part of the first line.
        if (!m_lines.empty() && m_lines[0].starts_with("\xEF\xBB\xBF")) m_lines[0].remove_prefix(3);
    }

    Result<IesProfile> parse();

private:
    std::unexpected<Error> failAt(int line, std::string message,
                                  ErrorCode code = ErrorCode::InvalidInput) const {
        return fail(code, "'" + m_fileName + "':" + std::to_string(line) + ": " + message);
    }
    int lastLine() const { return std::max(1, static_cast<int>(m_lines.size())); }
    bool atEnd() const { return m_next >= m_tokens.size(); }
    size_t remaining() const { return m_tokens.size() - m_next; }
    // The line where the next value is (or the file's last line at its end).
    int nextLine() const { return atEnd() ? lastLine() : m_tokens[m_next].line; }

    Result<int> header(IesProfile& profile);
    Result<void> tilt(std::string_view line, int lineNumber, IesProfile& profile);

public:
    Result<void> tiltData(IesProfile& profile);
    void tokenizeAll() { tokenize(0); }
    bool atEndOfData() const { return atEnd(); }
    std::unexpected<Error> failAtNext(std::string message) const {
        return failAt(nextLine(), std::move(message));
    }

private:
    void tokenize(size_t firstLine);
    Result<double> number(std::string_view role);
    Result<int> integer(std::string_view role);
    Result<std::vector<float>> angles(int count, std::string_view plural,
                                      std::string_view singular);
    Result<void> wrongCount(int nV, int nH);

    const std::string& m_fileName;
    std::vector<std::string_view> m_lines;
    std::vector<Token> m_tokens;
    size_t m_next = 0;
    // How many values the header's counts call for after the TILT line; a count that the data does
    // not match shows as a block that ends early or late.
    int64_t m_needed = 0;
};

// The format line, keyword / label lines and the TILT line; returns the index of the TILT line.
Result<int> Parser::header(IesProfile& profile) {
    size_t first = 0;
    const std::string_view formatLine = m_lines.empty() ? std::string_view() : trim(m_lines[0]);
    if (formatLine == "IES:LM-63-2019") {
        profile.format = IesFormat::Lm63_2019;
        first = 1;
    } else if (formatLine == "IESNA:LM-63-2002") {
        profile.format = IesFormat::Lm63_2002;
        first = 1;
    } else if (formatLine == "IESNA:LM-63-1995") {
        profile.format = IesFormat::Lm63_1995;
        first = 1;
    } else if (formatLine == "IESNA91" || formatLine == "IESNA:LM-63-1991") {
        profile.format = IesFormat::Lm63_1991;
        first = 1;
    } else if (startsWithNoCase(formatLine, "IESNA") || startsWithNoCase(formatLine, "IES:")) {
        return failAt(1,
                      "unknown IES format '" + shorten(formatLine) +
                          "', expected one of: 'IES:LM-63-2019', 'IESNA:LM-63-2002', "
                          "'IESNA:LM-63-1995', 'IESNA91', or no "
                          "format line (LM-63-1986)",
                      ErrorCode::Unsupported);
    } else {
        profile.format = IesFormat::Lm63_1986;  // no format line: the first line is already a label
    }

    for (size_t i = first; i < m_lines.size(); ++i) {
        const std::string_view line = trim(m_lines[i]);
        const int lineNumber = static_cast<int>(i) + 1;
        if (startsWithNoCase(line, "TILT")) {
            const std::string_view rest = trim(line.substr(4));
            if (rest.starts_with('=')) {
                if (auto t = tilt(trim(rest.substr(1)), lineNumber, profile); !t)
                    return std::unexpected(t.error());
                return static_cast<int>(i);
            }
        }
        if (line.empty()) continue;
        if (looksNumeric(line))
            return failAt(
                lineNumber,
                "missing TILT line: expected 'TILT=NONE' before the photometric data, found '" +
                    shorten(line) + "'");
        if (profile.format != IesFormat::Lm63_1986 && line.front() == '[') {
            const size_t close = line.find(']');
            if (close == std::string_view::npos)
                return failAt(lineNumber, "expected a keyword line '[KEYWORD] text', found '" +
                                              shorten(line) + "'");
            const std::string name(trim(line.substr(1, close - 1)));
            const std::string value(trim(line.substr(close + 1)));
            if (name == "MORE" && !profile.keywords.empty()) {
                profile.keywords.back().value +=
                    "\n" + value;  // [MORE] continues the previous keyword
            } else {
                profile.keywords.push_back({name, value});
            }
            continue;
        }
        profile.keywords.push_back(
            {"", std::string(line)});  // a free-text label (LM-63-1986 style)
    }
    return failAt(lastLine(),
                  "missing TILT line: expected 'TILT=NONE' before the photometric data, found the "
                  "end of the file");
}

Result<void> Parser::tilt(std::string_view value, int lineNumber, IesProfile& profile) {
    if (equalsNoCase(value, "NONE")) return {};
    if (equalsNoCase(value, "INCLUDE")) {
        profile.tilt = "INCLUDE";
        return {};
    }
    if (value.empty())
        return failAt(lineNumber,
                      "expected 'TILT=NONE', 'TILT=INCLUDE' or 'TILT=<file>', found 'TILT='");
    profile.tilt = std::string(value);  // a tilt file: loadIes reads it
    return {};
}

// The tilt block (LM-63-2002 §3.10): lamp-to-luminaire geometry, the number of angles, the angles,
// their multiplying factors.
Result<void> Parser::tiltData(IesProfile& profile) {
    const int geometryLine = nextLine();
    auto geometry = integer("the lamp-to-luminaire geometry (value 1 of the tilt data)");
    if (!geometry) return std::unexpected(geometry.error());
    if (*geometry < 1 || *geometry > 3)
        return failAt(geometryLine, "expected a lamp-to-luminaire geometry of 1, 2 or 3, found " +
                                        std::to_string(*geometry));
    profile.tiltGeometry = *geometry;
    const int countLine = nextLine();
    auto n = integer("the number of tilt angles (value 2 of the tilt data)");
    if (!n) return std::unexpected(n.error());
    if (*n < 1 || *n > kMaxAngles)
        return failAt(countLine, "expected 1.." + std::to_string(kMaxAngles) +
                                     " tilt angles, found " + std::to_string(*n));
    auto tiltAngles = angles(*n, "tilt angles", "tilt angle");
    if (!tiltAngles) return std::unexpected(tiltAngles.error());
    if (tiltAngles->front() < 0.0f || tiltAngles->back() > 180.0f)
        return failAt(countLine, "expected tilt angles within 0..180 degrees, found " +
                                     numberText(tiltAngles->front()) + ".." +
                                     numberText(tiltAngles->back()));
    profile.tiltAngles = std::move(*tiltAngles);
    profile.tiltFactors.clear();
    for (int k = 0; k < *n; ++k) {
        const int line = nextLine();
        auto f = number("tilt multiplying factor " + std::to_string(k + 1) + " of " +
                        std::to_string(*n));
        if (!f) return std::unexpected(f.error());
        if (!(*f >= 0.0) || !std::isfinite(*f))
            return failAt(line, "expected a tilt multiplying factor >= 0, found " + numberText(*f));
        profile.tiltFactors.push_back(static_cast<float>(*f));
    }
    return {};
}

void Parser::tokenize(size_t firstLine) {
    for (size_t l = firstLine; l < m_lines.size(); ++l) {
        const std::string_view line = m_lines[l];
        const size_t before = m_tokens.size();
        size_t i = 0;
        while (i < line.size()) {
            while (i < line.size() && (isSeparator(line[i]) || line[i] == '\r')) ++i;
            size_t j = i;
            while (j < line.size() && !isSeparator(line[j]) && line[j] != '\r') ++j;
            if (j > i)
                m_tokens.push_back({line.substr(i, j - i), static_cast<int>(l) + 1,
                                    m_tokens.size() == before, false});
            i = j;
        }
        if (m_tokens.size() > before) m_tokens.back().lastOnLine = true;
    }
}

Result<double> Parser::number(std::string_view role) {
    if (atEnd())
        return failAt(lastLine(), "truncated file: expected " + std::string(role) +
                                      ", found the end of the file");
    const Token& t = m_tokens[m_next];
    double v = 0.0;
    if (!parseNumber(t.text, v))
        return failAt(t.line, "expected a number for " + std::string(role) + ", found '" +
                                  shorten(t.text) + "'");
    ++m_next;
    return v;
}

Result<int> Parser::integer(std::string_view role) {
    const int line = nextLine();
    const std::string text = atEnd() ? std::string() : std::string(m_tokens[m_next].text);
    auto v = number(role);
    if (!v) return std::unexpected(v.error());
    if (*v != std::floor(*v) || std::abs(*v) > 1e9)
        return failAt(line, "expected an integer for " + std::string(role) + ", found '" +
                                shorten(text) + "'");
    return static_cast<int>(*v);
}

// When the values after the header do not add up to what its counts announce, the usual culprit is
// one wrong count in a table that is otherwise consistent: nV' + nH + nV'·nH or nV + nH' + nV·nH'
// values, the angle list ending at a line break. Name that count and what the data holds.
Result<void> Parser::wrongCount(int nV, int nH) {
    if (static_cast<int64_t>(m_tokens.size()) == m_needed) return {};
    const int64_t rest = static_cast<int64_t>(remaining());
    const auto endsLine = [&](int64_t n) {
        const int64_t i = static_cast<int64_t>(m_next) + n - 1;
        return i >= 0 && i < static_cast<int64_t>(m_tokens.size()) &&
               m_tokens[static_cast<size_t>(i)].lastOnLine;
    };
    if (rest > nH && (rest - nH) % (1 + nH) == 0) {
        const int64_t found = (rest - nH) / (1 + nH);
        if (found != nV && endsLine(found))
            return failAt(nextLine(), "expected " + std::to_string(nV) +
                                          " vertical angles, found " + std::to_string(found));
    }
    if (rest > nV && (rest - nV) % (1 + nV) == 0) {
        const int64_t found = (rest - nV) / (1 + nV);
        if (found != nH && endsLine(nV) && endsLine(nV + found))
            return failAt(m_tokens[m_next + static_cast<size_t>(nV)].line,
                          "expected " + std::to_string(nH) + " horizontal angles, found " +
                              std::to_string(found));
    }
    return {};
}

Result<std::vector<float>> Parser::angles(int count, std::string_view plural,
                                          std::string_view singular) {
    const int startLine = nextLine();
    const bool countsMismatch = static_cast<int64_t>(m_tokens.size()) != m_needed;
    const auto countError = [&](int64_t found) {
        return failAt(startLine, "expected " + std::to_string(count) + " " + std::string(plural) +
                                     ", found " + std::to_string(found));
    };
    std::vector<float> out;
    for (int k = 0; k < count; ++k) {
        if (atEnd())
            return failAt(lastLine(), "truncated file: expected " + std::to_string(count) + " " +
                                          std::string(plural) + ", found " + std::to_string(k));
        const Token& t = m_tokens[m_next];
        auto v = number(std::string(singular) + " " + std::to_string(k + 1) + " of " +
                        std::to_string(count));
        if (!v) return std::unexpected(v.error());
        // Compared as stored (float), so no two table angles can coincide.
        const float angle = static_cast<float>(*v);
        if (k > 0 && angle <= out.back()) {
            // A value that starts a new line and breaks the order is where the next block begins when
            // the values do not add up to what the header announced: the count is wrong.
            if (t.firstOnLine && countsMismatch) return countError(k);
            return failAt(t.line, "expected " + std::string(plural) +
                                      " in increasing order, found " + std::string(t.text) +
                                      " after " + numberText(out.back()));
        }
        out.push_back(angle);
    }
    // The block ends in the middle of a line while the totals do not match: the line holds more.
    if (count > 0 && countsMismatch && !m_tokens[m_next - 1].lastOnLine) {
        int64_t extra = 0;
        for (size_t i = m_next;
             i < m_tokens.size() && m_tokens[i].line == m_tokens[m_next - 1].line; ++i)
            ++extra;
        return countError(count + extra);
    }
    return out;
}

Result<IesProfile> Parser::parse() {
    IesProfile profile;
    profile.fileName = m_fileName;
    auto tiltLine = header(profile);
    if (!tiltLine) return std::unexpected(tiltLine.error());
    tokenize(static_cast<size_t>(*tiltLine) + 1);
    // TILT=INCLUDE: the tilt block comes first; the counts below start after it.
    int64_t tiltValues = 0;
    if (profile.tilt == "INCLUDE") {
        const size_t before = m_next;
        if (auto t = tiltData(profile); !t) return std::unexpected(t.error());
        tiltValues = static_cast<int64_t>(m_next - before);
    }

    // Line 1 after TILT: the lamp and geometry values (LM-63-2002 §3.12–§3.13).
    const int lampsLine = nextLine();
    auto lamps = integer("the number of lamps (value 1 of 10 after TILT)");
    if (!lamps) return std::unexpected(lamps.error());
    if (*lamps < 1)
        return failAt(lampsLine,
                      "expected a positive number of lamps, found " + std::to_string(*lamps));
    profile.numberOfLamps = *lamps;

    const int lumensLine = nextLine();
    auto lumens = number("the lumens per lamp (value 2 of 10 after TILT)");
    if (!lumens) return std::unexpected(lumens.error());
    if (*lumens < 0.0 && *lumens != -1.0)
        return failAt(lumensLine,
                      "expected the lumens per lamp (or -1 for absolute photometry), found " +
                          numberText(*lumens));
    profile.lumens = static_cast<float>(*lumens);

    const int multiplierLine = nextLine();
    auto multiplier = number("the candela multiplier (value 3 of 10 after TILT)");
    if (!multiplier) return std::unexpected(multiplier.error());
    if (*multiplier <= 0.0)
        return failAt(multiplierLine,
                      "expected a positive candela multiplier, found " + numberText(*multiplier));
    profile.multiplier = static_cast<float>(*multiplier);

    const auto count = [&](std::string_view what, std::string_view role) -> Result<int> {
        const int line = nextLine();
        auto n = integer(role);
        if (!n) return std::unexpected(n.error());
        if (*n < 1)
            return failAt(line, "expected a positive number of " + std::string(what) + ", found " +
                                    std::to_string(*n));
        if (*n > kMaxAngles)
            return failAt(line, "expected at most " + std::to_string(kMaxAngles) + " " +
                                    std::string(what) + ", found " + std::to_string(*n));
        return *n;
    };
    auto nV = count("vertical angles", "the number of vertical angles (value 4 of 10 after TILT)");
    if (!nV) return std::unexpected(nV.error());
    auto nH =
        count("horizontal angles", "the number of horizontal angles (value 5 of 10 after TILT)");
    if (!nH) return std::unexpected(nH.error());

    const int typeLine = nextLine();
    auto type = integer("the photometric type (value 6 of 10 after TILT)");
    if (!type) return std::unexpected(type.error());
    if (*type != 1 && *type != 2 && *type != 3)
        return failAt(typeLine, "expected photometric type 1 (C), 2 (B) or 3 (A), found " +
                                    std::to_string(*type));
    profile.photometricType = *type;

    const int unitsLine = nextLine();
    auto units = integer("the units type (value 7 of 10 after TILT)");
    if (!units) return std::unexpected(units.error());
    if (*units != 1 && *units != 2)
        return failAt(unitsLine, "expected units type 1 (feet) or 2 (meters), found " +
                                     std::to_string(*units));
    profile.unitsType = *units;

    float* const geometry[] = {&profile.width, &profile.length, &profile.height};
    const char* const geometryRoles[] = {"the luminous opening width (value 8 of 10 after TILT)",
                                         "the luminous opening length (value 9 of 10 after TILT)",
                                         "the luminous opening height (value 10 of 10 after TILT)"};
    for (int i = 0; i < 3; ++i) {
        auto v = number(geometryRoles[i]);
        if (!v) return std::unexpected(v.error());
        *geometry[i] = static_cast<float>(*v);
    }

    // Line 2 after TILT: ballast factor, ballast-lamp photometric factor ("future use"; LM-63-2019:
    // the file generation type), input watts.
    const bool lm2019 = profile.format == IesFormat::Lm63_2019;
    float* const electrical[] = {&profile.ballastFactor,
                                 lm2019 ? &profile.fileGenerationType : &profile.ballastLampFactor,
                                 &profile.inputWatts};
    const char* const electricalRoles[] = {
        "the ballast factor (value 1 of 3 on the second line after TILT)",
        lm2019 ? "the file generation type (value 2 of 3 on the second line after TILT)"
               : "the ballast-lamp photometric factor (value 2 of 3 on the second line after TILT)",
        "the input watts (value 3 of 3 on the second line after TILT)"};
    for (int i = 0; i < 3; ++i) {
        auto v = number(electricalRoles[i]);
        if (!v) return std::unexpected(v.error());
        *electrical[i] = static_cast<float>(*v);
    }

    const int64_t cells = static_cast<int64_t>(*nV) * *nH;
    m_needed = tiltValues + 13 + *nV + *nH + cells;
    if (auto wrong = wrongCount(*nV, *nH); !wrong) return std::unexpected(wrong.error());

    // Types A and B (LM-63-2002 §3.16, §3.17): both angles within −90..90 degrees of the aiming
    // axis, starting at −90, or at 0 for a distribution the same on both sides (mirrored).
    const bool typeC = profile.photometricType == 1;
    const char* const typeName = profile.photometricType == 2 ? "type B" : "type A";
    const auto checkAB = [&](const std::vector<float>& a, int line, const char* which,
                             bool& mirrored) -> Result<void> {
        if ((a.front() != -90.0f && a.front() != 0.0f) || a.back() > 90.0f)
            return failAt(line, "expected " + std::string(which) +
                                    " angles from -90 or 0 to at most 90 degrees (" + typeName +
                                    "), found " + numberText(a.front()) + ".." +
                                    numberText(a.back()));
        mirrored = a.front() == 0.0f;
        return {};
    };

    // Vertical angles, type C: 0..180 degrees from the nadir.
    const int verticalLine = nextLine();
    auto vertical = angles(*nV, "vertical angles", "vertical angle");
    if (!vertical) return std::unexpected(vertical.error());
    if (!typeC) {
        if (auto r = checkAB(*vertical, verticalLine, "vertical", profile.mirrorVertical); !r)
            return std::unexpected(r.error());
    } else if (vertical->front() < 0.0f || vertical->back() > 180.0f) {
        return failAt(verticalLine,
                      "expected vertical angles within 0..180 degrees (type C), found " +
                          numberText(vertical->front()) + ".." + numberText(vertical->back()));
    }
    profile.verticalAngles = std::move(*vertical);

    // Horizontal angles and the symmetry they imply.
    const int horizontalLine = nextLine();
    auto horizontal = angles(*nH, "horizontal angles", "horizontal angle");
    if (!horizontal) return std::unexpected(horizontal.error());
    const float hFirst = horizontal->front(), hLast = horizontal->back();
    if (!typeC) {
        if (auto r = checkAB(*horizontal, horizontalLine, "horizontal", profile.mirrorHorizontal);
            !r)
            return std::unexpected(r.error());
        profile.symmetry = IesSymmetry::None;
    } else if (horizontal->size() == 1) {
        profile.symmetry = IesSymmetry::Rotational;
    } else if (hFirst == 0.0f && hLast == 90.0f) {
        profile.symmetry = IesSymmetry::Quadrant;
    } else if (hFirst == 0.0f && hLast == 180.0f) {
        profile.symmetry = IesSymmetry::Bilateral;
    } else if (hFirst == 90.0f && hLast == 270.0f) {
        profile.symmetry = IesSymmetry::Bilateral90;
    } else if (hFirst == 0.0f && hLast > 180.0f && hLast <= 360.0f) {
        profile.symmetry = IesSymmetry::None;
    } else {
        return failAt(horizontalLine,
                      "expected horizontal angles 0 (rotationally symmetric), 0..90, 0..180, "
                      "0..360 or 90..270 degrees "
                      "(type C), found " +
                          numberText(hFirst) + ".." + numberText(hLast));
    }
    profile.horizontalAngles = std::move(*horizontal);

    // Candela values: one set of vertical values per horizontal angle.
    const int candelaLine = nextLine();
    const std::string cellsText = std::to_string(cells) + " candela values (" +
                                  std::to_string(*nH) + " horizontal x " + std::to_string(*nV) +
                                  " vertical angles)";
    profile.candela.reserve(
        static_cast<size_t>(std::min<int64_t>(cells, static_cast<int64_t>(remaining()))));
    for (int h = 0; h < *nH; ++h) {
        for (int v = 0; v < *nV; ++v) {
            const int64_t k = static_cast<int64_t>(h) * *nV + v;
            if (atEnd())
                return failAt(lastLine(), "truncated file: expected " + cellsText + ", found " +
                                              std::to_string(k));
            const Token& t = m_tokens[m_next++];
            const auto where = [&] {
                return "horizontal angle " +
                       numberText(profile.horizontalAngles[static_cast<size_t>(h)]) +
                       ", vertical angle " +
                       numberText(profile.verticalAngles[static_cast<size_t>(v)]);
            };
            double c = 0.0;
            if (!parseNumber(t.text, c))
                return failAt(t.line, "expected a number for candela value " +
                                          std::to_string(k + 1) + " of " + std::to_string(cells) +
                                          " (" + where() + "), found '" + shorten(t.text) + "'");
            if (c < 0.0)
                return failAt(t.line, "expected a non-negative candela value at " + where() +
                                          ", found " + std::string(t.text));
            const double cd = c * *multiplier;
            if (cd > std::numeric_limits<float>::max())
                return failAt(
                    t.line, "expected a candela value that times the multiplier fits a float at " +
                                where() + ", found " + std::string(t.text));
            profile.candela.push_back(static_cast<float>(cd));
        }
    }
    if (!atEnd())
        return failAt(candelaLine, "expected " + cellsText + ", found " +
                                       std::to_string(cells + static_cast<int64_t>(remaining())));

    profile.maxCandela = *std::max_element(profile.candela.begin(), profile.candela.end());
    return profile;
}

}  // namespace

std::string_view toString(IesFormat format) {
    switch (format) {
        case IesFormat::Lm63_1986:
            return "LM-63-1986";
        case IesFormat::Lm63_1991:
            return "LM-63-1991";
        case IesFormat::Lm63_1995:
            return "LM-63-1995";
        case IesFormat::Lm63_2002:
            return "LM-63-2002";
        case IesFormat::Lm63_2019:
            return "LM-63-2019";
    }
    return "?";
}

std::string_view toString(IesSymmetry symmetry) {
    switch (symmetry) {
        case IesSymmetry::Rotational:
            return "rotational";
        case IesSymmetry::Quadrant:
            return "quadrant";
        case IesSymmetry::Bilateral:
            return "bilateral";
        case IesSymmetry::Bilateral90:
            return "bilateral-90";
        case IesSymmetry::None:
            return "none";
    }
    return "?";
}

Result<IesProfile> parseIes(std::string_view text, const std::string& fileName) {
    return Parser(text, fileName).parse();
}

Result<void> parseIesTilt(std::string_view text, const std::string& fileName, IesProfile& profile) {
    Parser p(text, fileName);
    p.tokenizeAll();
    if (auto t = p.tiltData(profile); !t) return t;
    if (!p.atEndOfData())
        return p.failAtNext("expected the end of the tilt data, found more values");
    return {};
}

Result<IesProfile> loadIes(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        return fail(ErrorCode::NotFound, "'" + name + "': no such IES file");
    const auto size = std::filesystem::file_size(path, ec);
    if (ec)
        return fail(ErrorCode::Io,
                    "'" + name + "': cannot read the IES file (" + ec.message() + ")");
    if (size > kMaxFileBytes)
        return fail(ErrorCode::InvalidInput,
                    "'" + name + "': expected an IES file of at most 64 MiB, found " +
                        std::to_string(size) + " bytes");
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail(ErrorCode::Io, "'" + name + "': cannot open the IES file");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) return fail(ErrorCode::Io, "'" + name + "': cannot read the IES file");
    auto profile = parseIes(text, name);
    if (!profile || profile->tilt == "NONE" || profile->tilt == "INCLUDE") return profile;
    // TILT=<file>: the tilt data in a file of its own, next to the IES file.
    const std::filesystem::path tiltPath = path.parent_path() / profile->tilt;
    const std::string tiltName = tiltPath.string();
    if (!std::filesystem::is_regular_file(tiltPath, ec))
        return fail(ErrorCode::NotFound, "'" + name + "': TILT=" + profile->tilt +
                                             ": no such tilt file '" + tiltName + "'");
    if (std::filesystem::file_size(tiltPath, ec) > kMaxFileBytes)
        return fail(ErrorCode::InvalidInput,
                    "'" + tiltName + "': expected a tilt file of at most 64 MiB");
    std::ifstream tin(tiltPath, std::ios::binary);
    std::string tiltText((std::istreambuf_iterator<char>(tin)), std::istreambuf_iterator<char>());
    if (!tin && !tin.eof())
        return fail(ErrorCode::Io, "'" + tiltName + "': cannot read the tilt file");
    if (auto t = parseIesTilt(tiltText, tiltName, *profile); !t) return std::unexpected(t.error());
    return profile;
}

}  // namespace rg
