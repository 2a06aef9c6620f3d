// Result<T>: failures that come from input (a file, a script, a graph, a device) are values.
// An Error carries a one-line message that names the thing (file:line, pass, resource, field)
// and, where useful, the list of reasons behind it (e.g. why each GPU was rejected).
#pragma once

#include <expected>
#include <string>
#include <utility>
#include <vector>

namespace rg {

enum class ErrorCode {
    InvalidInput,  // a user file or declaration is wrong (exit code 2)
    NotFound,      // a named file / resource / pass does not exist (exit code 2)
    Unsupported,   // valid input we refuse by name (exit code 2)
    Device,        // Vulkan or driver failure (exit code 1)
    CheckFailed,   // a comparison or test did not pass (exit code 1)
    Io,            // the OS refused a read or write (exit code 1)
};

struct Error {
    ErrorCode code = ErrorCode::InvalidInput;
    std::string message;
    std::vector<std::string> reasons;

    Error() = default;
    Error(ErrorCode c, std::string msg, std::vector<std::string> why = {})
        : code(c), message(std::move(msg)), reasons(std::move(why)) {}

    // Message followed by the reasons, one per indented line.
    std::string describe() const {
        std::string s = message;
        for (const auto& r : reasons) s += "\n  " + r;
        return s;
    }
};

template <class T>
using Result = std::expected<T, Error>;

inline std::unexpected<Error> fail(ErrorCode code, std::string message,
                                   std::vector<std::string> reasons = {}) {
    return std::unexpected<Error>(Error(code, std::move(message), std::move(reasons)));
}

}  // namespace rg
