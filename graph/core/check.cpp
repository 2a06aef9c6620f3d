#include "check.h"

#include <cstdio>
#include <cstdlib>

namespace rg::detail {

CheckFailure::CheckFailure(const char* cond, const char* file, int line) {
    m_stream << file << ":" << line << ": check failed: " << cond << ": ";
}

CheckFailure::~CheckFailure() {
    std::fprintf(stderr, "%s\n", m_stream.str().c_str());
    std::fflush(stderr);
    std::abort();
}

}  // namespace rg::detail
