#pragma once
// Linear float images (environment maps) written with OpenImageIO (.exr, .hdr, ...).
#include <string>
#include <vector>

namespace fenestra {

// `pixels` holds height rows of width * channels floats, top row first.
void write_image(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels);

}  // namespace fenestra
