#include "golden/report.h"
#include "core/temp_path.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace rg::golden {

namespace {

// Writes `text` to a temp file beside `path` and renames it, so a failed write leaves what was there.
Result<void> writeTextFile(const std::string& path, const std::string& text) {
    std::error_code ec;
    if (auto parent = fs::path(path).parent_path(); !parent.empty())
        fs::create_directories(parent, ec);
    const std::string tmp = tempPathBeside(path);
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        out.flush();
        if (!out) {
            const int err = errno;
            out.close();
            fs::remove(tmp, ec);
            return fail(ErrorCode::Io, "cannot write '" + path + "': " + std::strerror(err));
        }
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        return fail(ErrorCode::Io, "cannot write '" + path + "': " + ec.message());
    }
    return {};
}

std::string xmlEscape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            default:
                // XML 1.0 has no place for other control characters.
                if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t' && c != '\r')
                    out += '?';
                else
                    out += c;
        }
    }
    return out;
}

std::string seconds(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", s);
    return buf;
}

// RGB of an image as binary16 values (grey replicated, a second channel kept as green).
std::string halfRgb(const Image& img) {
    std::vector<uint8_t> bytes;
    bytes.reserve(size_t(img.width) * img.height * 6);
    for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x)
            for (uint32_t k = 0; k < 3; ++k) {
                float v = img.channels == 1  ? img.at(x, y, 0)
                          : k < img.channels ? img.at(x, y, k)
                                             : 0.0f;
                const uint16_t h = floatToHalfBits(v);
                bytes.push_back(static_cast<uint8_t>(h & 0xffu));
                bytes.push_back(static_cast<uint8_t>(h >> 8));
            }
    return base64Encode(bytes.data(), bytes.size());
}

std::string rgb8(const Image& img) {
    std::vector<uint8_t> bytes;
    bytes.reserve(size_t(img.width) * img.height * 3);
    for (float v : img.pixels)
        bytes.push_back(static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)));
    return base64Encode(bytes.data(), bytes.size());
}

