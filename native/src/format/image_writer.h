#pragma once
// Linear float images (environment maps) written with OpenImageIO (.exr, .hdr, ...), through the
// image module (format/image_library.h).
#include <string>
#include <vector>

namespace fenestra {

// Throws std::invalid_argument unless `path` names a format that keeps the values themselves
// (cd/m^2 for a sky): .exr or .hdr, floating point. PNG, JPEG, TIFF and the like would clip them to
// 8-bit levels (a 318 cd/m^2 sky becomes 255 everywhere).
void check_value_image_path(const std::string& path);

// The bytes of the image file, in the format `path`'s extension names. `pixels` holds height
// rows of width * channels floats, top row first. Throws std::invalid_argument naming the path
// (first check_value_image_path).
std::string encode_image(const std::string& path, int width, int height, int channels,
                         const std::vector<float>& pixels);
// Encodes, then writes all or nothing (format/atomic_file.h: the path is checked first).
void write_image(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels);

}  // namespace fenestra
