#pragma once
// Linear float images (environment maps) written with OpenImageIO (.exr, .hdr, ...), through the
// image module (io/image_library.h).
#include <string>
#include <vector>

namespace fenestra {

// The bytes of the image file, in the format `path`'s extension names. `pixels` holds height
// rows of width * channels floats, top row first. Throws std::invalid_argument naming the path.
std::string encode_image(const std::string& path, int width, int height, int channels,
                         const std::vector<float>& pixels);
// Encodes, then writes all or nothing (io/atomic_file.h: the path is checked first).
void write_image(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels);

}  // namespace fenestra
