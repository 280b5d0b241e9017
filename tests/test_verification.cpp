// The analytic verification suite (verify/): every row of every check must pass.
// Each row carries its own tolerance and the reason for it (see `ddafit verify`).
#include <gtest/gtest.h>

#include "verify/verification.hpp"

namespace ddafit::verification {

// Printed in test names instead of the bytes of the struct (found by ADL, so it lives
// in Check's namespace).
void PrintTo(const Check& check, std::ostream* os) { *os << check.name; }

namespace {

class AnalyticCheck : public ::testing::TestWithParam<Check> {};

TEST_P(AnalyticCheck, EveryRowWithinItsTolerance) {
  const auto rows = GetParam().run();
  ASSERT_FALSE(rows.empty());
  for (const CheckRow& r : rows) {
    EXPECT_TRUE(r.pass) << r.case_name << " / " << r.quantity << ": analytic " << r.analytic << ", computed "
                        << r.computed << ", error " << r.error << " > tolerance " << r.tolerance << " (" << r.why
                        << ")";
    EXPECT_LE(r.error, r.tolerance);
  }
}

// The same suite, tolerances and reasons for both solvers (docs/verification.md).
std::vector<Check> both_suites() {
  std::vector<Check> checks = all_checks(Integrator::Implicit);
  for (Check& c : all_checks(Integrator::Substep)) checks.push_back(std::move(c));
  return checks;
}

INSTANTIATE_TEST_SUITE_P(Verification, AnalyticCheck, ::testing::ValuesIn(both_suites()),
                         [](const ::testing::TestParamInfo<Check>& info) {
                           std::string name = info.param.name;
                           for (char& c : name)
                             if (c == '/') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace ddafit::verification
