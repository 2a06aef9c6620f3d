// Internal to rg_image: whole-file reads and write-to-temp-then-rename, with errors that name the
// file and the OS reason. Not a public header.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "core/result.h"

namespace rg::image_detail {

// "'path'": how every message of this module names a file.
std::string quoted(const std::string& path);

// The OS's text for an errno value, e.g. "No such file or directory" (thread-safe).
std::string errnoText(int err);

// The whole file. Missing file: NotFound "cannot open 'x': No such file or directory"; any other
// OS failure: Io.
Result<std::vector<char>> readWholeFile(const std::string& path);

// A file written as "<path>.tmp-<pid>-<n>" and renamed to `path` by commit(), so that a failed
// write never replaces what was at `path`. Destroying it without commit() deletes the temp file.
class AtomicFileWriter {
public:
    static Result<AtomicFileWriter> open(const std::string& path);

    AtomicFileWriter(AtomicFileWriter&& other) noexcept;
    AtomicFileWriter& operator=(AtomicFileWriter&&) = delete;
    AtomicFileWriter(const AtomicFileWriter&) = delete;
    AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
    ~AtomicFileWriter();

    std::FILE* file() const { return m_file; }
    // Flushes, closes and renames; Io error naming `path` when any of it fails.
    Result<void> commit();
    // The Io error for a failed write with the given errno.
    Error writeError(int err) const;

private:
    AtomicFileWriter(std::string path, std::string tempPath, std::FILE* file)
        : m_path(std::move(path)), m_tempPath(std::move(tempPath)), m_file(file) {}

    std::string m_path;
    std::string m_tempPath;
    std::FILE* m_file = nullptr;
};

}  // namespace rg::image_detail
