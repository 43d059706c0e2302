#include "format/npz_writer.h"

#include <zlib.h>

#include <sstream>
#include <stdexcept>

namespace fenestra {
namespace {

void put16(std::string* s, uint16_t v) { s->push_back(char(v & 0xFF)), s->push_back(char(v >> 8)); }
void put32(std::string* s, uint32_t v) {
  for (int i = 0; i < 4; ++i) s->push_back(char((v >> (8 * i)) & 0xFF));
}

std::string npy(const char* descr, const void* data, size_t bytes, const std::vector<size_t>& shape) {
  std::ostringstream dict;
  dict << "{'descr': '" << descr << "', 'fortran_order': False, 'shape': (";
  for (size_t i = 0; i < shape.size(); ++i) dict << shape[i] << (shape.size() == 1 || i + 1 < shape.size() ? "," : "");
  dict << "), }";
  std::string header = dict.str();
  const size_t preamble = 10;  // magic, version, header length
  header.append((64 - (preamble + header.size() + 1) % 64) % 64, ' ');
  header.push_back('\n');
  std::string out("\x93NUMPY\x01\x00", 8);
  put16(&out, static_cast<uint16_t>(header.size()));
  out += header;
  out.append(static_cast<const char*>(data), bytes);
  return out;
}

}  // namespace

void NpzWriter::add_raw(const std::string& name, const char* descr, const void* data, size_t bytes,
                        const std::vector<size_t>& shape) {
  entries_.push_back({name + ".npy", npy(descr, data, bytes, shape)});
}

void NpzWriter::add(const std::string& name, const std::vector<double>& data, const std::vector<size_t>& shape) {
  add_raw(name, "<f8", data.data(), data.size() * sizeof(double), shape);
}

void NpzWriter::add(const std::string& name, const std::vector<int32_t>& data, const std::vector<size_t>& shape) {
  add_raw(name, "<i4", data.data(), data.size() * sizeof(int32_t), shape);
}

void NpzWriter::add(const std::string& name, const std::vector<float>& data, const std::vector<size_t>& shape) {
  add_raw(name, "<f4", data.data(), data.size() * sizeof(float), shape);
}

void NpzWriter::write(std::ostream& out) const {
  std::string central;
  uint64_t offset = 0;
  for (const auto& e : entries_) {
    if (e.bytes.size() >= 0xFFFFFFFFull || offset >= 0xFFFFFFFFull)
      throw std::runtime_error("array '" + e.name + "' is too large for a .npz without ZIP64");
    const uint32_t crc = crc32(0L, reinterpret_cast<const Bytef*>(e.bytes.data()), static_cast<uInt>(e.bytes.size()));
    const uint32_t size = static_cast<uint32_t>(e.bytes.size());
    std::string local;
    put32(&local, 0x04034b50);
    put16(&local, 20), put16(&local, 0), put16(&local, 0);  // version, flags, stored
    put16(&local, 0), put16(&local, 0x21);                  // time, date (1980-01-01)
    put32(&local, crc), put32(&local, size), put32(&local, size);
    put16(&local, static_cast<uint16_t>(e.name.size())), put16(&local, 0);
    local += e.name;
    out.write(local.data(), local.size());
    out.write(e.bytes.data(), e.bytes.size());

    put32(&central, 0x02014b50);
    put16(&central, 20), put16(&central, 20), put16(&central, 0), put16(&central, 0);
    put16(&central, 0), put16(&central, 0x21);
    put32(&central, crc), put32(&central, size), put32(&central, size);
    put16(&central, static_cast<uint16_t>(e.name.size()));
    put16(&central, 0), put16(&central, 0), put16(&central, 0), put16(&central, 0);
    put32(&central, 0), put32(&central, static_cast<uint32_t>(offset));
    central += e.name;
    offset += local.size() + e.bytes.size();
  }
  std::string end;
  put32(&end, 0x06054b50);
  put16(&end, 0), put16(&end, 0);
  put16(&end, static_cast<uint16_t>(entries_.size())), put16(&end, static_cast<uint16_t>(entries_.size()));
  put32(&end, static_cast<uint32_t>(central.size())), put32(&end, static_cast<uint32_t>(offset));
  put16(&end, 0);
  out.write(central.data(), central.size());
  out.write(end.data(), end.size());
}

}  // namespace fenestra
