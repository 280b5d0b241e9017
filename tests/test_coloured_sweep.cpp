// The sweeps update four manifolds of a colour at once (forward/substep/coloured_sweep.hpp).
// The contract: the same numbers, to the bit, as solving the colour's manifolds one at a time
// in order, because manifolds of one colour share no moving block. Checked here on random
// systems of contacts (one and two points, bonded and not, fixed blocks shared within a
// colour, colours of every size from 1 to several hundred, so that batches, remainders and the
// shared loop all run), in the relax and the soft sweep, at one pass and at sixteen.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <tuple>
#include <vector>

#include "forward/substep/prepare_contacts.hpp"
#include "forward/substep/solve_contacts.hpp"

namespace ddafit {
namespace {

struct System {
  std::vector<ContactManifold> manifolds;
  std::vector<std::vector<int>> colours;
  SweepState state;
};

// `blocks` blocks, the first `fixed` of them fixed; `count` manifolds between random pairs,
// coloured greedily as colour_manifolds does (a fixed block does not count).
System random_system(std::uint32_t seed, int blocks, int fixed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, blocks - 1);
  System s;
  s.state.velocity.resize(blocks);
  s.state.step_moves.resize(blocks);
  s.state.masses.resize(blocks);
  for (int b = 0; b < blocks; ++b) {
    s.state.velocity[b] = b < fixed ? Vec3::Zero() : Vec3(u(rng), u(rng), 0.3 * u(rng));
    s.state.step_moves[b] = b < fixed ? Vec3::Zero() : Vec3(0.01 * u(rng), 0.01 * u(rng), 0.001 * u(rng));
    const double mass = 1000.0 * (1.5 + u(rng));
    s.state.masses[b] = b < fixed ? BlockMass{} : BlockMass{1.0 / mass, 1.0 / (0.2 * mass), true};
  }
  std::vector<std::uint64_t> used(blocks, 0);  // per block, a mask of the colours it is in
  for (int k = 0; k < count; ++k) {
    int a = pick(rng), b = pick(rng);
    while (b == a || (a < fixed && b < fixed)) b = pick(rng);
    ContactManifold m;
    m.block_a = a, m.block_b = b;
    m.point_count = 1 + (u(rng) > 0.0);
    m.friction = 0.2 + 0.5 * (u(rng) + 1.0);
    m.deep_overlap = 0.01;
    const double angle = 3.14159 * u(rng);
    m.normal = Vec2(std::cos(angle), std::sin(angle));
    m.tangent = Vec2(m.normal.y(), -m.normal.x());
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = m.points[q];
      p.ra = Vec2(2.0 * u(rng), 2.0 * u(rng));
      p.rb = Vec2(2.0 * u(rng), 2.0 * u(rng));
      p.separation = 0.02 * u(rng);
      p.impulse.normal = std::max(0.0, 50.0 * u(rng));
      p.impulse.tangent = 10.0 * u(rng);
      p.impulse.normal_mass = 500.0 * (1.2 + u(rng));
      p.impulse.tangent_mass = 500.0 * (1.2 + u(rng));
      if (u(rng) > 0.6) p.impulse.tension = 20.0 * (1.0 + u(rng)), p.impulse.cohesion = 5.0 * (1.0 + u(rng));
    }
    // The first colour free on both moving blocks.
    std::uint64_t taken = 0;
    for (const int x : {a, b})
      if (x >= fixed) taken |= used[x];
    int colour = 0;
    while (colour < 63 && (taken >> colour & 1u)) ++colour;
    if (colour == 63) continue;  // a block with too many manifolds: left out
    for (const int x : {a, b})
      if (x >= fixed) used[x] |= std::uint64_t{1} << colour;
    if (static_cast<int>(s.colours.size()) <= colour) s.colours.resize(colour + 1);
    s.colours[colour].push_back(static_cast<int>(s.manifolds.size()));
    s.manifolds.push_back(m);
  }
  s.state.deep.assign(s.manifolds.size(), 0);
  return s;
}

SweepSettings sweep_settings(bool use_bias, int passes) {
  SweepSettings settings;
  settings.h = 0.01 / 3;
  settings.softness = make_softness(0.125 / settings.h, 10.0, settings.h);
  settings.max_pushout_speed = 1.0;
  settings.linear_slop = 0.005;
  settings.use_bias = use_bias;
  settings.manifold_passes = passes;
  return settings;
}

