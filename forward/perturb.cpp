#include "forward/perturb.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

#include "forward/geometry.hpp"

namespace ddafit {
namespace {

// SplitMix64 (Steele, Lea & Flood 2014): a fixed, portable sequence from a 64-bit seed.
struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
};

}  // namespace

Scene perturbed_scene(const Scene& scene, int realisation) {
  if (realisation <= 0) return scene;
  Scene out = scene;
  SplitMix64 random{static_cast<std::uint64_t>(realisation)};
  std::vector<Vec2> offset(scene.blocks.size(), Vec2::Zero());
  for (size_t b = 0; b < scene.blocks.size(); ++b) {
    if (scene.blocks[b].fixed) continue;
    const double size = std::sqrt(std::abs(signed_area(scene.blocks[b].polygon)));
    const double ratio = scene.options.jitter_ratio > 0.0 ? scene.options.jitter_ratio : kJitterRatio;
    const double radius = ratio * size * std::sqrt(random.uniform());
    const double angle = 2.0 * M_PI * random.uniform();
    offset[b] = Vec2(radius * std::cos(angle), radius * std::sin(angle));
    for (Vec2& p : out.blocks[b].polygon) p += offset[b];
  }
  for (MeasurePoint& m : out.measure)
    for (size_t b = 0; b < scene.blocks.size(); ++b)
      if (!scene.blocks[b].fixed && point_in_polygon(m.at, scene.blocks[b].polygon)) {
        m.at += offset[b];
        break;
      }
  return out;
}

}  // namespace ddafit
