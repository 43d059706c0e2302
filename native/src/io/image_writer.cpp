#include "io/image_writer.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <stdexcept>

#include "io/atomic_file.h"

namespace fenestra {

std::string encode_image(const std::string& path, int width, int height, int channels,
                         const std::vector<float>& pixels) {
  if (width < 1 || height < 1 || channels < 1 || pixels.size() != static_cast<size_t>(width) * height * channels)
    throw std::invalid_argument("image '" + path + "': pixel data does not match its size");
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::invalid_argument("cannot write image '" + path + "': " + OIIO::geterror());
  if (!out->supports("ioproxy"))
    throw std::invalid_argument("cannot write image '" + path + "': the " + out->format_name() +
                                " writer cannot write to memory; use .exr or .hdr");
  // Encoded in memory, so that the file itself is written all at once (io/atomic_file.h).
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  void* proxy = &memory;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !out->close())
    throw std::invalid_argument("cannot write image '" + path + "': " + out->geterror());
  return std::string(bytes.begin(), bytes.end());
}

void write_image(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels) {
  check_output_path(path);
  const std::string bytes = encode_image(path, width, height, channels, pixels);
  write_atomically(path, [&](std::ostream& o) { o.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

}  // namespace fenestra
