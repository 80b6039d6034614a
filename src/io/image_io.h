#pragma once
// Image files through OpenImageIO: written whole or not at all.
#include <filesystem>
#include <span>
#include <string>

#include "core/image.h"

namespace wideray {

/// Writes the image in the format its extension names (png, exr, jpg, tif, ...). 8-bit formats get
/// the sRGB transfer curve when `srgb` is set; float formats keep linear values. The image goes to a
/// temporary file in the same folder, renamed into place only once complete. Throws InputError.
void writeImage(const Image& image, const std::filesystem::path& path, bool srgb);

/// Whether the format `path`'s extension names stores floats (EXR, HDR, PFM) rather than 8-bit values.
bool isFloatFormat(const std::filesystem::path& path);

/// Reads an image as linear floats (sRGB decoded for 8-bit files when `srgb`). Throws InputError.
Image readImage(const std::filesystem::path& path, bool srgb);

/// Reads an image file held in memory (a PNG or JPEG inside a glTF file), its format named by
/// `name`'s extension; `name` is what messages call it. Throws InputError.
Image readImage(std::span<const unsigned char> bytes, const std::string& name, bool srgb);

} // namespace wideray
