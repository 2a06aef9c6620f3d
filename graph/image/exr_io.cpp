// OpenEXR reading and writing. OpenEXR reports every failure by throwing; each entry point here
// catches everything and turns it into a Result, so no exception leaves the module.
#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfDoubleAttribute.h>
#include <ImfFloatAttribute.h>
#include <ImfIntAttribute.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>
#include <ImfVersion.h>
#include <half.h>

#include <algorithm>
#include <map>
#include <array>
#include <cerrno>
#include <climits>
#include <cstring>
#include <exception>
#include <mutex>
#include <new>
#include <set>
#include <thread>

#include "image/file_io.h"
#include "image/image.h"

namespace rg {

using image_detail::quoted;

namespace {

// Reads a file already held in memory, so that the file is opened (and its OS errors reported)
// in one place, and a truncated file ends in one recognisable exception.
// Deliberately not "memory-mapped" (isMemoryMapped() stays false): OpenEXR 3.1 then reads
// uncompressed chunks in place and a chunk whose size field is too small makes it read past the
// end of the buffer (found by fuzzing); copying gives every chunk a buffer of full size.
class MemoryIStream final : public Imf::IStream {
public:
    MemoryIStream(const std::string& path, const std::vector<char>& data)
        : Imf::IStream(path.c_str()), m_data(data) {}

    bool read(char c[], int n) override {
        std::memcpy(c, take(n), size_t(n));
        return m_pos < m_data.size();
    }
    uint64_t tellg() override { return m_pos; }
    // Seeking past the end is allowed; the next read reports it.
    void seekg(uint64_t pos) override { m_pos = pos; }

private:
    const char* take(int n) {
        if (n < 0 || m_pos > m_data.size() || uint64_t(n) > m_data.size() - m_pos)
            throw Iex::InputExc("unexpected end of file (truncated?)");
        const char* p = m_data.data() + m_pos;
        m_pos += uint64_t(n);
        return p;
    }

    const std::vector<char>& m_data;
    uint64_t m_pos = 0;
};

// Writes through a FILE* and remembers the errno of a failure: OutputFile's destructor writes the
// chunk offset table and swallows exceptions, so a failure there is only visible through this.
class FileOStream final : public Imf::OStream {
public:
    FileOStream(const std::string& path, std::FILE* file)
        : Imf::OStream(path.c_str()), m_file(file) {}

    void write(const char c[], int n) override {
        if (n < 0 || std::fwrite(c, 1, size_t(n), m_file) != size_t(n)) failed();
    }
    uint64_t tellp() override {
        const off_t pos = ftello(m_file);
        if (pos < 0) failed();
        return uint64_t(pos);
    }
    void seekp(uint64_t pos) override {
        if (pos > uint64_t(LLONG_MAX) || fseeko(m_file, off_t(pos), SEEK_SET) != 0) failed();
    }

    int error() const { return m_errno; }

private:
    [[noreturn]] void failed() {
        m_errno = errno != 0 ? errno : EIO;
        throw Iex::IoExc("write failed");
    }