const char* kStyle = R"CSS(
body { font: 14px/1.4 system-ui, sans-serif; margin: 16px 24px; color: #1d1d1f; background: #fafafa; }
h1 { font-size: 22px; margin: 0 0 4px; } h2 { font-size: 18px; margin: 0 0 4px; } h3 { font-size: 15px; margin: 12px 0 4px; }
small, .meta { color: #666; }
table { border-collapse: collapse; margin: 6px 0; }
td, th { border: 1px solid #ddd; padding: 2px 8px; text-align: left; vertical-align: top; }
th { background: #f0f0f0; }
.badge { display: inline-block; min-width: 48px; text-align: center; border-radius: 4px; color: #fff; font-weight: 600; padding: 0 6px; }
.badge.PASS { background: #1a7f37; } .badge.FAIL { background: #cf222e; } .badge.ERROR { background: #9a6700; }
.ok { color: #1a7f37; } .bad { color: #cf222e; font-weight: 600; }
section.test { background: #fff; border: 1px solid #ddd; border-radius: 6px; padding: 12px 16px; margin: 16px 0; }
.message { white-space: pre-wrap; font-family: ui-monospace, monospace; font-size: 12px; background: #fff4f4; padding: 6px; }
.views { display: flex; flex-wrap: wrap; gap: 24px; align-items: flex-start; }
figure { margin: 0; }
figcaption { font-size: 12px; color: #444; margin-bottom: 2px; }
canvas { image-rendering: pixelated; display: block; background: #000; }
.swipebox { position: relative; cursor: ew-resize; }
.swipebox canvas { position: absolute; left: 0; top: 0; }
.swipebox canvas.under { position: relative; }
.divider { position: absolute; top: 0; bottom: 0; width: 1px; background: #fff; pointer-events: none; }
input.swipe { display: block; margin-top: 4px; }
.controls { margin-top: 6px; font-size: 12px; }
.hidden { display: none; }
)CSS";

const char* kScript = R"JS(
(function () {
  'use strict';
  var query = new URLSearchParams(window.location.search);
  var decoded = {};
  function bytes(id) {
    var bin = atob(document.getElementById(id).textContent.trim());
    var a = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; ++i) a[i] = bin.charCodeAt(i);
    return a;
  }
  function halfToFloat(h) {
    var s = (h & 0x8000) ? -1 : 1, e = (h >> 10) & 31, m = h & 1023;
    if (e === 0) return s * m * Math.pow(2, -24);
    if (e === 31) return m ? NaN : s * Infinity;
    return s * (1 + m / 1024) * Math.pow(2, e - 15);
  }
  function image(id) {
    if (decoded[id]) return decoded[id];
    var el = document.getElementById(id), b = bytes(id), data;
    if (el.dataset.kind === 'f16') {
      data = new Float32Array(b.length / 2);
      for (var i = 0; i < data.length; ++i) data[i] = halfToFloat(b[2 * i] | (b[2 * i + 1] << 8));
    } else {
      data = b;
    }
    return decoded[id] = { w: +el.dataset.w, h: +el.dataset.h, kind: el.dataset.kind, data: data };
  }
  function encode(v) {  // linear -> sRGB display value (IEC 61966-2-1)
    if (!(v > 0)) return 0;
    if (v >= 1) return 1;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055;
  }
  // Draws image `id` into a canvas: u8 as it is, f16 either as display values or as linear
  // values scaled by 2^exposure and sRGB-encoded.
  function draw(canvas, id, mode, exposure) {
    var img = image(id), scale = +canvas.dataset.scale || 1;
    canvas.width = img.w; canvas.height = img.h;
    canvas.style.width = (img.w * scale) + 'px'; canvas.style.height = (img.h * scale) + 'px';
    var ctx = canvas.getContext('2d'), out = ctx.createImageData(img.w, img.h), k = Math.pow(2, exposure);
    for (var p = 0, n = img.w * img.h; p < n; ++p) {
      for (var c = 0; c < 3; ++c) {
        var v = img.data[3 * p + c];
        if (img.kind === 'f16') v = mode === 'display' ? Math.min(Math.max(v, 0), 1) * 255 : encode(v * k) * 255;
        out.data[4 * p + c] = v;
      }
      out.data[4 * p + 3] = 255;
    }
    ctx.putImageData(out, 0, 0);
  }
  function setSwipe(block, t) {
    t = Math.min(Math.max(t, 0), 1);
    var over = block.querySelector('canvas.over'), divider = block.querySelector('.divider');
    var slider = block.querySelector('input.swipe');
    if (!over) return;
    over.style.clipPath = 'inset(0 0 0 ' + (t * 100) + '%)';
    divider.style.left = (t * 100) + '%';
    slider.value = Math.round(t * 1000);
  }
  function render(block, exposure) {
    var mode = block.dataset.mode;
    block.querySelectorAll('canvas[data-img]').forEach(function (cv) {
      draw(cv, cv.dataset.img, cv.dataset.raw ? 'display' : mode, exposure);
    });
    var out = block.querySelector('output.ev');
    if (out) out.textContent = (exposure >= 0 ? '+' : '') + exposure.toFixed(1) + ' EV';
    var input = block.querySelector('input.exposure');
    if (input) input.value = exposure;
  }
  var swipe0 = query.has('swipe') ? parseFloat(query.get('swipe')) : 0.5;
  var exposure0 = query.has('exposure') ? parseFloat(query.get('exposure')) : null;
  if (query.has('test')) {
    document.querySelectorAll('section.test').forEach(function (s) {
      if (s.dataset.test !== query.get('test')) s.classList.add('hidden');
    });
    document.querySelectorAll('tr[data-test]').forEach(function (r) {
      if (r.dataset.test !== query.get('test')) r.classList.add('hidden');
    });
  }
  if (query.get('failed') === '1') {
    document.querySelectorAll('section.test.PASS, tr.PASS').forEach(function (s) { s.classList.add('hidden'); });
  }
  document.querySelectorAll('.capture').forEach(function (block) {
    var exposure = exposure0 !== null && block.dataset.mode === 'linear' ? exposure0 : +block.dataset.exposure;
    render(block, exposure);
    var ev = block.querySelector('input.exposure');
    if (ev) ev.addEventListener('input', function () { render(block, parseFloat(ev.value)); });
    var slider = block.querySelector('input.swipe');
    if (slider) {
      slider.addEventListener('input', function () { setSwipe(block, slider.value / 1000); });
      var box = block.querySelector('.swipebox');
      var drag = function (e) {
        if (e.type === 'pointermove' && !e.buttons) return;
        var r = box.getBoundingClientRect();
        setSwipe(block, (e.clientX - r.left) / r.width);
      };
      box.addEventListener('pointerdown', drag);
      box.addEventListener('pointermove', drag);
      slider.value = Math.round(swipe0 * 1000);
      slider.dispatchEvent(new Event('input'));
    }
  });
  document.body.dataset.ready = '1';
})();
)JS";

// A pixel-art scale that shows a golden at about 256 CSS pixels.
uint32_t displayScale(uint32_t w, uint32_t h) { return std::max(1u, 256u / std::max({w, h, 1u})); }

struct Html {
    std::ostringstream body, data;
    int next = 0;

    // Embeds an image, returns its element id.
    std::string embed(const Image& img, bool heat) {
        const std::string id = "img" + std::to_string(next++);
        data << "<script type=\"application/octet-stream\" id=\"" << id << "\" data-w=\""
             << img.width << "\" data-h=\"" << img.height << "\" data-kind=\""
             << (heat ? "u8" : "f16") << "\">" << (heat ? rgb8(img) : halfRgb(img))
             << "</script>\n";
        return id;
    }
};

// Linear images open at 0 EV; integer data (ids, counts) opens with its largest value at 1.
double initialExposure(const CaptureOutcome& c) {
    const bool integer = c.format == "r8ui" || c.format == "r32ui" || c.format == "rgba32ui";
    if (!integer) return 0.0;
    float top = 0.0f;
    for (const Image* img : {&c.actual, &c.expected})
        for (float v : img->pixels)
            if (std::isfinite(v)) top = std::max(top, v);
    return top > 1.0f ? -std::ceil(std::log2(double(top)) * 10.0) / 10.0 : 0.0;
}

void writeCapture(Html& html, const TestOutcome& t, const CaptureOutcome& c) {
    auto& b = html.body;
    const bool first = c.resource == t.firstDivergent;
    b << "<div class=\"capture\" data-capture=\"" << htmlEscape(c.resource) << "\" data-mode=\""
      << (c.display ? "display" : "linear") << "\" data-exposure=\""
      << formatNumber(initialExposure(c)) << "\">\n";
    b << "<h3>" << htmlEscape(c.resource) << " <small>" << htmlEscape(c.format)
      << " &middot; golden " << storageName(c.storage);
    if (!c.writerPass.empty()) b << " &middot; written by " << htmlEscape(c.writerPass);
    b << "</small>"
      << (first ? " <span class=\"bad\">&larr; first divergent resource in pipeline order</span>"
                : "")
      << "</h3>\n";
    if (!c.note.empty()) b << "<p class=\"meta\">" << htmlEscape(c.note) << "</p>\n";
    b << "<table "
         "class=\"metrics\"><tr><th>metric</th><th>value</th><th>tolerance</th><th>result</"
         "th><th>detail</th></tr>\n";
    for (const auto& cmp : c.comparisons) {
        const bool higher = cmp.spec.metric == Metric::Psnr;
        b << "<tr><td>" << metricName(cmp.spec.metric);
        if (cmp.spec.metric == Metric::OverThreshold)
            b << "(" << formatNumber(cmp.spec.threshold) << ")";
        b << "</td>";
        if (!cmp.error.empty()) {
            b << "<td>&ndash;</td><td>" << (higher ? "&ge; " : "&le; ")
              << formatNumber(cmp.spec.tolerance) << "</td><td class=\"bad\">error</td><td>"
              << htmlEscape(cmp.error) << "</td></tr>\n";
            continue;
        }
        b << "<td>" << formatNumber(cmp.result.value) << "</td><td>" << (higher ? "&ge; " : "&le; ")
          << formatNumber(cmp.spec.tolerance) << "</td><td class=\""
          << (cmp.result.passed ? "ok\">pass" : "bad\">FAIL") << "</td><td>"
          << htmlEscape(cmp.result.detail) << "</td></tr>\n";
    }
    b << "</table>\n";

    const uint32_t scale = displayScale(c.actual.width, c.actual.height);
    const bool haveExpected = c.expected.width > 0 && c.expected.width == c.actual.width &&
                              c.expected.height == c.actual.height;
    const std::string actualId = html.embed(c.actual, false);
    b << "<div class=\"views\">\n";
    std::string expectedId;
    if (haveExpected) {
        expectedId = html.embed(c.expected, false);
        b << "<figure><figcaption>expected (golden)</figcaption><canvas class=\"expected\" "
             "data-img=\""
          << expectedId << "\" data-scale=\"" << scale << "\"></canvas></figure>\n";
    }
    b << "<figure><figcaption>actual</figcaption><canvas class=\"actual\" data-img=\"" << actualId
      << "\" data-scale=\"" << scale << "\"></canvas></figure>\n";
    if (haveExpected) {
        b << "<figure><figcaption>swipe: expected | actual</figcaption><div class=\"swipebox\" "
             "style=\"width:"
          << c.actual.width * scale << "px;height:" << c.actual.height * scale << "px\">"
          << "<canvas class=\"under\" data-img=\"" << expectedId << "\" data-scale=\"" << scale
          << "\"></canvas>"
          << "<canvas class=\"over\" data-img=\"" << actualId << "\" data-scale=\"" << scale
          << "\"></canvas>"
          << "<div class=\"divider\"></div></div>"
          << "<input type=\"range\" class=\"swipe\" min=\"0\" max=\"1000\" value=\"500\" "
             "style=\"width:"
          << c.actual.width * scale
          << "px\" aria-label=\"swipe between expected and actual\"></figure>\n";
        for (const auto& cmp : c.comparisons) {
            if (!cmp.error.empty() || cmp.result.error.width == 0) continue;
            const std::string heatId =
                html.embed(heatMap(cmp.result.error, cmp.result.heatScale), true);
            b << "<figure><figcaption>diff: " << metricName(cmp.spec.metric)
              << " (black 0 &hellip; yellow " << formatNumber(cmp.result.heatScale)
              << ")</figcaption><canvas class=\"diff\" data-raw=\"1\" data-img=\"" << heatId
              << "\" data-scale=\"" << scale << "\"></canvas></figure>\n";
        }
    } else {
        b << "<p class=\"bad\">no golden image to compare with</p>\n";
    }
    b << "</div>\n";
    if (!c.display)
        b << "<div class=\"controls\"><label>exposure <input type=\"range\" class=\"exposure\" "
             "min=\"-10\" max=\"10\" "
             "step=\"0.1\" value=\"0\"> <output class=\"ev\">+0.0 EV</output></label></div>\n";
    b << "</div>\n";
}

}  // namespace

const char* storageName(Storage s) {
    switch (s) {
        case Storage::Png:
            return "png";
        case Storage::ExrHalf:
            return "exr-half";
        case Storage::ExrFloat:
            return "exr-float";
    }
    return "?";
}

const char* storageExtension(Storage s) { return s == Storage::Png ? ".png" : ".exr"; }

const char* testStatusName(TestStatus s) {
    switch (s) {
        case TestStatus::Passed:
            return "PASS";
        case TestStatus::Failed:
            return "FAIL";
        case TestStatus::Error:
            return "ERROR";
    }
    return "?";
}

size_t RunReport::count(TestStatus s) const {
    return static_cast<size_t>(std::count_if(tests.begin(), tests.end(),
                                             [&](const TestOutcome& t) { return t.status == s; }));
}

std::string base64Encode(const uint8_t* data, size_t size) {
    static const char* kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((size + 2) / 3 * 4);
    for (size_t i = 0; i < size; i += 3) {
        const uint32_t n = (uint32_t(data[i]) << 16) |
                           (i + 1 < size ? uint32_t(data[i + 1]) << 8 : 0u) |
                           (i + 2 < size ? uint32_t(data[i + 2]) : 0u);
        out += kAlphabet[(n >> 18) & 63];
        out += kAlphabet[(n >> 12) & 63];
        out += i + 1 < size ? kAlphabet[(n >> 6) & 63] : '=';
        out += i + 2 < size ? kAlphabet[n & 63] : '=';
    }
    return out;
}

std::string htmlEscape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

Result<void> writeHtmlReport(const std::string& dir, const RunReport& run) {
    Html html;
    auto& b = html.body;
    const size_t passed = run.count(TestStatus::Passed), failed = run.count(TestStatus::Failed),
                 errors = run.count(TestStatus::Error);
    b << "<header><h1>rgraph golden tests: " << passed << " passed, " << failed << " failed";
    if (errors) b << ", " << errors << " errors";
    b << "</h1>\n<p class=\"meta\">" << run.tests.size() << " tests in " << seconds(run.seconds)
      << " s &middot; " << htmlEscape(run.environment.device) << " &middot; "
      << htmlEscape(run.environment.driver) << " &middot; CPU " << htmlEscape(run.environment.cpu)
      << " (" << htmlEscape(run.environment.cpuFeatures) << ")<br>"
      << "determinism profile: " << htmlEscape(run.profile) << "</p></header>\n";
    b << "<table "
         "class=\"summary\"><tr><th>result</th><th>test</th><th>pipeline</th><th>captures</"
         "th><th>time</th><th>what failed</th></tr>\n";
    for (const auto& t : run.tests) {
        const char* s = testStatusName(t.status);
        b << "<tr class=\"" << s << "\" data-test=\"" << htmlEscape(t.name)
          << "\"><td><span class=\"badge " << s << "\">" << s << "</span></td><td><a href=\"#test-"
          << htmlEscape(t.name) << "\">" << htmlEscape(t.name) << "</a></td><td>"
          << htmlEscape(t.pipeline) << "</td><td>";
        for (size_t i = 0; i < t.captures.size(); ++i) {
            const auto& c = t.captures[i];
            b << (i ? ", " : "") << "<span class=\"" << (c.passed ? "ok" : "bad") << "\">"
              << htmlEscape(c.resource);
            for (const auto& cmp : c.comparisons)
                if (cmp.error.empty())
                    b << " " << metricName(cmp.spec.metric) << " "
                      << formatNumber(cmp.result.value);
            b << "</span>";
        }
        b << "</td><td>" << seconds(t.seconds) << " s</td><td>" << htmlEscape(t.message)
          << "</td></tr>\n";
    }
    b << "</table>\n";

    for (const auto& t : run.tests) {
        const char* s = testStatusName(t.status);
        b << "<section class=\"test " << s << "\" id=\"test-" << htmlEscape(t.name)
          << "\" data-test=\"" << htmlEscape(t.name) << "\">\n<h2><span class=\"badge " << s
          << "\">" << s << "</span> " << htmlEscape(t.name) << "</h2>\n";
        b << "<p class=\"meta\">" << htmlEscape(t.file) << " &middot; pipeline "
          << htmlEscape(t.pipeline) << " &middot; " << t.width << "&times;" << t.height
          << " &middot; " << t.frames << " frame" << (t.frames == 1 ? "" : "s") << " &middot; "
          << seconds(t.seconds) << " s";
        if (t.golden != t.name) b << " &middot; goldens of '" << htmlEscape(t.golden) << "'";
        b << "</p>\n";
        if (!t.doc.empty()) b << "<p>" << htmlEscape(t.doc) << "</p>\n";
        if (!t.message.empty()) b << "<p class=\"message\">" << htmlEscape(t.message) << "</p>\n";
        for (const auto& line : t.changes)
            b << "<p class=\"meta\">" << htmlEscape(line) << "</p>\n";
        for (const auto& c : t.captures) writeCapture(html, t, c);
        b << "</section>\n";
    }

    std::string page =
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>rgraph golden "
        "tests</title>\n<style>";
    page += kStyle;
    page += "</style></head>\n<body>\n";
    page += b.str();
    page += html.data.str();
    page += "<script>";
    page += kScript;
    page += "</script>\n</body></html>\n";
    return writeTextFile((fs::path(dir) / "index.html").string(), page);
}

Result<void> writeJunit(const std::string& file, const RunReport& run) {
    const size_t failures = run.count(TestStatus::Failed), errors = run.count(TestStatus::Error);
    std::ostringstream x;
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    x << "<testsuites name=\"rgraph golden\" tests=\"" << run.tests.size() << "\" failures=\""
      << failures << "\" errors=\"" << errors << "\" time=\"" << seconds(run.seconds) << "\">\n";
    x << "  <testsuite name=\"golden\" tests=\"" << run.tests.size() << "\" failures=\"" << failures
      << "\" errors=\"" << errors << "\" skipped=\"0\" time=\"" << seconds(run.seconds) << "\">\n";
    x << "    <properties>\n      <property name=\"device_family\" value=\""
      << xmlEscape(run.environment.family) << "\"/>\n      <property name=\"device\" value=\""
      << xmlEscape(run.environment.device) << "\"/>\n      <property name=\"driver\" value=\""
      << xmlEscape(run.environment.driver) << "\"/>\n    </properties>\n";
    for (const auto& t : run.tests) {
        x << "    <testcase classname=\"golden\" name=\"" << xmlEscape(t.name) << "\" file=\""
          << xmlEscape(t.file) << "\" time=\"" << seconds(t.seconds) << "\">\n";
        std::string details;
        for (const auto& c : t.captures)
            for (const auto& cmp : c.comparisons)
                details +=
                    c.resource + ": " +
                    (cmp.error.empty() ? cmp.result.verdict() + (cmp.result.passed ? "" : " FAIL")
                                       : cmp.error) +
                    "\n";
        if (t.status == TestStatus::Failed)
            x << "      <failure message=\"" << xmlEscape(t.message) << "\">" << xmlEscape(details)
              << "</failure>\n";
        else if (t.status == TestStatus::Error)
            x << "      <error message=\"" << xmlEscape(t.message) << "\"></error>\n";
        if (!details.empty()) x << "      <system-out>" << xmlEscape(details) << "</system-out>\n";
        x << "    </testcase>\n";
    }
    x << "  </testsuite>\n</testsuites>\n";
    return writeTextFile(file, x.str());
}

}  // namespace rg::golden
