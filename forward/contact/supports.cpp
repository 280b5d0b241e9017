#include "forward/contact/supports.hpp"

#include <algorithm>
#include <limits>

#include "forward/contact/face_axes.hpp"

namespace ddafit {
namespace {
constexpr double kUpward = 0.1;  // a normal pushes a block up when it points up by more than this
}  // namespace

Supports read_supports(const BlockSystem& s, const std::vector<ContactManifold>& previous, double slop,
                       const Vec2& gravity) {
  const double g = gravity.norm();
  const Vec2 up = g > 0.0 ? Vec2(-gravity / g) : Vec2::Zero();
  const size_t n = s.blocks.size();
  // held: the touching points that push up; all: every touching point; count: how many push up.
  std::vector<Vec2> held(n, Vec2::Zero()), all(n, Vec2::Zero()), nearest_normal(n, Vec2::Zero());
  std::vector<int> count(n, 0);
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  // Per manifold, its touching points together (they share its normal).
  const auto add = [&](int block, const Vec2& into, int touching, double closest) {
    all[block] += touching * into;
    if (!(into.dot(up) > kUpward)) return;
    held[block] += touching * into;
    count[block] += touching;
    if (closest < nearest[block]) nearest[block] = closest, nearest_normal[block] = into;
  };
  Supports out{std::vector<Vec2>(n, Vec2::Zero()), std::vector<Vec2>(n, Vec2::Zero()),
               std::vector<Vec2>(s.vertices.size(), Vec2::Zero())};
  // Per corner: the sum of the normals into its block of the touching points on it (in
  // out.corner_held until it is read below), and how many.
  std::vector<int> corner_count(s.vertices.size(), 0);
  for (const ContactManifold& m : previous) {
    int touching = 0;
    double closest = std::numeric_limits<double>::infinity();
    for (int q = 0; q < m.point_count; ++q) {
      const ContactPoint& p = m.points[q];
      touching += p.separation <= slop;
      closest = std::min(closest, p.separation);
      if (!(p.separation <= slop) || p.owner < 0) continue;
      const bool on_a = s.vertex_block[static_cast<size_t>(p.owner)] == m.block_a;
      out.corner_held[static_cast<size_t>(p.owner)] += on_a ? Vec2(-m.normal) : m.normal;
      ++corner_count[static_cast<size_t>(p.owner)];
    }
    add(m.block_b, m.normal, touching, closest);
    add(m.block_a, -m.normal, touching, closest);
  }
  for (size_t v = 0; v < corner_count.size(); ++v) {
    Vec2& sum = out.corner_held[v];
    if (corner_count[v] == 0) continue;
    sum = sum.norm() >= face_axes::kRestsOn * corner_count[v] ? Vec2(sum.normalized()) : Vec2::Zero();
  }
  for (size_t b = 0; b < n; ++b) {
    const Vec2& v = held[b].norm() == 0.0 ? all[b] : held[b];
    const double length = v.norm();
    if (length > 0.0) out.support[b] = v / length;
    if (s.blocks[b].fixed) continue;
    if (length == 0.0) out.support[b] = nearest_normal[b];  // it lands: the surface it comes down on
    if (count[b] == 0) {
      out.rest[b] = nearest_normal[b];
    } else if (held[b].norm() >= face_axes::kRestsOn * count[b]) {
      out.rest[b] = held[b].normalized();
    }
  }
  return out;
}

}  // namespace ddafit