void expect_same_bits(const System& a, const System& b) {
  for (size_t k = 0; k < a.state.velocity.size(); ++k)
    for (int i = 0; i < 3; ++i) ASSERT_EQ(a.state.velocity[k][i], b.state.velocity[k][i]) << "block " << k;
  for (size_t k = 0; k < a.manifolds.size(); ++k) {
    ASSERT_EQ(a.state.deep[k], b.state.deep[k]) << "manifold " << k;
    for (int q = 0; q < a.manifolds[k].point_count; ++q) {
      ASSERT_EQ(a.manifolds[k].points[q].impulse.normal, b.manifolds[k].points[q].impulse.normal) << "manifold " << k;
      ASSERT_EQ(a.manifolds[k].points[q].impulse.tangent, b.manifolds[k].points[q].impulse.tangent) << "manifold " << k;
    }
  }
}

TEST(ColouredSweep, BatchesGiveTheNumbersOfOneManifoldAtATime) {
  int colour_sizes_seen = 0;
  for (const std::uint32_t seed : {1u, 2u, 3u})
    for (const auto& [blocks, fixed, count] : {std::tuple{12, 2, 20}, std::tuple{300, 20, 900}, std::tuple{2000, 50, 5000}})
      for (const bool use_bias : {false, true})
        for (const int passes : {1, 16}) {
          const System start = random_system(seed, blocks, fixed, count);
          colour_sizes_seen = std::max<int>(colour_sizes_seen, static_cast<int>(start.colours[0].size()));
          System batched = start, one_by_one = start;
          const SweepSettings settings = sweep_settings(use_bias, passes);
          for (int sweep = 0; sweep < 2; ++sweep) {
            solve_contacts(batched.manifolds, batched.colours, settings, batched.state);
            for (const std::vector<int>& colour : one_by_one.colours)
              for (const int k : colour)
                solve_manifold(one_by_one.manifolds[k], one_by_one.state.deep[k], settings, 1.0 / settings.h,
                               one_by_one.state);
          }
          SCOPED_TRACE(testing::Message() << "seed " << seed << ", " << count << " manifolds, bias " << use_bias
                                          << ", passes " << passes);
          expect_same_bits(batched, one_by_one);
          // Not vacuous: the sweeps changed the velocities.
          EXPECT_FALSE(batched.state.velocity == start.state.velocity);
        }
  // The largest systems' colours reach the shared loop (kColourParallelMinimum, 64).
  EXPECT_GE(colour_sizes_seen, 64);
}

// The colouring's order (colour_manifolds): order_by_key must give exactly std::stable_sort's
// order, ties in id order, or the sweeps would meet the manifolds in another order and the
// answer would move. Keys of both signs and magnitudes from 1e-300 to 1e300, many ties (keys
// rounded to a few levels, as the manifolds of one course of bricks or one row share a
// height), -0.0 beside 0.0 (equal under <), and sizes 0, 1, 2 and up to 20 000.
TEST(ColourOrder, RadixOrderIsTheStableSortOrder) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300), level(-3, 3), kind(0, 3);
  for (const int n : {0, 1, 2, 17, 256, 257, 5000, 20000})
    for (int trial = 0; trial < 3; ++trial) {
      std::vector<double> key(n);
      for (double& k : key) {
        switch (kind(rng)) {
          case 0: k = unit(rng) * std::pow(10.0, exponent(rng)); break;
          case 1: k = 0.5 * level(rng); break;
          case 2: k = unit(rng) < 0.0 ? -0.0 : 0.0; break;
          default: k = 1000.0 + unit(rng); break;
        }
      }
      std::vector<int> expected(n);
      for (int i = 0; i < n; ++i) expected[i] = i;
      std::stable_sort(expected.begin(), expected.end(), [&](int a, int b) { return key[a] < key[b]; });
      std::vector<int> order;
      order_by_key(key, order);
      ASSERT_EQ(order, expected) << n << " keys, trial " << trial;
    }
}

}  // namespace
}  // namespace ddafit
