// OpenImageIO behind a plain C interface, built as its own module (fenestra_images.so) and loaded
// on first use (format/image_library.h): Debian's OpenImageIO pulls in some 250 libraries, whose
// loading would otherwise cost every run and every `import fenestra` a third of a second.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "format/image_codec_abi.h"

namespace {

void set_error(char* error, size_t capacity, const std::string& message) {
  if (!error || capacity == 0) return;
  std::strncpy(error, message.c_str(), capacity - 1);
  error[capacity - 1] = '\0';
}

// Runs `work`, returning `failed` with FENESTRA_IMAGE_OUT_OF_MEMORY in `error` when an allocation
// fails, or with the text of any other exception: none may cross the C interface.
template <typename R, typename F>
R guarded(R failed, char* error, size_t capacity, F&& work) {
  try {
    return work();
  } catch (const std::bad_alloc&) {
    set_error(error, capacity, FENESTRA_IMAGE_OUT_OF_MEMORY);
  } catch (const std::exception& e) {
    set_error(error, capacity, e.what());
  }
  return failed;
}

// The image in the format the path's extension names, handed to `sink`.
int encode(const char* path, int width, int height, int channels, const float* pixels, fenestra_image_bytes_sink sink,
           void* context, char* error, size_t capacity) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    set_error(error, capacity, OIIO::geterror());
    return 0;
  }
  if (!out->supports("ioproxy")) {
    set_error(error, capacity,
              std::string("the ") + out->format_name() + " writer cannot write to memory; use .exr or .hdr");
    return 0;
  }
  // Encoded in memory, so that the file itself is written all at once (format/atomic_file.h).
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  void* proxy = &memory;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels) || !out->close()) {
    set_error(error, capacity, out->geterror());
    return 0;
  }
  sink(context, reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return 1;
}

}  // namespace

extern "C" {

int fenestra_image_abi_version() { return FENESTRA_IMAGE_ABI_VERSION; }

void* fenestra_image_open(const char* path, int* width, int* height, int* channels, char* error, size_t capacity) {
  return guarded<void*>(nullptr, error, capacity, [&]() -> void* {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
      set_error(error, capacity, OIIO::geterror());
      return nullptr;
    }
    const OIIO::ImageSpec& spec = in->spec();
    *width = spec.width, *height = spec.height, *channels = spec.nchannels;
    return in.release();
  });
}

int fenestra_image_read(void* handle, float* pixels, char* error, size_t capacity) {
  return guarded(0, error, capacity, [&] {
    auto* in = static_cast<OIIO::ImageInput*>(handle);
    const int channels = in->spec().nchannels;
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels)) {
      set_error(error, capacity, in->geterror());
      return 0;
    }
    return 1;
  });
}

void fenestra_image_close(void* handle) {
  std::unique_ptr<OIIO::ImageInput> in(static_cast<OIIO::ImageInput*>(handle));
  if (in) in->close();
}

int fenestra_image_encode(const char* path, int width, int height, int channels, const float* pixels,
                          fenestra_image_bytes_sink sink, void* context, char* error, size_t capacity) {
  return guarded(0, error, capacity,
                 [&] { return encode(path, width, height, channels, pixels, sink, context, error, capacity); });
}

}  // extern "C"
