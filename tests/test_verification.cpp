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

INSTANTIATE_TEST_SUITE_P(Verification, AnalyticCheck, ::testing::ValuesIn(all_checks()),
                         [](const ::testing::TestParamInfo<Check>& info) { return info.param.name; });

}  // namespace
}  // namespace ddafit::verification
