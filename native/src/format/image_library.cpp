#include "format/image_library.h"

#include <dlfcn.h>
#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>
#include <vector>

#include "format/image_codec_abi.h"
#include "util/out_of_memory.h"
#include "util/quoted_text.h"

namespace fenestra {
namespace {

constexpr const char* kModuleFile = "fenestra_images.so";
// OpenImageIO's libraries take about 600 MB of address space as they load (measured: 601 MB), and
// their static initialisers abort the process when an allocation fails there (the exception has
// nowhere to go): under an address-space limit (ulimit -v) that leaves less, refuse first.
constexpr size_t kModuleAddressSpace = 640ull << 20;
constexpr size_t kErrorCapacity = 1024;

struct ImageModule {
  decltype(&fenestra_image_open) open = nullptr;
  decltype(&fenestra_image_read) read = nullptr;
  decltype(&fenestra_image_close) close = nullptr;
  decltype(&fenestra_image_encode) encode = nullptr;
  std::string path;     // where it was loaded from
  std::string failure;  // why it could not be, naming every place tried
};

std::string directory_of(const std::string& file) {
  char resolved[PATH_MAX];
  const std::string real = realpath(file.c_str(), resolved) ? std::string(resolved) : file;
  const size_t slash = real.find_last_of('/');
  return slash == std::string::npos ? std::string() : real.substr(0, slash);
}

// Beside the binary holding this code (the Python module, or the program), beside the running
// program, then where the build put it.
std::vector<std::string> candidate_paths() {
  std::vector<std::string> out;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&candidate_paths), &info) && info.dli_fname && info.dli_fname[0] == '/')
    out.push_back(directory_of(info.dli_fname) + "/" + kModuleFile);
  char exe[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof(exe) - 1);
  if (n > 0) out.push_back(directory_of(std::string(exe, static_cast<size_t>(n))) + "/" + kModuleFile);
#ifdef FENESTRA_IMAGES_MODULE
  out.push_back(FENESTRA_IMAGES_MODULE);
#endif
  return out;
}

ImageModule load_module() {
  ImageModule m;
  std::string tried;
  for (const std::string& path : candidate_paths()) {
    if (access(path.c_str(), F_OK) != 0) {
      tried += "\n  " + path + ": not there";
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      tried += "\n  " + path + ": " + (why ? why : "cannot be loaded");
      continue;
    }
    auto version = reinterpret_cast<decltype(&fenestra_image_abi_version)>(dlsym(handle, "fenestra_image_abi_version"));
    m.open = reinterpret_cast<decltype(m.open)>(dlsym(handle, "fenestra_image_open"));
    m.read = reinterpret_cast<decltype(m.read)>(dlsym(handle, "fenestra_image_read"));
    m.close = reinterpret_cast<decltype(m.close)>(dlsym(handle, "fenestra_image_close"));
    m.encode = reinterpret_cast<decltype(m.encode)>(dlsym(handle, "fenestra_image_encode"));
    if (!version || version() != FENESTRA_IMAGE_ABI_VERSION || !m.open || !m.read || !m.close || !m.encode) {
      tried += "\n  " + path + ": another version of the image module (rebuild Fenestra)";
      m = ImageModule();
      continue;
    }
    m.path = path;
    return m;
  }
  m.failure = "the image module " + std::string(kModuleFile) + " (OpenImageIO) could not be loaded; tried:" + tried;
  return m;
}

// Whether kModuleAddressSpace can be reserved now (and is released at once).
bool room_to_load_module() {
  void* p = mmap(nullptr, kModuleAddressSpace, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (p == MAP_FAILED) return false;
  munmap(p, kModuleAddressSpace);
  return true;
}

const ImageModule& module() {
  static std::atomic<bool> loaded{false};
  if (!loaded && !room_to_load_module())
    throw OutOfMemory("out of memory while loading the image module " + std::string(kModuleFile) +
                      " (OpenImageIO needs about " + std::to_string(kModuleAddressSpace >> 20) +
                      " MB of address space, more than the process's limit leaves: see ulimit -v)");
  static const ImageModule m = load_module();
  loaded = true;
  if (!m.open) throw ImageError(m.failure, m.failure);
  return m;
}

// An allocation that failed inside the module (which lets no exception out) fails here again.
void throw_if_out_of_memory(const char* error) {
  if (std::strcmp(error, FENESTRA_IMAGE_OUT_OF_MEMORY) == 0) throw std::bad_alloc();
}

}  // namespace

std::string image_module_path() {
  try {
    return module().path;
  } catch (const std::exception& e) {
    return e.what();
  }
}

namespace detail {

ImageHeader open_image(const std::string& path) {
  const ImageModule& m = module();
  char error[kErrorCapacity] = {};
  ImageHeader h;
  h.handle = m.open(path.c_str(), &h.width, &h.height, &h.channels, error, sizeof(error));
  if (!h.handle) throw_if_out_of_memory(error);
  if (!h.handle) throw ImageError("cannot read image '" + quoted_path(path) + "': " + error, error);
  return h;
}

void read_image(const std::string& path, const ImageHeader& header, float* pixels) {
  char error[kErrorCapacity] = {};
  if (!module().read(header.handle, pixels, error, sizeof(error))) {
    throw_if_out_of_memory(error);
    throw ImageError("cannot read image '" + quoted_path(path) + "': " + error, error);
  }
}

void close_image(const ImageHeader& header) {
  if (header.handle) module().close(header.handle);
}

}  // namespace detail

std::string encode_float_image(const std::string& path, int width, int height, int channels, const float* pixels) {
  const ImageModule& m = module();
  char error[kErrorCapacity] = {};
  std::string bytes;
  auto sink = [](void* context, const char* data, size_t size) { static_cast<std::string*>(context)->assign(data, size); };
  if (!m.encode(path.c_str(), width, height, channels, pixels, sink, &bytes, error, sizeof(error))) {
    throw_if_out_of_memory(error);
    throw ImageError("cannot write image '" + quoted_path(path) + "': " + error, error);
  }
  return bytes;
}

}  // namespace fenestra
