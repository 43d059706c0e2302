#pragma once
// Image files through the image module (fenestra_images.so, OpenImageIO), loaded on first use:
// scenes without environment maps and runs that write no images never load it.
#include <stdexcept>
#include <string>
#include <vector>

namespace fenestra {

// An image that cannot be read or written, or a missing image module: `reason` says why, without
// the path (callers name the file in their own terms).
class ImageError : public std::invalid_argument {
 public:
  ImageError(const std::string& message, std::string reason) : std::invalid_argument(message), reason_(std::move(reason)) {}
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

struct FloatImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;  // height rows of width * channels, top row first
};

// Reads an image. `check_size(width, height, channels)` runs on the header, before the pixels
// are allocated (and may throw). Throws ImageError naming the path.
template <typename CheckSize>
FloatImage read_float_image(const std::string& path, CheckSize check_size);

// The bytes of the image file, in the format `path`'s extension names.
std::string encode_float_image(const std::string& path, int width, int height, int channels, const float* pixels);

// Where the image module was found, or a message saying where it was looked for (for errors).
std::string image_module_path();

namespace detail {
struct ImageHeader {
  void* handle = nullptr;
  int width = 0, height = 0, channels = 0;
};
ImageHeader open_image(const std::string& path);
void read_image(const std::string& path, const ImageHeader& header, float* pixels);
void close_image(const ImageHeader& header);
}  // namespace detail

template <typename CheckSize>
FloatImage read_float_image(const std::string& path, CheckSize check_size) {
  const detail::ImageHeader header = detail::open_image(path);
  FloatImage image;
  try {
    check_size(header.width, header.height, header.channels);
    image.width = header.width, image.height = header.height, image.channels = header.channels;
    image.pixels.resize(static_cast<size_t>(header.width) * header.height * header.channels);
    detail::read_image(path, header, image.pixels.data());
  } catch (...) {
    detail::close_image(header);
    throw;
  }
  detail::close_image(header);
  return image;
}

}  // namespace fenestra