    std::FILE* m_file;
    int m_errno = 0;
};

std::string layerLabel(const std::string& name) { return "layer '" + name + "'"; }

std::string fullChannelName(const std::string& layer, const std::string& channel) {
    return layer.empty() ? channel : layer + "." + channel;
}

// Attribute names a single-part scanline file owns (OpenEXR spec, "Header Attributes"); a string
// attribute with one of these names would clash with, or be misread as, the real one.
bool isReservedAttribute(const std::string& key) {
    static const std::set<std::string> reserved = {"channels",
                                                   "compression",
                                                   "dataWindow",
                                                   "displayWindow",
                                                   "lineOrder",
                                                   "pixelAspectRatio",
                                                   "screenWindowCenter",
                                                   "screenWindowWidth",
                                                   "tiles",
                                                   "type",
                                                   "name",
                                                   "version",
                                                   "chunkCount",
                                                   "view",
                                                   "multiView"};
    return reserved.contains(key);
}

Result<void> validateLayers(const std::string& path, const std::vector<ImageLayer>& layers,
                            const ExrWriteOptions& opts) {
    const std::string file = quoted(path);
    if (layers.empty()) return fail(ErrorCode::InvalidInput, file + ": no layers to write");
    const Image& first = layers.front().image;
    std::set<std::string> fullNames;
    for (const ImageLayer& layer : layers) {
        const Image& img = layer.image;
        const std::string label = layerLabel(layer.name);
        if (img.width == 0 || img.height == 0 || img.channels == 0)
            return fail(ErrorCode::InvalidInput, file + ": " + label + " is empty (" +
                                                     std::to_string(img.width) + "x" +
                                                     std::to_string(img.height) + ", " +
                                                     std::to_string(img.channels) + " channels)");
        if (img.width > uint32_t(INT_MAX) || img.height > uint32_t(INT_MAX))
            return fail(ErrorCode::Unsupported, file + ": " + label + " is too large for OpenEXR");
        if (img.pixels.size() != size_t(img.width) * img.height * img.channels)
            return fail(ErrorCode::InvalidInput,
                        file + ": " + label + " has " + std::to_string(img.pixels.size()) +
                            " samples, expected " + std::to_string(img.width) + "x" +
                            std::to_string(img.height) + "x" + std::to_string(img.channels));
        if (img.width != first.width || img.height != first.height)
            return fail(ErrorCode::InvalidInput,
                        file + ": " + label + " is " + std::to_string(img.width) + "x" +
                            std::to_string(img.height) + " but " + layerLabel(layers.front().name) +
                            " is " + std::to_string(first.width) + "x" +
                            std::to_string(first.height) +
                            "; all layers of an EXR file must have the same size");
        if (layer.channelNames.size() != img.channels)
            return fail(ErrorCode::InvalidInput, file + ": " + label + " names " +
                                                     std::to_string(layer.channelNames.size()) +
                                                     " channels but its image has " +
                                                     std::to_string(img.channels));
        if (!layer.name.empty() && (layer.name.front() == '.' || layer.name.back() == '.'))
            return fail(ErrorCode::InvalidInput,
                        file + ": " + label + ": a layer name cannot start or end with '.'");
        for (const std::string& ch : layer.channelNames) {
            // A '.' in a channel name would move it into another layer when read back.
            if (ch.empty() || ch.find('.') != std::string::npos)
                return fail(ErrorCode::InvalidInput,
                            file + ": " + label + ": invalid channel name '" + ch +
                                "' (must be non-empty and contain no '.')");
            const std::string full = fullChannelName(layer.name, ch);
            if (!fullNames.insert(full).second)
                return fail(ErrorCode::InvalidInput,
                            file + ": channel '" + full + "' appears twice");
        }
    }
    std::set<std::string> keys;
    auto checkKey = [&](const std::string& key) -> Result<void> {
        if (key.empty()) return fail(ErrorCode::InvalidInput, file + ": empty metadata key");
        if (isReservedAttribute(key))
            return fail(ErrorCode::InvalidInput,
                        file + ": metadata key '" + key + "' is a standard OpenEXR attribute");
        if (!keys.insert(key).second)
            return fail(ErrorCode::InvalidInput,
                        file + ": metadata key '" + key + "' is given twice");
        return {};
    };
    for (const auto& [key, value] : opts.metadata)
        if (auto r = checkKey(key); !r) return r;
    for (const auto& [key, value] : opts.floats)
        if (auto r = checkKey(key); !r) return r;
    for (const auto& [key, value] : opts.ints)
        if (auto r = checkKey(key); !r) return r;
    return {};
}

// Channels of one layer in the order readExr promises: R, G, B, A, then alphabetical.
void sortChannels(std::vector<std::string>& names) {
    auto rank = [](const std::string& n) {
        static const std::array<const char*, 4> rgba = {"R", "G", "B", "A"};
        for (size_t i = 0; i < rgba.size(); ++i)
            if (n == rgba[i]) return int(i);
        return int(rgba.size());
    };
    std::sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) {
        const int ra = rank(a), rb = rank(b);
        return ra != rb ? ra < rb : a < b;
    });
}

