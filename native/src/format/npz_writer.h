#pragma once
// NumPy .npz archives (a ZIP of .npy arrays, stored uncompressed): numpy.load() reads them.
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace fenestra {

class NpzWriter {
 public:
  // Row-major data of the given shape.
  void add(const std::string& name, const std::vector<double>& data, const std::vector<size_t>& shape);
  void add(const std::string& name, const std::vector<int32_t>& data, const std::vector<size_t>& shape);
  void add(const std::string& name, const std::vector<float>& data, const std::vector<size_t>& shape);
  void write(std::ostream& out) const;

 private:
  struct Entry {
    std::string name;
    std::string bytes;  // the whole .npy file
  };
  void add_raw(const std::string& name, const char* descr, const void* data, size_t bytes,
               const std::vector<size_t>& shape);
  std::vector<Entry> entries_;
};

}  // namespace fenestra
