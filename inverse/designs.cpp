#include "inverse/designs.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace ddafit::inverse {
namespace {

// A double in [0, 1) from the top 53 bits: the same sequence on every platform, unlike
// std::uniform_real_distribution, whose algorithm the standard leaves open.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// A permutation of 0..n-1, Fisher-Yates with the same portable draws.
std::vector<int> permutation(int n, std::mt19937_64& rng) {
  std::vector<int> p(static_cast<size_t>(n));
  std::iota(p.begin(), p.end(), 0);
  for (int i = n - 1; i > 0; --i) {
    const int j = static_cast<int>(uniform(rng) * (i + 1));
    std::swap(p[static_cast<size_t>(i)], p[static_cast<size_t>(std::min(j, i))]);
  }
  return p;
}

}  // namespace

std::vector<UnitPoint> grid_design(int dimensions, int points) {
  std::vector<UnitPoint> out;
  std::vector<int> index(static_cast<size_t>(dimensions), 0);
  while (true) {
    UnitPoint u(static_cast<size_t>(dimensions));
    for (int d = 0; d < dimensions; ++d) u[d] = static_cast<double>(index[d]) / (points - 1);
    out.push_back(u);
    int d = 0;
    while (d < dimensions && ++index[d] == points) index[d++] = 0;
    if (d == dimensions) break;
  }
  return out;
}

std::vector<UnitPoint> latin_hypercube(int dimensions, int samples, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<UnitPoint> out(static_cast<size_t>(samples), UnitPoint(static_cast<size_t>(dimensions)));
  for (int d = 0; d < dimensions; ++d) {
    const std::vector<int> strata = permutation(samples, rng);
    for (int s = 0; s < samples; ++s) out[s][d] = (strata[s] + uniform(rng)) / samples;
  }
  return out;
}

MorrisDesign morris_design(int dimensions, int trajectories, int levels, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  MorrisDesign m;
  m.dimensions = dimensions;
  m.levels = levels;
  m.delta = levels / (2.0 * (levels - 1));
  const int steps = levels - 1;
  const int low_levels = levels / 2;  // starts from which +delta stays inside [0, 1]
  for (int t = 0; t < trajectories; ++t) {
    UnitPoint x(static_cast<size_t>(dimensions));
    for (int d = 0; d < dimensions; ++d) x[d] = static_cast<int>(uniform(rng) * low_levels) / static_cast<double>(steps);
    // Each coordinate moves once, up or down by delta, in random order; a start in the
    // lower half moves up, so every point stays on the grid inside the cube.
    m.points.push_back(x);
    m.moved.push_back(-1);
    for (int d : permutation(dimensions, rng)) {
      x[d] = x[d] + m.delta <= 1.0 + 1e-12 ? x[d] + m.delta : x[d] - m.delta;
      m.points.push_back(x);
      m.moved.push_back(d);
    }
  }
  return m;
}

MorrisEffects morris_effects(const MorrisDesign& m, const std::vector<double>& values) {
  MorrisEffects e;
  const size_t n = static_cast<size_t>(m.dimensions);
  std::vector<std::vector<double>> effects(n);
  for (size_t k = 1; k < m.points.size() && k < values.size(); ++k) {
    const int d = m.moved[k];
    if (d < 0 || !std::isfinite(values[k]) || !std::isfinite(values[k - 1])) continue;
    const double step = m.points[k][d] - m.points[k - 1][d];
    effects[d].push_back((values[k] - values[k - 1]) / step);
  }
  for (size_t d = 0; d < n; ++d) {
    const auto& v = effects[d];
    double mean_abs = 0.0, mean = 0.0;
    for (double x : v) mean_abs += std::abs(x), mean += x;
    const double count = static_cast<double>(std::max<size_t>(v.size(), 1));
    mean_abs /= count;
    mean /= count;
    double var = 0.0;
    for (double x : v) var += (x - mean) * (x - mean);
    e.mu_star.push_back(v.empty() ? NAN : mean_abs);
    e.sigma.push_back(v.size() > 1 ? std::sqrt(var / (v.size() - 1)) : NAN);
    e.counted.push_back(static_cast<int>(v.size()));
  }
  return e;
}

std::vector<double> scale_to_bounds(const UnitPoint& u, const std::vector<double>& lower, const std::vector<double>& upper) {
  std::vector<double> x(u.size());
  for (size_t d = 0; d < u.size(); ++d) x[d] = lower[d] + u[d] * (upper[d] - lower[d]);
  return x;
}

}  // namespace ddafit::inverse
