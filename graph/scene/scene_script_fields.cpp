// The checks of a scene declaration's fields against their schema (a number in its range, a
// vector, a colour, a string, a choice, a boolean) and how their errors show a value.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lua/declarations.h"
#include "scene_script_detail.h"

namespace rg::scene_script {

std::string formatNumber(double d) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", d);
    return buf;
}

// A value as an error message shows it: -1, "text", {1, 2, 3}, a table, a boolean.
std::string describe(const Value& v, int depth) {
    if (v.isNumber()) return formatNumber(v.asNumber());
    if (v.isString()) return "\"" + v.asString() + "\"";
    if (v.isBool()) return v.asBool() ? "true" : "false";
    if (v.isList()) {
        if (depth > 0) return "a list";
        std::string s = "{";
        for (size_t i = 0; i < v.asList().size() && i < 6; ++i)
            s += (i ? ", " : "") + describe(v.asList()[i], depth + 1);
        return s + (v.asList().size() > 6 ? ", ...}" : "}");
    }
    if (v.isTable()) return "a table";
    return "nil";
}

Result<double> number(const Where& w, const Value& body, const std::string& field, double def,
                      Range range) {
    const Value& v = body[field];
    if (v.isNil()) return def;
    if (!v.isNumber() || !range.contains(v.asNumber()))
        return w.at(field).error("expected " + range.words() + ", got " + describe(v));
    return v.asNumber();
}

Result<float> numberF(const Where& w, const Value& body, const std::string& field, float def,
                      Range range) {
    auto r = number(w, body, field, def, range);
    if (!r) return std::unexpected(r.error());
    return static_cast<float>(*r);
}

// A list of `n` numbers, each within `range`; `shape` names them in messages ("{x, y, z}").
Result<std::vector<float>> numbers(const Where& w, const Value& v, size_t n,
                                   const std::string& shape, Range range) {
    bool ok = v.isList() && v.asList().size() == n;
    if (ok)
        for (const auto& e : v.asList()) ok = ok && e.isNumber() && range.contains(e.asNumber());
    if (!ok) {
        const std::string each = range.lo == -HUGE_VAL && range.hi == HUGE_VAL
                                     ? " (" + std::to_string(n) + " numbers)"
                                     : " with each value " + range.words("").substr(1);
        return w.error("expected " + shape + each + ", got " + describe(v));
    }
    std::vector<float> out;
    for (const auto& e : v.asList()) out.push_back(static_cast<float>(e.asNumber()));
    return out;
}

Result<glm::vec3> vec3(const Where& w, const Value& body, const std::string& field, glm::vec3 def,
                       const std::string& shape, Range range) {
    const Value& v = body[field];
    if (v.isNil()) return def;
    auto r = numbers(w.at(field), v, 3, shape, range);
    if (!r) return std::unexpected(r.error());
    return glm::vec3((*r)[0], (*r)[1], (*r)[2]);
}

Result<glm::vec3> colour(const Where& w, const Value& body, const std::string& field, glm::vec3 def,
                         Range range) {
    return vec3(w, body, field, def, "{r, g, b}", range);
}

Result<std::string> string(const Where& w, const Value& body, const std::string& field,
                           const std::string& def) {
    const Value& v = body[field];
    if (v.isNil()) return def;
    if (!v.isString() || v.asString().empty())
        return w.at(field).error("expected a string, got " + describe(v));
    return v.asString();
}

Result<std::string> choice(const Where& w, const Value& body, const std::string& field,
                           const std::string& def, const std::vector<std::string>& allowed,
                           const std::string& what) {
    auto s = string(w, body, field, def);
    if (!s) return s;
    if (std::find(allowed.begin(), allowed.end(), *s) == allowed.end())
        return w.at(field).error("unknown " + what + " '" + *s + "'" + suggestion(*s, allowed) +
                                 "; expected one of: " + joinQuoted(allowed));
    return s;
}

Result<bool> boolean(const Where& w, const Value& body, const std::string& field, bool def) {
    const Value& v = body[field];
    if (v.isNil()) return def;
    if (!v.isBool()) return w.at(field).error("expected a boolean, got " + describe(v));
    return v.asBool();
}

}  // namespace rg::scene_script
