// Scan designs (inverse/designs.hpp): the properties each design is defined by.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <vector>

#include "inverse/designs.hpp"

namespace ddafit::inverse {
namespace {

TEST(Designs, LatinHypercubePutsOnePointInEveryStratumOfEveryParameter) {
  // The defining property (McKay et al. 1979): n samples, n strata per dimension, exactly
  // one sample in each. Exact integer counts: no tolerance.
  for (std::uint64_t seed : {1u, 7u, 12345u}) {
    const int n = 17, dims = 3;
    const auto points = latin_hypercube(dims, n, seed);
    ASSERT_EQ(points.size(), static_cast<size_t>(n));
    for (int d = 0; d < dims; ++d) {
      std::vector<int> count(n, 0);
      for (const UnitPoint& p : points) {
        ASSERT_GE(p[d], 0.0);
        ASSERT_LT(p[d], 1.0);
        ++count[static_cast<int>(p[d] * n)];
      }
      for (int s = 0; s < n; ++s) EXPECT_EQ(count[s], 1) << "seed " << seed << ", dimension " << d << ", stratum " << s;
    }
  }
}

TEST(Designs, LatinHypercubeIsReproducibleFromItsSeed) {
  // A resumed scan must ask for the same points, or the cache cannot serve them.
  EXPECT_EQ(latin_hypercube(2, 9, 42), latin_hypercube(2, 9, 42));
  EXPECT_NE(latin_hypercube(2, 9, 42), latin_hypercube(2, 9, 43));
}

TEST(Designs, GridHasEveryCombinationOnce) {
  const auto points = grid_design(3, 4);
  EXPECT_EQ(points.size(), 64u);  // 4^3
  EXPECT_EQ(std::set<UnitPoint>(points.begin(), points.end()).size(), 64u);
  EXPECT_NE(std::find(points.begin(), points.end(), UnitPoint{0, 0, 0}), points.end());
  EXPECT_NE(std::find(points.begin(), points.end(), UnitPoint{1, 1, 1}), points.end());
}

TEST(Designs, MorrisRanksAKnownFunction) {
  // f = 10 x0 + 2 x1 + 0.2 x2 + 4 x1 x3. Elementary effects: x0 always 10 and x2 always
  // 0.2 (linear: sigma 0); x1's is 2 + 4 x3 (mean about 4) and x3's is 4 x1 (mean about
  // 2), both spread by the interaction (sigma > 0). mu* must rank x0 > x1 > x3 > x2; the
  // linear effects are exact to round-off (1e-9), the spread well above it (> 0.1).
  const MorrisDesign design = morris_design(4, 20, 4, 2026);
  ASSERT_EQ(design.points.size(), 20u * 5u);
  std::vector<double> f;
  for (const UnitPoint& x : design.points) {
    for (double c : x) ASSERT_TRUE(c >= -1e-12 && c <= 1.0 + 1e-12);
    f.push_back(10 * x[0] + 2 * x[1] + 0.2 * x[2] + 4 * x[1] * x[3]);
  }
  const MorrisEffects e = morris_effects(design, f);
  std::vector<int> order(4);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return e.mu_star[a] > e.mu_star[b]; });
  EXPECT_EQ(order, (std::vector<int>{0, 1, 3, 2}));
  EXPECT_NEAR(e.mu_star[0], 10.0, 1e-9);
  EXPECT_NEAR(e.mu_star[2], 0.2, 1e-9);
  EXPECT_LT(e.sigma[0], 1e-9);
  EXPECT_LT(e.sigma[2], 1e-9);
  EXPECT_GT(e.sigma[1], 0.1);
  EXPECT_GT(e.sigma[3], 0.1);
  for (int count : e.counted) EXPECT_EQ(count, 20);  // one effect per trajectory and parameter
}

}  // namespace
}  // namespace ddafit::inverse
