#include "forward/step/open_close_iterate.hpp"

#include "forward/step/check_contacts.hpp"

namespace ddafit {

OpenCloseResult open_close_iterate(const BlockSystem& s, std::vector<Contact>& contacts,
                                   const StepParameters& step, const SimulationOptions& options,
                                   SparseSolver& solver, BlockSparseMatrix& k, Eigen::VectorXd& f,
                                   Eigen::VectorXd& d, StepProfile& profile) {
  OpenCloseResult result;
  for (int pass = 1; pass <= options.max_open_close_iterations; ++pass) {
    result.iterations = pass;
    {
      ScopedTimer timer(profile.assemble);
      assemble(s, contacts, step, k, f);
    }
    {
      ScopedTimer timer(profile.solve);
      if (!solver.solve(k, f, d, result.reason)) {
        result.solver_failed = true;
        return result;
      }
    }
    ContactCheck check;
    {
      ScopedTimer timer(profile.check_contacts);
      check = check_contacts(s, contacts, d, step);
    }
    if (check.changed == 0 &&
        (check.max_force_change <= kNormalForceTolerance || pass == options.max_open_close_iterations)) {
      result.converged = true;
      return result;
    }
    result.unsettled_contact = check.first_changed;
  }
  result.reason = "open-close iteration did not settle in " + std::to_string(options.max_open_close_iterations) +
                  " passes";
  return result;
}

}  // namespace ddafit
