// The subcommands of the ddafit command line. Each returns the process exit code.
#pragma once

#include <string>

namespace ddafit::app {

struct SimulateArgs {
  std::string scene;
  std::string out = "ddafit-out";
  bool quiet = false;
};
int run_simulate(const SimulateArgs& args);

struct VerifyArgs {
  std::string only;  // run only checks whose name contains this
  bool stability_map = false;  // print the incline stability map instead
};
int run_verify(const VerifyArgs& args);

}  // namespace ddafit::app
