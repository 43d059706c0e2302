#include "io/image_writer.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <stdexcept>

namespace fenestra {

void write_image(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels) {
  if (width < 1 || height < 1 || channels < 1 || pixels.size() != static_cast<size_t>(width) * height * channels)
    throw std::invalid_argument("image '" + path + "': pixel data does not match its size");
  // Write beside the target and rename, so a failed write leaves nothing behind.
  const std::string tmp = path + ".tmp" + path.substr(path.find_last_of('.') == std::string::npos ? path.size() : path.find_last_of('.'));
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::invalid_argument("cannot write image '" + path + "': " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  if (!out->open(tmp, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !out->close()) {
    std::remove(tmp.c_str());
    throw std::invalid_argument("cannot write image '" + path + "': " + out->geterror());
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::invalid_argument("cannot write image '" + path + "'");
  }
}

}  // namespace fenestra
