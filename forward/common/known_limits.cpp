#include "forward/common/known_limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "forward/contact/detect_contacts.hpp"

namespace ddafit {
namespace {

// Extents of block b along the unit vectors t and n.
void extents(const BlockSystem& s, int b, const Vec2& t, const Vec2& n, double& along_t, double& along_n) {
  const Block& block = s.blocks[b];
  double t_lo = std::numeric_limits<double>::infinity(), t_hi = -t_lo, n_lo = t_lo, n_hi = -t_lo;
  for (int k = 0; k < block.vertex_count; ++k) {
    const Vec2& v = s.vertices[block.first_vertex + k];
    t_lo = std::min(t_lo, v.dot(t)), t_hi = std::max(t_hi, v.dot(t));
    n_lo = std::min(n_lo, v.dot(n)), n_hi = std::max(n_hi, v.dot(n));
  }
  along_t = t_hi - t_lo, along_n = n_hi - n_lo;
}

// Normals within this of horizontal (n . up below it) are side by side, not one block resting
// on the other (collide.cpp's supports take a tenth too).
constexpr double kRestsOn = 0.1;

// Whether one block of m rests on the other (its normal more than kRestsOn against gravity), and
// which: m.normal runs from a to b, so n . up > 0 means b lies on a.
bool resting_pair(const ContactManifold& m, const Vec2& up, int& upper, int& lower) {
  const double c = m.normal.dot(up);
  if (std::abs(c) <= kRestsOn) return false;
  upper = c > 0.0 ? m.block_b : m.block_a, lower = c > 0.0 ? m.block_a : m.block_b;
  return true;
}

// The free block of m resting on the fixed one as a tall-slider candidate, into `out`.
void take_slider(const BlockSystem& s, const ContactManifold& m, const Vec2& up, TallSlider& out) {
  const bool fa = s.blocks[m.block_a].fixed;
  const Interface& face = s.interfaces[m.interface];
  if (face.cohesion > 0.0 || face.tensile_strength > 0.0) return;
  // The face's normal into the free block (m.normal runs from a to b) and its inclination.
  const int b = fa ? m.block_b : m.block_a;
  const Vec2 n = fa ? m.normal : Vec2(-m.normal);
  const double c = n.dot(up);
  if (c <= 0.0) return;  // not resting on it
  const double mu = std::tan(face.friction_angle * M_PI / 180.0);
  const double tan_slope = std::sqrt(std::max(0.0, 1.0 - c * c)) / c;
  const Vec2 t(-n.y(), n.x());
  const bool launched = std::abs(s.blocks[b].velocity.head<2>().dot(t)) > 0.0;
  if (!(tan_slope > mu) && !launched) return;  // held by its friction, at rest
  double length = 0.0, height = 0.0;
  extents(s, b, t, n, length, height);
  if (length <= 0.0) return;
  const double reach = mu * height / length;
  if (reach > out.reach) out = {b, reach, std::atan(tan_slope) * 180.0 / M_PI, face.friction_angle, launched};
}

// The upper of two free blocks of m, if one rests on the other, as a heavy-on-light candidate.
void take_heavy(const BlockSystem& s, const ContactManifold& m, const Vec2& up, HeavyOnLight& out) {
  int upper = -1, lower = -1;
  if (!resting_pair(m, up, upper, lower)) return;
  const double light = s.mass(lower);
  if (!(light > 0.0)) return;
  const double ratio = s.mass(upper) / light;
  if (ratio > out.ratio) out = {upper, lower, ratio};
}

}  // namespace

bool is_tall(const TallSlider& slider) { return slider.block >= 0 && slider.reach > kTallSliderReach * (1.0 + 1e-9); }

bool is_heavy_on_light(const HeavyOnLight& heavy) { return heavy.heavy >= 0 && heavy.ratio >= kHeavyOnLightRatio; }

KnownLimits find_known_limits(const Scene& scene, const BlockSystem& s) {
  KnownLimits out;
  const double g = scene.gravity.norm();
  if (g <= 0.0) return out;
  const Vec2 up = -scene.gravity / g;
  const double max_move = step_move_limit(scene.options.max_displacement_ratio, s);
  ContactDetection detection;
  if (!prepare_detection(s, detection).empty()) return out;
  set_run_tolerances(detection.settings, scene.options.search_distance_factor, max_move);
  detection.settings.gravity = scene.gravity;
  ContactSet contacts;
  if (!detect_contacts(s, detection, contacts).empty()) return out;
  const auto touches = [&](const ContactManifold& m) {
    if (m.interface < 0) return false;
    for (int q = 0; q < m.point_count; ++q)
      if (m.points[q].separation <= detection.settings.linear_slop) return true;
    return false;
  };
  for (const ContactManifold& m : contacts.manifolds) {
    if (!touches(m)) continue;
    const bool fa = s.blocks[m.block_a].fixed, fb = s.blocks[m.block_b].fixed;
    if (fa != fb) {
      take_slider(s, m, up, out.slider);
    } else if (!fa) {
      take_heavy(s, m, up, out.heavy);
    }
  }
  return out;
}

}  // namespace ddafit
