#include "io/atomic_file.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace fenestra {

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (!target.parent_path().empty() && !fs::is_directory(target.parent_path()))
    throw std::invalid_argument("cannot write '" + path + "': directory '" + target.parent_path().string() +
                                "' does not exist");
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::invalid_argument("cannot write '" + path + "'");
    write(out);
    out.close();
    if (!out) throw std::invalid_argument("failed writing '" + path + "'");
    fs::rename(tmp, target);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace fenestra