// OpenEXR's messages repeat the file name ('Cannot read image file "x.exr". Invalid data window
// in image header.'); ours already start with it, so keep only what OpenEXR adds.
std::string exrReason(const std::string& path, const std::string& what) {
    const std::string named = "\"" + path + "\". ";
    const size_t at = what.find(named);
    if (at == std::string::npos) return what;
    std::string action = what.substr(0, at);
    const std::string reason = what.substr(at + named.size());
    for (const char* tail : {" from image file ", " image file "}) {
        if (action.ends_with(tail)) {
            action.resize(action.size() - std::strlen(tail));
            break;
        }
    }
    if (action == "Cannot read" || action == "Cannot open") return reason;
    return action + ": " + reason;
}

// The header's attribute sizes against the file (OpenEXR layout: magic, version, then per part
// attributes "name\0type\0" + int32 size + value, ended by an empty name; a multi-part file ends
// its list of headers with one more empty name). OpenEXR allocates an attribute's claimed size
// before it reads it, so a 300-byte file claiming a 2 GB string attribute costs 2 GB before it
// fails (tools/fuzz.sh image found such files); this refuses them first.
// At most 2^28 samples (1 GiB of floats: an 8192 x 8192 RGBA environment), and no more than the
// file could hold at 65536 samples per byte — beyond any OpenEXR codec's ratio on real images
// (DEFLATE's is ~1000:1) — so a 300-byte file cannot claim gigabytes (tools/fuzz.sh image found
// such headers).
constexpr int64_t kMaxExrSamples = int64_t(1) << 28;
constexpr int64_t kMaxExrSamplesPerByte = 65536;

// The size in bytes of an OpenEXR attribute type's value when it is fixed (OpenEXR 3.1's
// predefined types), or -1.
int32_t exrFixedAttributeSize(const std::string& type) {
    static const std::map<std::string, int32_t> sizes = {
        {"box2i", 16},   {"box2f", 16},         {"v2i", 8},         {"v2f", 8},
        {"v2d", 16},     {"v3i", 12},           {"v3f", 12},        {"v3d", 24},
        {"m33f", 36},    {"m33d", 72},          {"m44f", 64},       {"m44d", 128},
        {"int", 4},      {"float", 4},          {"double", 8},      {"rational", 8},
        {"timecode", 8}, {"keycode", 28},       {"compression", 1}, {"lineOrder", 1},
        {"envmap", 1},   {"deepImageState", 1}, {"tiledesc", 9},    {"chromaticities", 32}};
    auto it = sizes.find(type);
    return it == sizes.end() ? -1 : it->second;
}

