#include "format/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <streambuf>

#include "util/quoted_text.h"

namespace fenestra {
namespace {

namespace fs = std::filesystem;

std::atomic<const Progress*> g_interrupt{nullptr};
std::atomic<unsigned> g_counter{0};

constexpr const char* kTempMarker = ".fenestra-";
constexpr const char* kTempSuffix = ".tmp";

std::string directory_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

std::string name_of(const std::string& path) { return fs::path(path).filename().string(); }

// `.NAME.fenestra-PID-N.tmp` beside `path`.
std::string temporary_name(const std::string& path) {
  return (fs::path(directory_of(path)) / ("." + name_of(path) + kTempMarker + std::to_string(::getpid()) + "-" +
                                           std::to_string(g_counter++) + kTempSuffix))
      .string();
}

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw std::invalid_argument("cannot write '" + quoted_path(path) + "': " + why);
}

// A std::streambuf over a file descriptor that remembers whether any write failed.
class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd) { setp(buffer_, buffer_ + sizeof buffer_); }
  ~FdBuffer() override = default;
  bool flush_all() { return sync() == 0 && ok_; }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n >= static_cast<std::streamsize>(sizeof buffer_)) {  // large blocks straight through
      if (!drain() || !write_all(s, static_cast<size_t>(n))) return 0;
      return n;
    }
    return std::streambuf::xsputn(s, n);
  }

 private:
  bool drain() {
    const size_t n = static_cast<size_t>(pptr() - pbase());
    const bool ok = write_all(pbase(), n);
    setp(buffer_, buffer_ + sizeof buffer_);
    return ok;
  }
  bool write_all(const char* p, size_t n) {
    while (ok_ && n > 0) {
      const ssize_t w = ::write(fd_, p, n);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        ok_ = false;
        error_ = w < 0 ? errno : ENOSPC;
        break;
      }
      p += w;
      n -= static_cast<size_t>(w);
    }
    return ok_;
  }
  int fd_;
  bool ok_ = true;
  int error_ = 0;
  char buffer_[1 << 16];
};

// One output being written: an open temporary (unnamed, or named `named`).
struct Pending {
  std::string target;
  int fd = -1;
  std::string named;      // the temporary's name once it has one
  bool renamed = false;   // moved over the target

  void discard() {
    if (fd >= 0) ::close(fd), fd = -1;
    if (!named.empty() && !renamed) ::unlink(named.c_str());
  }
};

// Opens an unnamed temporary in the target's directory, or a named one where O_TMPFILE is not
// supported.
void open_temporary(Pending* p) {
  const std::string dir = directory_of(p->target);
#ifdef O_TMPFILE
  p->fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (p->fd >= 0) return;
#endif
  p->named = temporary_name(p->target);
  p->fd = ::open(p->named.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, 0666);
  if (p->fd < 0) {
    const int e = errno;
    p->named.clear();
    fail(p->target, std::strerror(e));
  }
}

// Gives an unnamed temporary a name beside its target.
void name_temporary(Pending* p) {
  if (!p->named.empty()) return;
  const std::string name = temporary_name(p->target);
  if (::linkat(p->fd, "", AT_FDCWD, name.c_str(), AT_EMPTY_PATH) != 0) {
    const std::string proc = "/proc/self/fd/" + std::to_string(p->fd);
    if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) != 0)
      fail(p->target, std::string("cannot name the temporary file: ") + std::strerror(errno));
  }
  p->named = name;
}

bool process_running(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

}  // namespace

void set_write_interrupt(const Progress* interrupt) { g_interrupt = interrupt; }

