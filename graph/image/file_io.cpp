#include "image/file_io.h"
#include "core/temp_path.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <system_error>
#include <utility>

namespace rg::image_detail {

std::string quoted(const std::string& path) { return "'" + path + "'"; }

std::string errnoText(int err) { return std::generic_category().message(err); }

Result<std::vector<char>> readWholeFile(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) {
        const int err = errno;
        return fail(err == ENOENT ? ErrorCode::NotFound : ErrorCode::Io,
                    "cannot open " + quoted(path) + ": " + errnoText(err));
    }
    std::vector<char> data;
    // Grows by reading, not by asking for the size, so pipes and /proc files work too.
    size_t used = 0;
    for (;;) {
        data.resize(std::max<size_t>(used * 2, 64 * 1024));
        const size_t got = std::fread(data.data() + used, 1, data.size() - used, f);
        used += got;
        if (used < data.size()) break;
    }
    const bool readFailed = std::ferror(f) != 0;
    const int err = errno;
    std::fclose(f);
    if (readFailed)
        return fail(ErrorCode::Io, "cannot read " + quoted(path) + ": " + errnoText(err));
    data.resize(used);
    data.shrink_to_fit();
    return data;
}

Result<AtomicFileWriter> AtomicFileWriter::open(const std::string& path) {
    // Two writers of the same path (threads, processes, machines) never share a temp file.
    std::string tempPath = tempPathBeside(path);
    std::FILE* f = std::fopen(tempPath.c_str(), "wb");
    if (!f) {
        const int err = errno;
        return fail(ErrorCode::Io, "cannot write " + quoted(path) + ": " + errnoText(err));
    }
    return AtomicFileWriter(path, std::move(tempPath), f);
}

AtomicFileWriter::AtomicFileWriter(AtomicFileWriter&& other) noexcept
    : m_path(std::move(other.m_path)),
      m_tempPath(std::move(other.m_tempPath)),
      m_file(std::exchange(other.m_file, nullptr)) {}

AtomicFileWriter::~AtomicFileWriter() {
    if (m_file) {
        std::fclose(m_file);
        std::remove(m_tempPath.c_str());
    }
}

Error AtomicFileWriter::writeError(int err) const {
    return Error(ErrorCode::Io, "cannot write " + quoted(m_path) + ": " + errnoText(err));
}

Result<void> AtomicFileWriter::commit() {
    std::FILE* f = std::exchange(m_file, nullptr);
    const bool flushFailed = std::fflush(f) != 0 || std::ferror(f) != 0;
    int err = errno;
    // fclose reports delayed write errors (NFS, quota), so its result counts too.
    const bool closeFailed = std::fclose(f) != 0;
    if (!flushFailed && closeFailed) err = errno;
    if (flushFailed || closeFailed) {
        std::remove(m_tempPath.c_str());
        return std::unexpected(writeError(err));
    }
    if (std::rename(m_tempPath.c_str(), m_path.c_str()) != 0) {
        err = errno;
        std::remove(m_tempPath.c_str());
        return std::unexpected(writeError(err));
    }
    return {};
}

}  // namespace rg::image_detail
