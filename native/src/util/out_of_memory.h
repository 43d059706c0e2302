#pragma once
// A failed allocation, with what was being done: "out of memory while reading geometry file
// 'big.obj'". It is a std::bad_alloc, so that every handler of running out of memory still
// sees it as one; the command line prints its text and Python raises MemoryError with it.
#include <new>
#include <string>
#include <utility>

namespace fenestra {

class OutOfMemory : public std::bad_alloc {
 public:
  explicit OutOfMemory(std::string message) : message_(std::move(message)) {}
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string message_;
};

// Runs `work`; a std::bad_alloc from it becomes OutOfMemory("out of memory while " + doing). An
// OutOfMemory from deeper down (naming something more precise) passes through unchanged.
template <typename F>
auto out_of_memory_while(const std::string& doing, F&& work) -> decltype(work()) {
  try {
    return work();
  } catch (const OutOfMemory&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw OutOfMemory("out of memory while " + doing);
  }
}

}  // namespace fenestra
