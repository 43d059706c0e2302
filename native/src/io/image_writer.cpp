#include "io/image_writer.h"

#include <stdexcept>

#include "io/atomic_file.h"
#include "io/image_library.h"

namespace fenestra {

std::string encode_image(const std::string& path, int width, int height, int channels,
                         const std::vector<float>& pixels) {
  if (width < 1 || height < 1 || channels < 1 || pixels.size() != static_cast<size_t>(width) * height * channels)
    throw std::invalid_argument("image '" + path + "': pixel data does not match its size");
  return encode_float_image(path, width, height, channels, pixels.data());
}

void write_image(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels) {
  check_output_path(path);
  const std::string bytes = encode_image(path, width, height, channels, pixels);
  write_atomically(path, [&](std::ostream& o) { o.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

}  // namespace fenestra
