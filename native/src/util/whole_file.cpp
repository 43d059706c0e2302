#include "util/whole_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "util/out_of_memory.h"
#include "util/quoted_text.h"

namespace fenestra {
namespace {

// Closes the descriptor on every way out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// Reads up to `n` bytes into `p`, through interruptions; the count read (short only at the end).
size_t read_up_to(int fd, char* p, size_t n, const std::string& named) {
  size_t done = 0;
  while (done < n) {
    const ssize_t got = ::read(fd, p + done, n - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw std::invalid_argument("cannot read " + named + ": " + std::strerror(errno));
    if (got == 0) break;
    done += static_cast<size_t>(got);
  }
  return done;
}

}  // namespace

std::string read_whole_file(const std::string& path, const std::string& what) {
  const std::string named = what + " '" + quoted_path(path) + "'";
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (file.fd < 0) throw std::invalid_argument("cannot open " + named + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) throw std::invalid_argument("cannot read " + named + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw std::invalid_argument(named + " is not a regular file");
  const size_t size = static_cast<size_t>(st.st_size);
  std::string bytes;
  try {
    bytes.resize(size);
  } catch (const std::bad_alloc&) {
    throw OutOfMemory("out of memory while reading " + named + " (" + std::to_string(size) + " bytes)");
  }
  const size_t got = read_up_to(file.fd, bytes.data(), size, named);
  if (got != size)
    throw std::invalid_argument(named + " changed while it was read: it had " + std::to_string(size) +
                                " bytes when opened and ended after " + std::to_string(got));
  char extra = 0;
  if (read_up_to(file.fd, &extra, 1, named) != 0)
    throw std::invalid_argument(named + " changed while it was read: it grew beyond the " + std::to_string(size) +
                                " bytes it had when opened");
  return bytes;
}

}  // namespace fenestra
