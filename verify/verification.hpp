// The built-in analytic suite run by `ddafit verify` and asserted by the tests.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace ddafit::verification {

struct CheckRow {
  std::string case_name;
  std::string quantity;
  double analytic = 0.0;
  double computed = 0.0;
  double error = 0.0;      // relative unless the quantity says absolute
  double tolerance = 0.0;  // error <= tolerance passes
  bool pass = false;
  std::string why;         // where the tolerance comes from
};

// Each check runs its scene and returns its rows. Checks are independent.
struct Check {
  std::string name;
  std::function<std::vector<CheckRow>()> run;
};

std::vector<Check> all_checks();

}  // namespace ddafit::verification