void check_output_path(const std::string& path, const std::vector<std::string>& inputs) {
  if (path.empty()) throw std::invalid_argument("cannot write '': the output path is empty");
  // The system would take the name only up to the NUL, and write another file.
  if (path.find('\0') != std::string::npos)
    throw std::invalid_argument("cannot write '" + quoted_path(path) +
                                "': the file name holds a NUL byte (\\u0000), which no file name can hold");
  const std::string dir = directory_of(path);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) fail(path, "directory '" + quoted_path(dir) + "' does not exist");
  if (!S_ISDIR(st.st_mode)) fail(path, "'" + quoted_path(dir) + "' is not a directory");
  if (::access(dir.c_str(), W_OK | X_OK) != 0) fail(path, "directory '" + quoted_path(dir) + "' is not writable");
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return;  // a new file
    fail(path, std::strerror(errno));
  }
  if (S_ISLNK(st.st_mode))
    fail(path, "it is a symbolic link; fenestra replaces only regular files (write to the link's target, or "
               "remove the link)");
  if (S_ISDIR(st.st_mode)) fail(path, "it is a directory");
  if (!S_ISREG(st.st_mode))
    fail(path, "it is not a regular file (a device, FIFO or socket); fenestra writes only regular files");
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (!input.empty() && fs::equivalent(path, input, ec) && !ec)
      fail(path, "it is the input file '" + input + "'; refusing to overwrite an input");
  }
}

void check_output_paths(const std::vector<std::string>& paths, const std::vector<std::string>& inputs) {
  for (size_t i = 0; i < paths.size(); ++i) {
    check_output_path(paths[i], inputs);
    for (size_t j = 0; j < i; ++j) {
      std::error_code ec;
      const bool same = fs::weakly_canonical(paths[i], ec) == fs::weakly_canonical(paths[j], ec) ||
                        (fs::equivalent(paths[i], paths[j], ec) && !ec);
      if (same) fail(paths[i], "it is also the output '" + paths[j] + "'");
    }
  }
}

void write_files_atomically(const std::vector<OutputFile>& files, const std::vector<std::string>& inputs,
                            const Progress* interrupt) {
  std::vector<std::string> paths;
  for (const OutputFile& f : files) paths.push_back(f.path);
  check_output_paths(paths, inputs);
  for (const std::string& p : paths) remove_stale_temporaries(directory_of(p));
  if (!interrupt) interrupt = g_interrupt.load();

  std::vector<Pending> pending(files.size());
  try {
    for (size_t i = 0; i < files.size(); ++i) {
      pending[i].target = files[i].path;
      open_temporary(&pending[i]);
      FdBuffer buffer(pending[i].fd);
      std::ostream out(&buffer);
      files[i].write(out);
      if (!out || !buffer.flush_all())
        fail(files[i].path, buffer.error() ? std::strerror(buffer.error()) : "the write failed");
    }
    if (interrupt) interrupt->throw_if_cancelled();
    for (Pending& p : pending) name_temporary(&p);
    for (Pending& p : pending) {
      if (::rename(p.named.c_str(), p.target.c_str()) != 0) fail(p.target, std::strerror(errno));
      p.renamed = true;
    }
    for (Pending& p : pending) p.discard();
  } catch (...) {
    for (Pending& p : pending) {
      if (p.renamed) ::unlink(p.target.c_str());  // a set is all or nothing
      p.discard();
    }
    throw;
  }
}

void write_atomically(const std::string& path, const FileWriter& write) { write_files_atomically({{path, write}}); }

void remove_stale_temporaries(const std::string& directory) {
  DIR* d = ::opendir(directory.c_str());
  if (!d) return;
  const std::string marker = kTempMarker, suffix = kTempSuffix;
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    // .NAME.fenestra-PID-N.tmp
    if (name.size() < marker.size() + suffix.size() + 4 || name[0] != '.' ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const size_t at = name.rfind(marker);
    if (at == std::string::npos) continue;
    const std::string rest = name.substr(at + marker.size(), name.size() - suffix.size() - at - marker.size());
    const size_t dash = rest.find('-');
    if (dash == std::string::npos || dash == 0 || rest.find_first_not_of("0123456789-") != std::string::npos) continue;
    const long pid = std::strtol(rest.substr(0, dash).c_str(), nullptr, 10);
    if (pid == ::getpid() || process_running(pid)) continue;
    ::unlinkat(::dirfd(d), name.c_str(), 0);
  }
  ::closedir(d);
}

}  // namespace fenestra
