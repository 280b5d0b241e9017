// Designs of a scan over a study's continuous parameters: where to run the forward model.
// Pure functions of their arguments (and an explicit seed), so that a scan is reproducible
// and a resumed scan asks for the same points, which the evaluation cache then serves.
// Points are in the unit cube, one coordinate per continuous parameter; scale_to_bounds()
// maps them onto [lower, upper].
#pragma once

#include <cstdint>
#include <vector>

namespace ddafit::inverse {

using UnitPoint = std::vector<double>;  // each coordinate in [0, 1]

// Full factorial grid: `points` levels per dimension, 0 and 1 included (points >= 2).
std::vector<UnitPoint> grid_design(int dimensions, int points);

// Latin hypercube: `samples` points, exactly one in each of the `samples` equal strata of
// every dimension (McKay, Beckman & Conover 1979), placed at random within its stratum.
std::vector<UnitPoint> latin_hypercube(int dimensions, int samples, std::uint64_t seed);

// Morris elementary-effects design (Morris 1991; Campolongo et al. 2007 for mu*): `r`
// trajectories of dimensions + 1 points on a grid of `levels` values (levels even, >= 2),
// each moving one coordinate at a time by delta = levels / (2 (levels - 1)).
struct MorrisDesign {
  int dimensions = 0;
  int levels = 0;
  double delta = 0.0;
  std::vector<UnitPoint> points;  // trajectory by trajectory, dimensions + 1 each
  std::vector<int> moved;         // for point k > 0 of a trajectory: the coordinate moved to reach it (-1 at a start)
};
MorrisDesign morris_design(int dimensions, int trajectories, int levels, std::uint64_t seed);

// Elementary effects of `values` (one per design point, e.g. chi2) per dimension, in unit
// coordinates: mu* (mean of |effect|, the importance) and sigma (their standard deviation,
// the sign of interaction or non-linearity). Non-finite values skip their effects.
struct MorrisEffects {
  std::vector<double> mu_star, sigma;
  std::vector<int> counted;  // effects used per dimension
};
MorrisEffects morris_effects(const MorrisDesign& design, const std::vector<double>& values);

// lower + u (upper - lower), coordinate by coordinate.
std::vector<double> scale_to_bounds(const UnitPoint& u, const std::vector<double>& lower, const std::vector<double>& upper);

}  // namespace ddafit::inverse
