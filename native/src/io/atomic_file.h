#pragma once
// Writes a file all at once or not at all: to a temporary beside it, renamed on success.
#include <functional>
#include <ostream>
#include <string>

namespace fenestra {

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace fenestra
