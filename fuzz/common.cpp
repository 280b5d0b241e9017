#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "fuzz/targets.hpp"

namespace ddafit::fuzz {

void finding(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::abort();
}

void check_message(const std::string& message) {
  if (message.empty()) finding("an empty error message");
  for (const char c : message)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) finding("a control character in: " + message);
}

std::string scratch_folder() {
  static const std::string folder = [] {
    const char* tmp = std::getenv("TMPDIR");
    const std::filesystem::path dir = std::filesystem::path(tmp ? tmp : "/tmp") /
                                      ("ddafit-fuzz-" + std::to_string(static_cast<long>(getpid())));
    std::filesystem::create_directories(dir);
    return dir.string();
  }();
  return folder;
}

}  // namespace ddafit::fuzz
