#include <cmath>
#include <system_error>
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/core.h>

#include "core/error.h"
#include "io/file_extension.h"
#include "io/image_io.h"

namespace wideray {
namespace {

float linearToSrgb(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgbToLinear(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

} // namespace

bool isFloatFormat(const std::filesystem::path& path) {
    const std::string ext = lowercaseExtension(path);
    return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

void writeImage(const Image& image, const std::filesystem::path& path, bool srgb) {
    const std::string file = path.string();
    const std::string ext = lowercaseExtension(path);
    std::filesystem::path dir = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    // A hidden name in the same folder, so that the rename cannot cross file systems; it keeps the
    // extension, which is how OpenImageIO picks the format.
    std::string tempName = path.stem().string();
    tempName.insert(0, 1, '.');
    tempName += ".tmp" + std::to_string(getpid()) + ext;
    std::filesystem::path temp = dir / tempName;

    auto out = OIIO::ImageOutput::create(temp.string());
    if (!out) throw InputError(file, "", "cannot write this image format: " + OIIO::geterror());
    bool floatOut = isFloatFormat(path);
    OIIO::ImageSpec spec(image.width, image.height, image.channels, floatOut ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    std::vector<float> data = image.pixels;
    if (!floatOut && srgb && image.channels >= 3)
        for (size_t i = 0; i < data.size(); ++i)
            if (image.channels == 3 || i % image.channels < 3) data[i] = linearToSrgb(data[i]);
    bool ok = out->open(temp.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, data.data()) && out->close();
    if (!ok) {
        std::string why = out->geterror();
        std::filesystem::remove(temp, ec);
        throw InputError(file, "", "cannot write image: " + why);
    }
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        std::filesystem::remove(temp, ec);
        throw InputError(file, "", "cannot move the finished image into place: " + ec.message());
    }
}

namespace {

/// Pixels and values (pixels times channels) beyond which an image is refused before its pixels are
/// allocated (3 GiB of floats): a header may claim any size.
constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;
constexpr uint64_t kMaxImageValues = 3 * kMaxImagePixels;

Image readOpened(OIIO::ImageInput* in, const std::string& name, bool srgb) {
    if (!in) throw InputError(name, "", "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    const uint64_t pixels = uint64_t(std::max(spec.width, 0)) * uint64_t(std::max(spec.height, 0));
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.nchannels > 4096 || pixels > kMaxImagePixels ||
        pixels * uint64_t(spec.nchannels) > kMaxImageValues)
        throw InputError(name, "", fmt::format("image of {}x{} with {} channels: wideray reads up to 2^28 pixels "
                                               "and 3 x 2^28 values (3 GiB of floats)",
                                               spec.width, spec.height, spec.nchannels));
    Image image(spec.width, spec.height, spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        throw InputError(name, "", "cannot read image: " + in->geterror());
    if (srgb && spec.format == OIIO::TypeDesc::UINT8)
        for (float& v : image.pixels) v = srgbToLinear(v);
    return image;
}

} // namespace

Image readImage(const std::filesystem::path& path, bool srgb) {
    auto in = OIIO::ImageInput::open(path.string());
    return readOpened(in.get(), path.string(), srgb);
}

Image readImage(std::span<const unsigned char> bytes, const std::string& name, bool srgb) {
    OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
    auto in = OIIO::ImageInput::open(name, nullptr, &memory);
    return readOpened(in.get(), name, srgb);
}

} // namespace wideray
