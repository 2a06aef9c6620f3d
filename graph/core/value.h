// Value: a plain, Lua-shaped datum (nil, bool, number, string, list, table) used for pass
// parameters, so a pass kind reads its settings from the same shape a script wrote.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace rg {

class Value {
public:
    using List = std::vector<Value>;
    using Table = std::map<std::string, Value>;

    Value() = default;
    Value(bool b) : m_v(b) {}
    Value(double d) : m_v(d) {}
    Value(int i) : m_v(static_cast<double>(i)) {}
    Value(const char* s) : m_v(std::string(s)) {}
    Value(std::string s) : m_v(std::move(s)) {}
    Value(List l) : m_v(std::move(l)) {}
    Value(Table t) : m_v(std::move(t)) {}

    bool isNil() const { return std::holds_alternative<std::monostate>(m_v); }
    bool isBool() const { return std::holds_alternative<bool>(m_v); }
    bool isNumber() const { return std::holds_alternative<double>(m_v); }
    bool isString() const { return std::holds_alternative<std::string>(m_v); }
    bool isList() const { return std::holds_alternative<List>(m_v); }
    bool isTable() const { return std::holds_alternative<Table>(m_v); }

    bool asBool(bool def = false) const { return isBool() ? std::get<bool>(m_v) : def; }
    double asNumber(double def = 0.0) const { return isNumber() ? std::get<double>(m_v) : def; }
    const std::string& asString() const;
    const List& asList() const;
    const Table& asTable() const;
    List& list() { return std::get<List>(m_v); }
    Table& table() { return std::get<Table>(m_v); }

    // Table lookup; a nil Value when absent or when this is not a table.
    const Value& operator[](const std::string& key) const;
    bool has(const std::string& key) const { return !(*this)[key].isNil(); }
    std::string typeName() const;

    bool operator==(const Value& o) const { return m_v == o.m_v; }

private:
    std::variant<std::monostate, bool, double, std::string, List, Table> m_v;
};

}  // namespace rg
