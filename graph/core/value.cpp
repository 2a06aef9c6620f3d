#include "value.h"

namespace rg {

namespace {
const Value kNil;
const std::string kEmptyString;
const Value::List kEmptyList;
const Value::Table kEmptyTable;
}  // namespace

const std::string& Value::asString() const {
    return isString() ? std::get<std::string>(m_v) : kEmptyString;
}
const Value::List& Value::asList() const { return isList() ? std::get<List>(m_v) : kEmptyList; }
const Value::Table& Value::asTable() const {
    return isTable() ? std::get<Table>(m_v) : kEmptyTable;
}

const Value& Value::operator[](const std::string& key) const {
    if (!isTable()) return kNil;
    const auto& t = std::get<Table>(m_v);
    auto it = t.find(key);
    return it == t.end() ? kNil : it->second;
}

std::string Value::typeName() const {
    switch (m_v.index()) {
        case 0:
            return "nil";
        case 1:
            return "boolean";
        case 2:
            return "number";
        case 3:
            return "string";
        case 4:
            return "list";
        default:
            return "table";
    }
}

}  // namespace rg
