#include "format/output_pair.h"
#include "util/quoted_text.h"

#include <sys/stat.h>

#include <stdexcept>

namespace fenestra {
namespace {

// "a device", "a FIFO", ... for what stat says is at `path`; "" for a regular file or nothing.
std::string non_file_kind(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return "";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  if (S_ISDIR(st.st_mode)) return "a directory";
  return "";
}

}  // namespace

std::pair<std::string, std::string> npz_json_pair(const std::string& out) {
  const bool has_ext = out.size() > 4 && out.compare(out.size() - 4, 4, ".npz") == 0;
  const std::string stem = has_ext ? out.substr(0, out.size() - 4) : out;
  std::pair<std::string, std::string> pair{stem + ".npz", stem + ".json"};
  for (const std::string& named : {out, stem}) {
    const std::string kind = non_file_kind(named);
    // A directory `results` beside an explicit `results.npz` is no mistake; as `-o results` it is.
    if (!kind.empty() && !(named != out && kind == "a directory"))
      throw std::invalid_argument("cannot write '" + quoted_path(pair.first) + "' and '" + quoted_path(pair.second) + "': the output '" + out +
                                  "' names " + kind + (named == out ? "" : " ('" + quoted_path(named) + "')") +
                                  ", and its .npz and .json would be created beside it; name a new or regular "
                                  "file (OUT or OUT.npz) in a writable directory");
  }
  return pair;
}

}  // namespace fenestra
