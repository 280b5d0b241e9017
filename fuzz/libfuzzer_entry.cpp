// libFuzzer's entry point for one target, chosen at compile time (fuzz/CMakeLists.txt).
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return ddafit::fuzz::DDAFIT_FUZZ_TARGET(data, size);
}
