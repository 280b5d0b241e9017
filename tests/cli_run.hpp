// Running the ddafit binary from a test: its exit code, stdout and stderr, and scene files
// written for it. Shared by the command-line tests.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ddafit_test {

namespace fs = std::filesystem;

struct CommandResult {
  int code = -1;    // the exit code; -1 when the process ended by a signal
  int signal = 0;   // the signal that ended it, if any
  std::string out, err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `ddafit ARGS` with stdout and stderr kept in DDAFIT_TEST_TMP/TAG.
inline CommandResult ddafit(const std::string& args, const std::string& tag) {
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / tag;
  fs::create_directories(dir);
  const std::string cmd = std::string(DDAFIT_BINARY) + " " + args + " > " + (dir / "stdout").string() + " 2> " +
                          (dir / "stderr").string();
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  // The shell reports a child killed by a signal as exit 128 + signal.
  if (r.code > 128 && r.code < 160) r.signal = r.code - 128;
  r.out = slurp(dir / "stdout");
  r.err = slurp(dir / "stderr");
  return r;
}

inline fs::path write_file(const std::string& tag, const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / tag;
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

inline fs::path write_scene(const std::string& tag, const std::string& text) {
  return write_file(tag, "scene.yaml", text);
}

}  // namespace ddafit_test
