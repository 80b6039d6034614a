#pragma once
// A float image and its output through OpenImageIO, written whole or not at all.
#include <filesystem>
#include <vector>

namespace wideray {

struct Image {
    int width = 0, height = 0, channels = 3;
    std::vector<float> pixels;  ///< row-major, channels interleaved, linear values

    Image() = default;
    Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(size_t(w) * h * c, 0.0f) {}
    float* at(int x, int y) { return &pixels[(size_t(y) * width + x) * channels]; }
    const float* at(int x, int y) const { return &pixels[(size_t(y) * width + x) * channels]; }
};

/// Writes the image in the format its extension names (png, exr, jpg, tif, ...). 8-bit formats get
/// the sRGB transfer curve when `srgb` is set; float formats keep linear values. The image goes to a
/// temporary file in the same folder, renamed into place only once complete. Throws InputError.
void writeImage(const Image& image, const std::filesystem::path& path, bool srgb);

/// Reads an image as linear floats (sRGB decoded for 8-bit files when `srgb`). Throws InputError.
Image readImage(const std::filesystem::path& path, bool srgb);

} // namespace wideray