Result<void> checkExrHeaderSizes(const std::string& file, const std::vector<char>& data) {
    size_t pos = 8;
    const auto bad = [&](const std::string& what) {
        return fail(ErrorCode::InvalidInput, file + ": invalid OpenEXR header: " + what);
    };
    // The version field is OpenEXR's to judge (it names the version it cannot read).
    if (data.size() < 8 || data[4] != 2) return {};
    std::string nameError;
    const auto readName = [&](std::string& out) -> bool {
        const size_t end =
            std::find(data.begin() + static_cast<std::ptrdiff_t>(std::min(pos, data.size())),
                      data.end(), '\0') -
            data.begin();
        if (end - std::min(pos, end) > 255) {
            nameError = "an attribute name is more than 255 characters long";
            return false;
        }
        if (end >= data.size()) {
            nameError = "truncated file: an attribute name runs past its end";
            return false;
        }
        out.assign(data.data() + pos, end - pos);
        pos = end + 1;
        return true;
    };
    const bool multipart =
        data.size() >= 8 && (static_cast<unsigned char>(data[5]) & 0x10) != 0;  // version bit 12
    // Each part's data window times its channels, against what a file of this size can hold:
    // OpenEXR sizes its decompression buffers from them when it opens the file.
    int64_t width = 0, height = 0, channels = 0;
    const auto checkSamples = [&]() -> Result<void> {
        const int64_t plausible =
            std::min(kMaxExrSamples, int64_t(data.size()) * kMaxExrSamplesPerByte);
        if (width > 0 && height > 0 && channels > 0 &&
            (width > plausible || height > plausible || width * height > plausible / channels))
            return fail(ErrorCode::InvalidInput,
                        file + ": the header claims " + std::to_string(width) + "x" +
                            std::to_string(height) + "x" + std::to_string(channels) +
                            " samples, more than a " + std::to_string(data.size()) +
                            "-byte file can hold or rgraph reads (truncated or corrupt?)");
        width = height = channels = 0;
        return {};
    };
    for (;;) {
        std::string name, type;
        if (!readName(name)) return bad(nameError);
        if (name.empty())
            return {};  // the end of the list of headers (or an empty one: OpenEXR says what is wrong)
        for (;;) {
            if (!readName(type)) return bad(nameError + " (the type of attribute '" + name + "')");
            if (pos + 4 > data.size())
                return bad("truncated file: attribute '" + name + "' has no size");
            int32_t size = 0;
            std::memcpy(&size, data.data() + pos, 4);
            pos += 4;
            if (size < 0 || static_cast<uint64_t>(size) > data.size() - pos)
                return bad((size < 0 ? "" : "truncated file: ") + std::string("attribute '") +
                           name + "' claims " + std::to_string(size) + " bytes, " +
                           std::to_string(data.size() - pos) + " are left in the file");
            // OpenEXR reads a fixed-size type's value whatever size the file states, so a wrong
            // size would put this walk out of step with it: refuse one.
            if (const int32_t fixed = exrFixedAttributeSize(type); fixed >= 0 && size != fixed)
                return bad("attribute '" + name + "' of type " + type + " is " +
                           std::to_string(fixed) + " bytes, the file says " + std::to_string(size));
            // A channel list is read entry by entry up to an empty name, whatever its size says:
            // the entries (name, then 16 bytes) must end exactly at its end. A string vector is
            // read as lengths and strings: they must tile it.
            if (type == "chlist" || type == "stringvector") {
                const size_t end = pos + static_cast<size_t>(size);
                size_t p = pos;
                bool closed = false;
                int64_t entries = 0;
                while (p < end && !closed) {
                    if (type == "chlist") {
                        const size_t nul =
                            std::find(data.begin() + static_cast<std::ptrdiff_t>(p),
                                      data.begin() + static_cast<std::ptrdiff_t>(end), '\0') -
                            data.begin();
                        if (nul >= end) break;
                        closed = nul == p;
                        entries += closed ? 0 : 1;
                        p = closed ? nul + 1 : nul + 1 + 16;
                    } else {
                        int32_t length = 0;
                        if (p + 4 > end) break;
                        std::memcpy(&length, data.data() + p, 4);
                        if (length < 0) break;
                        p += 4 + static_cast<size_t>(length);
                    }
                }
                if (p != end || (type == "chlist" && !closed))
                    return bad("attribute '" + name + "' (" + type + ") does not fill its " +
                               std::to_string(size) + " bytes exactly");
                if (type == "chlist" && name == "channels") channels = entries;
            }
            if (type == "box2i" && name == "dataWindow") {
                int32_t box[4];
                std::memcpy(box, data.data() + pos, 16);
                width = int64_t(box[2]) - box[0] + 1;
                height = int64_t(box[3]) - box[1] + 1;
            }
            // A preview image allocates its own width x height, which must be what follows.
            if (type == "preview") {
                uint32_t w = 0, h = 0;
                if (size < 8)
                    return bad("attribute '" + name +
                               "' (preview) is shorter than its size fields");
                std::memcpy(&w, data.data() + pos, 4);
                std::memcpy(&h, data.data() + pos + 4, 4);
                if (uint64_t(w) * h * 4 + 8 != uint64_t(size))
                    return bad("attribute '" + name + "' (preview) claims " + std::to_string(w) +
                               "x" + std::to_string(h) + " pixels in " + std::to_string(size) +
                               " bytes");
            }
            pos += static_cast<size_t>(size);
            if (!readName(name)) return bad(nameError);
            if (name.empty()) break;  // the end of this part's header
        }
        if (auto r = checkSamples(); !r) return r;
        if (!multipart) return {};
    }
}

}  // namespace

