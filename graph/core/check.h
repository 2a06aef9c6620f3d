// RG_CHECK(cond) << "message": contract violations (bugs, not bad input). Stays on in release
// builds; prints the condition, file:line and message, then aborts.
#pragma once

#include <sstream>

namespace rg::detail {

class CheckFailure {
public:
    CheckFailure(const char* cond, const char* file, int line);
    [[noreturn]] ~CheckFailure();
    template <class T>
    CheckFailure& operator<<(const T& v) {
        m_stream << v;
        return *this;
    }

private:
    std::ostringstream m_stream;
};

}  // namespace rg::detail

#define RG_CHECK(cond) \
    if (cond) {        \
    } else             \
        ::rg::detail::CheckFailure(#cond, __FILE__, __LINE__)
