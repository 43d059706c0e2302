#include "format/image_writer.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "format/atomic_file.h"
#include "format/image_library.h"
#include "util/quoted_text.h"

namespace fenestra {

void check_value_image_path(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".exr" || extension == ".hdr") return;
  throw std::invalid_argument("cannot write '" + quoted_path(path) + "': only .exr and .hdr (floating point) keep the values in "
                              "cd/m^2, and " +
                              (extension.empty() ? std::string("it has no extension")
                                                 : extension + " cannot (8-bit formats clip a 318 cd/m^2 sky to 255 "
                                                               "everywhere)") +
                              ": name it .exr or .hdr");
}

std::string encode_image(const std::string& path, int width, int height, int channels,
                         const std::vector<float>& pixels) {
  check_value_image_path(path);
  if (width < 1 || height < 1 || channels < 1 || pixels.size() != static_cast<size_t>(width) * height * channels)
    throw std::invalid_argument("image '" + quoted_path(path) + "': pixel data does not match its size");
  return encode_float_image(path, width, height, channels, pixels.data());
}

void write_image(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels) {
  check_output_path(path);
  check_value_image_path(path);
  const std::string bytes = encode_image(path, width, height, channels, pixels);
  write_atomically(path, [&](std::ostream& o) { o.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

}  // namespace fenestra
