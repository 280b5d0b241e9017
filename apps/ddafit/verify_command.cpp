#include <fmt/format.h>

#include <iostream>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "verify/verification.hpp"

namespace ddafit::app {

int run_verify(const VerifyArgs& args) {
  int failed = 0, ran = 0;
  std::cout << fmt::format("{:<28} {:<72} {:>12} {:>12} {:>10} {:>9} {}\n", "case", "quantity", "analytic",
                           "computed", "error", "tolerance", "pass");
  for (const auto& check : verification::all_checks()) {
    if (!args.only.empty() && check.name.find(args.only) == std::string::npos) continue;
    for (const auto& r : check.run()) {
      ++ran;
      if (!r.pass) ++failed;
      std::cout << fmt::format("{:<28} {:<72} {:>12.6g} {:>12.6g} {:>10.3g} {:>9.3g} {}\n", r.case_name, r.quantity,
                               r.analytic, r.computed, r.error, r.tolerance, r.pass ? "yes" : "NO")
                << std::flush;
    }
  }
  if (ran == 0) {
    std::cerr << "verify: --only: no check matches '" << args.only << "'\n";
    return kExitBadInput;
  }
  std::cout << fmt::format("{} passed, {} failed\n", ran - failed, failed);
  return failed == 0 ? kExitSuccess : kExitFailedCheck;
}

}  // namespace ddafit::app