Result<void> writeExr(const std::string& path, const std::vector<ImageLayer>& layers,
                      const ExrWriteOptions& opts) {
    if (auto valid = validateLayers(path, layers, opts); !valid) return valid;
    const int width = int(layers.front().image.width);
    const int height = int(layers.front().image.height);
    const bool half = opts.pixelType == ExrPixelType::Half;
    const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;

    // OpenEXR compresses a file's line blocks on its own thread pool, which is empty unless asked
    // for: one thread a core (the default frame's EXR: ~120 -> ~80 ms on two cores).
    static std::once_flag threads;
    std::call_once(threads, [] {
        Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency())));
    });

    auto writer = image_detail::AtomicFileWriter::open(path);
    if (!writer) return std::unexpected(writer.error());

    std::vector<std::vector<::half>> halfPixels;  // converted copies, alive until writePixels
    FileOStream stream(path, writer->file());
    try {
        Imf::Header header(width, height);
        header.compression() = opts.compress ? Imf::ZIP_COMPRESSION : Imf::NO_COMPRESSION;
        header.zipCompressionLevel() =
            1;  // zlib's fastest: lossless all the same, and several times quicker than its default
        for (const auto& [key, value] : opts.metadata)
            header.insert(key, Imf::StringAttribute(value));
        for (const auto& [key, value] : opts.floats) header.insert(key, Imf::FloatAttribute(value));
        for (const auto& [key, value] : opts.ints) header.insert(key, Imf::IntAttribute(value));

        Imf::FrameBuffer frameBuffer;
        for (const ImageLayer& layer : layers) {
            const Image& img = layer.image;
            const void* base = img.pixels.data();
            size_t sampleSize = sizeof(float);
            if (half) {
                halfPixels.emplace_back(img.pixels.begin(), img.pixels.end());
                base = halfPixels.back().data();
                sampleSize = sizeof(::half);
            }
            const size_t xStride = sampleSize * img.channels;
            for (uint32_t c = 0; c < img.channels; ++c) {
                const std::string name = fullChannelName(layer.name, layer.channelNames[c]);
                header.channels().insert(name, Imf::Channel(type));
                const char* channelBase = static_cast<const char*>(base) + c * sampleSize;
                frameBuffer.insert(name, Imf::Slice::Make(type, channelBase, header.dataWindow(),
                                                          xStride, xStride * img.width));
            }
        }
        {
            Imf::OutputFile out(stream, header);
            out.setFrameBuffer(frameBuffer);
            out.writePixels(height);
        }
    } catch (const std::bad_alloc&) {
        return fail(ErrorCode::Io, "cannot write " + quoted(path) + ": out of memory");
    } catch (const std::exception& e) {
        if (stream.error() != 0) return std::unexpected(writer->writeError(stream.error()));
        return fail(ErrorCode::InvalidInput,
                    quoted(path) + ": OpenEXR: " + exrReason(path, e.what()));
    } catch (...) {
        return fail(ErrorCode::InvalidInput, quoted(path) + ": OpenEXR: unknown exception");
    }
    if (stream.error() != 0) return std::unexpected(writer->writeError(stream.error()));
    return writer->commit();
}

