// rg.param: a typed parameter (number, integer, boolean, vec3, choice) with bounds, choices and
// a default that satisfies them.
#include "declarations_detail.h"

#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

namespace rg::declarations {

Result<void> Builder::param(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(w, b, {"type", "default", "min", "max", "choices", "doc", "scene"});
        !r)
        return r;
    ParamDesc p;
    p.name = fullName(d);
    p.origin = d.origin;
    p.doc = b["doc"].asString();
    if (b.has("scene")) {
        if (!b["scene"].isString() || !isGlslIdentifier(b["scene"].asString()))
            return w.at("scene").error(
                "expected the name of a scene setting, e.g. scene = \"area_light_model\"");
        p.sceneSetting = b["scene"].asString();
    }
    auto type = requireString(w, b, "type");
    if (!type) return std::unexpected(type.error());
    static const std::vector<std::pair<std::string, ParamType>> types = {
        {"number", ParamType::Number},
        {"integer", ParamType::Integer},
        {"boolean", ParamType::Boolean},
        {"vec3", ParamType::Vec3},
        {"choice", ParamType::Choice}};
    auto it = std::find_if(types.begin(), types.end(), [&](auto& t) { return t.first == *type; });
    if (it == types.end()) {
        std::vector<std::string> names;
        for (auto& t : types) names.push_back(t.first);
        return w.at("type").error("unknown type '" + *type + "'" + suggestion(*type, names) +
                                  "; expected one of: " + joinQuoted(names));
    }
    p.type = it->second;
    for (const char* bound : {"min", "max"}) {
        if (!b.has(bound)) continue;
        if (p.type != ParamType::Number && p.type != ParamType::Integer)
            return w.at(bound).error(std::string("only number and integer parameters have a ") +
                                     bound);
        if (auto r = expectType(w.at(bound), b[bound], "number"); !r) return r;
    }
    p.min = b["min"].asNumber(p.min);
    p.max = b["max"].asNumber(p.max);
    if (p.min > p.max) {
        char b[96];
        std::snprintf(b, sizeof b, "min (%g) is above max (%g)", p.min, p.max);
        return w.at("min").error(b);
    }
    if (p.type == ParamType::Choice) {
        auto choices = stringList(w.at("choices"), b["choices"]);
        if (!choices) return std::unexpected(choices.error());
        if (choices->empty())
            return w.at("choices").error("missing (expected the list of allowed strings)");
        p.choices = *choices;
    } else if (b.has("choices"))
        return w.at("choices").error("only choice parameters have choices");
    if (!b.has("default")) return w.at("default").error("missing (expected the default value)");
    auto value = checkParamValue(p, b["default"]);
    if (!value) return w.at("default").error(value.error().message);
    p.value = *value;
    out.params.push_back(p);
    return {};
}

}  // namespace rg::declarations
