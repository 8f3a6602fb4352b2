#include "core/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace glimmer {

ImageFormat imageFormatForPath(const std::filesystem::path& path, const char* flag) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (ext == ".png") return ImageFormat::Png;
    if (ext == ".exr") return ImageFormat::Exr;
    throw UsageError(std::string(flag) + ": " + path.string() + ": unsupported image type (use .png or .exr)");
}

// Encodes in memory (OpenImageIO's IOVecOutput) so the file itself is written by AtomicFile, whose every write
// is checked: OpenImageIO's PNG writer does not report a full disk.
static void writeRaw(const std::filesystem::path& path, const void* data, OIIO::TypeDesc type, int width, int height,
                     int channels, bool bottomUp) {
    const char* format = imageFormatForPath(path, "image") == ImageFormat::Exr ? "openexr" : "png";
    checkOutputPath(path, "");
    auto out = OIIO::ImageOutput::create(format);
    if (!out || !out->supports("ioproxy")) throw Error(path.string() + ": cannot write (" + OIIO::geterror() + ")");
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    OIIO::ImageSpec spec(width, height, channels, type);
    if (type == OIIO::TypeDesc::FLOAT) spec.attribute("compression", "zip");
    if (!out->set_ioproxy(&proxy) || !out->open(path.string(), spec))
        throw Error(path.string() + ": cannot write (" + out->geterror() + ")");
    size_t pixelBytes = size_t(channels) * type.size();
    OIIO::stride_t yStride = OIIO::stride_t(pixelBytes * width);
    const char* start = static_cast<const char*>(data);
    if (bottomUp) {
        // Last row first with a negative stride flips GL's bottom-up rows.
        start += size_t(height - 1) * pixelBytes * width;
        yStride = -yStride;
    }
    if (!out->write_image(type, start, OIIO::AutoStride, yStride) || !out->close() || bytes.empty())
        throw Error(path.string() + ": write failed (" + out->geterror() + ")");
    writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), "");
}

void writePng(const std::filesystem::path& path, const uint8_t* rgba, int width, int height) {
    writeRaw(path, rgba, OIIO::TypeDesc::UINT8, width, height, 4, true);
}

void writeExr(const std::filesystem::path& path, const float* rgba, int width, int height, int channels) {
    writeRaw(path, rgba, OIIO::TypeDesc::FLOAT, width, height, channels, true);
}

void writeImage(const std::filesystem::path& path, const ImageF& image) {
    if (imageFormatForPath(path, "image") == ImageFormat::Exr) {
        writeRaw(path, image.pixels.data(), OIIO::TypeDesc::FLOAT, image.width, image.height, image.channels, false);
        return;
    }
    std::vector<uint8_t> bytes(image.pixels.size());
    for (size_t i = 0; i < bytes.size(); ++i)
        bytes[i] = uint8_t(std::clamp(image.pixels[i], 0.0f, 1.0f) * 255.0f + 0.5f);
    writeRaw(path, bytes.data(), OIIO::TypeDesc::UINT8, image.width, image.height, image.channels, false);
}

