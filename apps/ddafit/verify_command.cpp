#include <fmt/format.h>

#include <iostream>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "verify/verification.hpp"

namespace ddafit::app {

static void print_substep_stability_map() {
  std::cout << "substep solver: incline (phi = 25 deg, i = 5 deg; worst relative displacement error against seed Eq. 5) "
               "and a stack of five blocks at rest (top movement in 5 s, m)\n";
  std::cout << fmt::format("{:>8} {:>10} {:>9} {:>12}  {}\n", "scene", "time step", "substeps", "error", "status");
  for (const auto& p : verification::substep_stability_map({1e-3, 5e-3, 1e-2, 2e-2, 5e-2}, {1, 2, 4, 8}))
    std::cout << fmt::format("{:>8} {:>10g} {:>9} {:>12.4g}  {}\n", p.scene, p.time_step, p.substeps, p.error,
                             p.completed ? "completed" : "failed: " + p.diagnosis)
              << std::flush;
}

static int print_stability_map() {
  std::cout << "incline (phi = 25 deg, i = 5 deg): worst relative errors against seed Eq. 5\n";
  std::cout << fmt::format("{:>8} {:>10} {:>8} {:>14} {:>14} {:>8}\n", "penalty", "time step", "Omega",
                           "displacement", "acceleration", "warned");
  for (const auto& p : verification::incline_stability_map({2, 10, 50, 250}, {5e-6, 1e-5, 2e-5, 5e-5, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3}))
    std::cout << fmt::format("{:>6g} E {:>10g} {:>8.2f} {:>14.4g} {:>14.4g} {:>8}\n", p.penalty_factor, p.time_step,
                             p.omega, p.displacement_error, p.acceleration_error, p.warned ? "yes" : "no")
              << std::flush;
  return kExitSuccess;
}

int run_verify(const VerifyArgs& args) {
  if (args.stability_map) {
    if (args.integrator == "substep" || args.integrator == "all") print_substep_stability_map();
    return args.integrator == "substep" ? kExitSuccess : print_stability_map();
  }
  int failed = 0, ran = 0;
  std::cout << fmt::format("{:<28} {:<72} {:>12} {:>12} {:>10} {:>9} {}\n", "case", "quantity", "expected",
                           "computed", "error", "tolerance", "pass");
  std::vector<verification::Check> checks;
  for (Integrator integrator : {Integrator::Implicit, Integrator::Substep}) {
    if (args.integrator != "all" && args.integrator != to_string(integrator)) continue;
    for (auto& check : verification::all_checks(integrator)) checks.push_back(std::move(check));
  }
  for (const auto& check : checks) {
    if (!args.only.empty() && check.name.find(args.only) == std::string::npos) continue;
    for (const auto& r : check.run()) {
      ++ran;
      if (!r.pass) ++failed;
      // A one-sided check shows its bound where others show the analytic value.
      const std::string expected = r.bound.empty() ? fmt::format("{:.6g}", r.analytic) : r.bound;
      std::cout << fmt::format("{:<28} {:<72} {:>12} {:>12.6g} {:>10.3g} {:>9.3g} {}\n", r.case_name, r.quantity,
                               expected, r.computed, r.error, r.tolerance, r.pass ? "yes" : "NO")
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