Result<ExrFile> readExr(const std::string& path) {
    auto data = image_detail::readWholeFile(path);
    if (!data) return std::unexpected(data.error());
    const std::string file = quoted(path);
    if (data->size() < 4 || !Imf::isImfMagic(data->data()))
        return fail(ErrorCode::InvalidInput, file + ": not an OpenEXR file");

    if (auto sizes = checkExrHeaderSizes(file, *data); !sizes)
        return std::unexpected(sizes.error());
    try {
        MemoryIStream stream(path, *data);
        Imf::InputFile input(stream);
        const Imf::Header& header = input.header();
        const Imath::Box2i dataWindow = header.dataWindow();
        const int64_t width = int64_t(dataWindow.max.x) - dataWindow.min.x + 1;
        const int64_t height = int64_t(dataWindow.max.y) - dataWindow.min.y + 1;
        if (width <= 0 || height <= 0)
            return fail(ErrorCode::InvalidInput, file + ": empty data window");

        // Group channel names by layer; the channel list is sorted, so layers come out sorted.
        std::map<std::string, std::vector<std::string>> layerChannels;
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
            const std::string full = it.name();
            const Imf::Channel& channel = it.channel();
            if (channel.xSampling != 1 || channel.ySampling != 1)
                return fail(ErrorCode::Unsupported,
                            file + ": channel '" + full + "' is subsampled (" +
                                std::to_string(channel.xSampling) + "x" +
                                std::to_string(channel.ySampling) + "), which is not supported");
            const size_t dot = full.rfind('.');
            if (dot == std::string::npos)
                layerChannels[""].push_back(full);
            else
                layerChannels[full.substr(0, dot)].push_back(full.substr(dot + 1));
        }
        if (layerChannels.empty()) return fail(ErrorCode::InvalidInput, file + ": no channels");

        // A garbage header can claim any size; refuse before allocating rather than die in it
        // (checkExrHeaderSizes did for the data window OpenEXR opened; this is what we allocate).
        constexpr int64_t maxSamples = kMaxExrSamples;
        const int64_t plausibleSamples = int64_t(data->size()) * kMaxExrSamplesPerByte;
        int64_t channelCount = 0;
        for (const auto& [name, channels] : layerChannels) channelCount += int64_t(channels.size());
        if (width > INT32_MAX || height > INT32_MAX || width * height > maxSamples / channelCount)
            return fail(ErrorCode::Unsupported, file + ": " + std::to_string(width) + "x" +
                                                    std::to_string(height) + "x" +
                                                    std::to_string(channelCount) +
                                                    " samples is too large to read (at most 2^28)");
        if (width * height > plausibleSamples / channelCount)
            return fail(ErrorCode::InvalidInput,
                        file + ": the header claims " + std::to_string(width) + "x" +
                            std::to_string(height) + "x" + std::to_string(channelCount) +
                            " samples, more than a " + std::to_string(data->size()) +
                            "-byte file can hold (truncated or corrupt?)");

        ExrFile result;
        result.layers.reserve(layerChannels.size());  // the slices point into these images
        Imf::FrameBuffer frameBuffer;
        for (auto& [name, channels] : layerChannels) {
            sortChannels(channels);
            ImageLayer& layer = result.layers.emplace_back();
            layer.name = name;
            layer.channelNames = channels;
            layer.image = Image(uint32_t(width), uint32_t(height), uint32_t(channels.size()));
            const size_t xStride = sizeof(float) * channels.size();
            for (size_t c = 0; c < channels.size(); ++c)
                frameBuffer.insert(fullChannelName(name, channels[c]),
                                   Imf::Slice::Make(Imf::FLOAT, &layer.image.pixels[c], dataWindow,
                                                    xStride, xStride * size_t(width)));
        }
        input.setFrameBuffer(frameBuffer);
        input.readPixels(dataWindow.min.y, dataWindow.max.y);

        for (auto it = header.begin(); it != header.end(); ++it)
            if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                result.metadata[it.name()] = s->value();
            else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&it.attribute()))
                result.floats[it.name()] = f->value();
            else if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&it.attribute()))
                result.floats[it.name()] = d->value();
            else if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&it.attribute()))
                result.ints[it.name()] = i->value();
        return result;
    } catch (const std::bad_alloc&) {
        return fail(ErrorCode::Io, "cannot read " + file + ": out of memory");
    } catch (const std::exception& e) {
        return fail(ErrorCode::InvalidInput,
                    file + ": invalid OpenEXR file: " + exrReason(path, e.what()));
    } catch (...) {
        return fail(ErrorCode::InvalidInput, file + ": invalid OpenEXR file: unknown exception");
    }
}

}  // namespace rg
