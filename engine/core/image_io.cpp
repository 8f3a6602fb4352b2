#include "core/image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "core/error.h"

namespace glimmer {

ImageFormat imageFormatForPath(const std::filesystem::path& path, const char* flag) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (ext == ".png") return ImageFormat::Png;
    if (ext == ".exr") return ImageFormat::Exr;
    throw UsageError(std::string(flag) + ": " + path.string() + ": unsupported image type (use .png or .exr)");
}

static void writeRaw(const std::filesystem::path& path, const void* data, OIIO::TypeDesc type, int width, int height,
                     int channels, bool bottomUp) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw Error(path.string() + ": cannot write (" + OIIO::geterror() + ")");
    OIIO::ImageSpec spec(width, height, channels, type);
    if (type == OIIO::TypeDesc::FLOAT) spec.attribute("compression", "zip");
    if (!out->open(path.string(), spec)) throw Error(path.string() + ": cannot write (" + out->geterror() + ")");
    size_t pixelBytes = size_t(channels) * type.size();
    OIIO::stride_t yStride = OIIO::stride_t(pixelBytes * width);
    const char* start = static_cast<const char*>(data);
    if (bottomUp) {
        // Last row first with a negative stride flips GL's bottom-up rows.
        start += size_t(height - 1) * pixelBytes * width;
        yStride = -yStride;
    }
    if (!out->write_image(type, start, OIIO::AutoStride, yStride) || !out->close())
        throw Error(path.string() + ": write failed (" + out->geterror() + ")");
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

ImageF readImage(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw Error(path.string() + ": cannot read image (" + OIIO::geterror() + ")");
    const OIIO::ImageSpec& spec = in->spec();
    ImageF image;
    image.width = spec.width;
    image.height = spec.height;
    image.channels = spec.nchannels;
    image.pixels.resize(size_t(image.width) * image.height * image.channels);
    if (!in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        throw Error(path.string() + ": cannot decode image (" + in->geterror() + ")");
    in->close();
    return image;
}

}  // namespace glimmer