std::string sniffImageFormat(const unsigned char* b, size_t n) {
    if (n >= 8 && std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0) return "png";
    if (n >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return "jpeg";
    if (n >= 4 && b[0] == 0x76 && b[1] == 0x2F && b[2] == 0x31 && b[3] == 0x01) return "openexr";
    if (n >= 2 && b[0] == '#' && b[1] == '?') return "hdr";  // "#?RADIANCE" or "#?RGBE"
    return "";
}

static bool formatAllowed(const std::string& format, ImageUse use) {
    switch (use) {
        case ImageUse::Texture: return format == "png" || format == "jpeg";
        case ImageUse::Environment: return format == "hdr" || format == "openexr" || format == "png";
        case ImageUse::Any: return !format.empty();
    }
    return false;
}

static const char* allowedList(ImageUse use) {
    switch (use) {
        case ImageUse::Texture: return "PNG or JPEG";
        case ImageUse::Environment: return "Radiance .hdr, OpenEXR or PNG";
        case ImageUse::Any: break;
    }
    return "PNG, JPEG, Radiance .hdr or OpenEXR";
}

static bool extensionMatches(std::string ext, const std::string& format) {
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (format == "png") return ext == ".png";
    if (format == "jpeg") return ext == ".jpg" || ext == ".jpeg";
    if (format == "hdr") return ext == ".hdr" || ext == ".pic";
    if (format == "openexr") return ext == ".exr";
    return false;
}

void checkImageSize(const std::string& what, int width, int height, int channels, int bytesPerChannel,
                    uint64_t fileBytes, ImageUse use) {
    int maxSide = use == ImageUse::Texture ? kMaxTextureSide : kMaxEnvironmentSide;
    uint64_t maxPixels = use == ImageUse::Texture ? kMaxTexturePixels : kMaxEnvironmentPixels;
    std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (width <= 0 || height <= 0 || channels <= 0 || channels > 4)
        throw Error(what + ": header gives an impossible size " + size + " with " + std::to_string(channels) + " channels");
    uint64_t pixels = uint64_t(width) * uint64_t(height);
    if (width > maxSide || height > maxSide || pixels > maxPixels)
        throw Error(what + ": header size " + size + " exceeds the limit (" + std::to_string(maxSide) + " per side, " +
                    std::to_string(maxPixels) + " pixels)");
    uint64_t decoded = pixels * uint64_t(channels) * uint64_t(std::max(bytesPerChannel, 1));
    if (decoded > fileBytes * kMaxExpansionPerFileByte + kExpansionAllowance)
        throw Error(what + ": header size " + size + " cannot be held by a file of " + std::to_string(fileBytes) +
                    " bytes (truncated or forged header)");
}

static uint32_t bigEndian(const unsigned char* p, int bytes) {
    uint32_t v = 0;
    for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
    return v;
}

bool readImageHeader(const unsigned char* b, size_t n, int& width, int& height, int& channels) {
    std::string format = sniffImageFormat(b, n);
    if (format == "png") {
        // Signature, then the IHDR chunk: length, "IHDR", width, height, bit depth, colour type (PNG 11.2.2).
        if (n < 26 || std::memcmp(b + 12, "IHDR", 4) != 0) return false;
        width = int(std::min<uint32_t>(bigEndian(b + 16, 4), 0x7fffffff));
        height = int(std::min<uint32_t>(bigEndian(b + 20, 4), 0x7fffffff));
        static const int channelsOfType[7] = {1, 0, 3, 1, 2, 0, 4};
        channels = b[25] < 7 ? channelsOfType[b[25]] : 0;
        return true;
    }
    if (format == "jpeg") {
        // Walk the marker segments to the first start-of-frame (ITU T.81 B.2.2).
        size_t at = 2;
        while (at + 4 <= n) {
            if (b[at] != 0xFF) return false;
            unsigned marker = b[at + 1];
            if (marker == 0xFF) { ++at; continue; }
            if (marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) { at += 2; continue; }
            size_t length = bigEndian(b + at + 2, 2);
            bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
            if (frame) {
                if (at + 10 > n) return false;
                height = int(bigEndian(b + at + 5, 2));
                width = int(bigEndian(b + at + 7, 2));
                channels = b[at + 9];
                return true;
            }
            if (length < 2) return false;
            at += 2 + length;
        }
        return false;
    }
    return false;
}

// OpenEXR allocates what a header attribute's size field claims before noticing the file is shorter (fuzzing found
// it: tests/data/hostile/fuzz-exr-attribute-1.6gb.exr, docs/cli.md), and no OpenEXR or OpenImageIO call checks the
// header without reading it. So the attribute list (OpenEXR file layout: name, type, int32 size, value, until
// an empty name) is walked here first: every attribute must lie inside the file, the file must be a single-part
// flat image, and its dataWindow must pass checkImageSize.
static void checkExrHeader(const std::filesystem::path& path, uint64_t fileBytes, ImageUse use) {
    const std::string file = path.string();
    std::ifstream in(path, std::ios::binary);
    std::vector<char> head(size_t(std::min<uint64_t>(fileBytes, uint64_t(1) << 20)));
    in.read(head.data(), std::streamsize(head.size()));
    size_t n = size_t(in.gcount()), at = 8;
    if (n < 8) throw Error(file + ": truncated OpenEXR header");
    uint32_t flags = uint8_t(head[5]) | uint32_t(uint8_t(head[6])) << 8 | uint32_t(uint8_t(head[7])) << 16;
    if (head[4] != 2 || (flags & 0x18) != 0)  // bits 11, 12 of the version field: deep data, multi-part
        throw Error(file + ": only single-part, flat OpenEXR version 2 files are supported");
    auto text = [&](const char* what) {
        size_t end = at;
        while (end < n && head[end] != '\0' && end - at < 256) ++end;
        if (end >= n || head[end] != '\0') throw Error(file + ": OpenEXR header: unterminated " + what);
        std::string value(head.data() + at, end - at);
        at = end + 1;
        return value;
    };
    bool haveWindow = false;
    int32_t window[4] = {};
    for (;;) {
        std::string name = text("attribute name");
        if (name.empty()) break;
        std::string type = text("attribute type");
        if (at + 4 > n) throw Error(file + ": OpenEXR header: truncated attribute '" + name + "'");
        int32_t size;
        std::memcpy(&size, head.data() + at, 4);
        at += 4;
        if (size < 0 || uint64_t(at) + uint64_t(size) > n)
            throw Error(file + ": OpenEXR header: attribute '" + name + "' claims " + std::to_string(size) +
                        " bytes, more than the file holds");
        if (name == "dataWindow" && type == "box2i" && size == 16) {
            std::memcpy(window, head.data() + at, 16);
            haveWindow = true;
        }
        at += size_t(size);
    }
    if (!haveWindow) throw Error(file + ": OpenEXR header has no dataWindow");
    int64_t width = int64_t(window[2]) - window[0] + 1, height = int64_t(window[3]) - window[1] + 1;
    checkImageSize(file, int(std::clamp<int64_t>(width, -1, 1 << 30)), int(std::clamp<int64_t>(height, -1, 1 << 30)),
                   1, 2, fileBytes, use);
}

ImageF readImage(const std::filesystem::path& path, ImageUse use) {
    const std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(file + ": cannot read image (file not found)");
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(file + ": cannot read image (not a regular file)");
    uint64_t fileBytes = std::filesystem::file_size(path, ec);
    unsigned char magic[16] = {};
    size_t got = 0;
    {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw Error(file + ": cannot read image (cannot open)");
        in.read(reinterpret_cast<char*>(magic), sizeof magic);
        got = size_t(in.gcount());
    }
    std::string format = sniffImageFormat(magic, got);
    if (!formatAllowed(format, use))
        throw Error(file + ": not a " + allowedList(use) + " image" + (format.empty() ? "" : " (it is " + format + ")"));
    if (!extensionMatches(path.extension().string(), format))
        throw Error(file + ": content is " + format + " but the extension is '" + path.extension().string() + "'");
    if (format == "openexr") checkExrHeader(path, fileBytes, use);
    // The reader of that format only, never OpenImageIO's search through every plugin.
    auto in = OIIO::ImageInput::create(format);
    OIIO::ImageSpec spec;
    if (!in || !in->open(file, spec)) throw Error(file + ": cannot read image (" + (in ? in->geterror() : OIIO::geterror()) + ")");
    spec = in->spec();
    if (spec.depth > 1 || spec.deep) throw Error(file + ": volume and deep images are not supported");
    checkImageSize(file, spec.width, spec.height, std::min(spec.nchannels, 4), int(spec.format.size()), fileBytes, use);
    ImageF image;
    image.width = spec.width;
    image.height = spec.height;
    image.channels = std::min(spec.nchannels, 4);
    image.pixels.resize(size_t(image.width) * image.height * image.channels);
    if (!in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        throw Error(file + ": cannot decode image (" + in->geterror() + ")");
    in->close();
    return image;
}

}  // namespace glimmer
