#include "scene/input_limits.h"

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "util/quoted_text.h"

namespace fenestra {

namespace fs = std::filesystem;

std::string IntegerRange::requirement() const {
  return "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

std::string coordinate_requirement() {
  std::ostringstream s;
  s << "must be finite and within +-" << limits::kMaxCoordinate << " m";
  return s.str();
}

std::string local_range_problem(const Vec3d& origin) {
  std::ostringstream limit, centre;
  limit << limits::kMaxLocalCoordinate;
  centre.precision(15);
  centre << "[" << origin.x() << ", " << origin.y() << ", " << origin.z() << "]";
  std::string s = "lies farther than " + limit.str() + " m from the model's local origin " + centre.str() +
                  " (a scene must fit within +-" + limit.str() + " m of it)";
  return s;
}

void check_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
  // The system would read the name only up to the NUL, and open another file.
  if (path.find('\0') != std::string::npos)
    throw std::invalid_argument(what + " '" + quoted_text(path) +
                                "': the file name holds a NUL byte (\\u0000), which no file name can hold");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    throw std::invalid_argument("cannot open " + what + " '" + quoted_path(path) + "': " +
                                (ec ? ec.message() : std::string("no such file")));
  if (!fs::is_regular_file(status))
    throw std::invalid_argument(what + " '" + quoted_path(path) + "' is not a regular file" +
                                (fs::is_directory(status) ? " (a directory)" : " (a device, FIFO or socket)"));
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw std::invalid_argument("cannot open " + what + " '" + quoted_path(path) + "': " + ec.message());
  if (size > max_bytes) {
    std::ostringstream s;
    s << what << " '" << path << "' is " << size << " bytes, more than the limit of " << max_bytes << " bytes ("
      << (max_bytes >> 20) << " MiB)";
    throw std::invalid_argument(s.str());
  }
}

}  // namespace fenestra
