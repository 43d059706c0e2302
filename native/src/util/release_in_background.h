#pragma once
// Frees a large object on a thread of its own. Returning gigabytes to the system takes a good part
// of a second, and a cancelled computation should return at once: what it built is handed over
// here instead of being destroyed while the cancel unwinds.
#include <thread>
#include <utility>

namespace fenestra {

template <typename T>
void release_in_background(T&& object) {
  std::thread([freed = std::move(object)]() {}).detach();
}

}  // namespace fenestra
