#include "forward/contact/supports.hpp"

#include <limits>

#include "forward/contact/face_axes.hpp"

namespace ddafit {
namespace {
constexpr double kUpward = 0.1;  // a normal pushes a block up when it points up by more than this
}  // namespace

std::vector<Vec2> supports(const BlockSystem& s, const std::vector<ContactManifold>& previous, double slop,
                           const Vec2& gravity) {
  const double g = gravity.norm();
  const Vec2 up = g > 0.0 ? Vec2(-gravity / g) : Vec2::Zero();
  std::vector<Vec2> held(s.blocks.size(), Vec2::Zero()), all(s.blocks.size(), Vec2::Zero());
  const auto add = [&](int block, const Vec2& into, int touching) {
    all[block] += touching * into;
    if (into.dot(up) > kUpward) held[block] += touching * into;
  };
  for (const ContactManifold& m : previous) {
    int touching = 0;
    for (int q = 0; q < m.point_count; ++q) touching += m.points[q].separation <= slop;
    add(m.block_b, m.normal, touching);
    add(m.block_a, -m.normal, touching);
  }
  for (size_t b = 0; b < held.size(); ++b) {
    Vec2& v = held[b];
    if (v.norm() == 0.0) v = all[b];
    const double length = v.norm();
    v = length > 0.0 ? Vec2(v / length) : Vec2::Zero();
  }
  return held;
}

std::vector<Vec2> rests(const BlockSystem& s, const std::vector<ContactManifold>& previous, double slop,
                        const Vec2& gravity) {
  const double g = gravity.norm();
  const Vec2 up = g > 0.0 ? Vec2(-gravity / g) : Vec2::Zero();
  const size_t n = s.blocks.size();
  std::vector<Vec2> held(n, Vec2::Zero()), nearest_normal(n, Vec2::Zero());
  std::vector<int> count(n, 0);
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  const auto add = [&](int block, const Vec2& into, double separation) {
    if (!(into.dot(up) > kUpward)) return;
    if (separation <= slop) held[block] += into, ++count[block];
    if (separation < nearest[block]) nearest[block] = separation, nearest_normal[block] = into;
  };
  for (const ContactManifold& m : previous)
    for (int q = 0; q < m.point_count; ++q) {
      add(m.block_b, m.normal, m.points[q].separation);
      add(m.block_a, -m.normal, m.points[q].separation);
    }
  std::vector<Vec2> out(n, Vec2::Zero());
  for (size_t b = 0; b < n; ++b) {
    if (s.blocks[b].fixed) continue;
    if (count[b] == 0) {
      out[b] = nearest_normal[b];
    } else if (const Vec2 mean = held[b] / count[b]; mean.norm() >= face_axes::kRestsOn) {
      out[b] = mean.normalized();
    }
  }
  return out;
}

}  // namespace ddafit
