#pragma once
// Whole files read into memory. iostreams turn a failed allocation into a stream state that a
// read loop takes for the end of the file (`s << in.rdbuf()` then holds a prefix of the file,
// or nothing); this reads the size up front, allocates it, reads it and checks the byte count.
#include <string>

namespace fenestra {

// The bytes of the regular file at `path`. `what` names it for messages ("geometry file").
// Throws OutOfMemory ("out of memory while reading <what> '<path>' (N bytes)") when its buffer
// cannot be allocated, std::invalid_argument when it cannot be opened or read, or when it
// changed size while being read.
std::string read_whole_file(const std::string& path, const std::string& what);

}  // namespace fenestra
