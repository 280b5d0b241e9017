#include "forward/substep/collide.hpp"
#include "forward/substep/parallel.hpp"

#include <algorithm>

#include "forward/substep/manifold.hpp"

namespace ddafit {
namespace {

// The largest piece has a few dozen corners (merged Vajont blocks); copies of two pieces'
// corners live on the stack of the narrow phase.
constexpr int kMaxCorners = 128;

int gather(const BlockSystem& s, const SubstepShapes& shapes, int piece, Vec2* out) {
  const ConvexPiece& p = shapes.pieces[piece];
  const int n = std::min(p.count, kMaxCorners);
  for (int k = 0; k < n; ++k) out[k] = s.vertices[shapes.corners[p.first + k]];
  return n;
}

// The last step's manifold of the same pair of pieces, if any (both lists are sorted).
const SubstepManifold* previous_of(const std::vector<SubstepManifold>& previous, int a, int b) {
  const auto it = std::lower_bound(previous.begin(), previous.end(), std::make_pair(a, b),
                                   [](const SubstepManifold& m, const std::pair<int, int>& key) {
                                     return std::make_pair(m.piece_a, m.piece_b) < key;
                                   });
  return it != previous.end() && it->piece_a == a && it->piece_b == b ? &*it : nullptr;
}

// A new point starts unloaded with no slip; one whose features touched in the last step
// carries its impulses (warm start) and its accumulated slip (seed Eq. 2). A corner that
// moved onto the neighbouring face of the same piece keeps its slip (seed section 2.2),
// not its impulses.
void carry_over(const SubstepManifold* old, SubstepPoint& p) {
  if (!old) return;
  for (int k = 0; k < old->point_count; ++k) {
    if (old->points[k].id == p.id) {
      const SubstepPoint& o = old->points[k];
      p.normal_impulse = o.normal_impulse;
      p.tangent_impulse = o.tangent_impulse;
      p.slip = o.slip;
      p.last_slip = o.last_slip;
      p.bonded = o.bonded;
      return;
    }
  }
  for (int k = 0; k < old->point_count; ++k) {
    if (old->points[k].owner == p.owner) {
      p.slip = old->points[k].slip;
      p.last_slip = old->points[k].last_slip;
      return;
    }
  }
}

}  // namespace

std::string collide(const BlockSystem& s, const SubstepShapes& shapes, const std::vector<std::pair<int, int>>& pairs,
                    const CollideSettings& settings, std::vector<SubstepManifold>& manifolds) {
  // Pass 1, the geometry of every pair of boxes; pass 2 builds the solver's manifolds of
  // the pairs that touch, in place (no full manifold per pair of boxes, no copy).
  const long n = static_cast<long>(pairs.size());
  std::vector<Manifold> geometry(pairs.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    const auto [a, b] = pairs[k];
    Vec2 corners_a[kMaxCorners], corners_b[kMaxCorners];
    const int na = gather(s, shapes, a, corners_a);
    const int nb = gather(s, shapes, b, corners_b);
    const std::span<const char> solid(shapes.solid);
    const double reach = settings.extra_reach.empty() ? 0.0
                         : settings.extra_reach[shapes.pieces[a].block] + settings.extra_reach[shapes.pieces[b].block];
    geometry[k] = collide_polygons(std::span<const Vec2>(corners_a, na), std::span<const Vec2>(corners_b, nb),
                                   settings.margin + reach, settings.linear_slop,
                                   solid.subspan(shapes.pieces[a].first, na),
                                   solid.subspan(shapes.pieces[b].first, nb), settings.margin,
                                   s.blocks[shapes.pieces[a].block].fixed || s.blocks[shapes.pieces[b].block].fixed);
  }
  std::vector<int> touching;
  for (long k = 0; k < n; ++k)
    if (geometry[k].point_count > 0) touching.push_back(static_cast<int>(k));

  const std::vector<SubstepManifold> previous = std::move(manifolds);
  manifolds.assign(touching.size(), SubstepManifold{});
  const long t = static_cast<long>(touching.size());
#pragma omp parallel for schedule(static) if (t >= kParallelMinimum)
  for (long j = 0; j < t; ++j) {
    const int k = touching[j];
    const auto [a, b] = pairs[k];
    const Manifold& m = geometry[k];
    SubstepManifold& out = manifolds[j];
    out.piece_a = a;
    out.piece_b = b;
    out.block_a = shapes.pieces[a].block;
    out.block_b = shapes.pieces[b].block;
    out.interface = s.interface_between(out.block_a, out.block_b);
    out.normal = m.normal;
    out.tangent = Vec2(m.normal.y(), -m.normal.x());
    out.point_count = m.point_count;
    const SubstepManifold* old = previous_of(previous, a, b);
    for (int q = 0; q < m.point_count; ++q) {
      const ManifoldPoint& mp = m.points[q];
      SubstepPoint& p = out.points[q];
      p.id = mp.id;
      p.anchor = mp.point;
      p.separation = mp.separation;
      const int piece = mp.owner == 0 ? a : b;
      // The corner's owner is the overriding block of seed Eq. 2; its length sets d_c. A
      // corner of a fixed block (the bedrock's) rides under the moving one, whose length
      // governs instead.
      p.owner = shapes.corners[shapes.pieces[piece].first + mp.vertex];
      carry_over(old, p);
      int length_block = shapes.pieces[piece].block;
      if (s.blocks[length_block].fixed) length_block = mp.owner == 0 ? out.block_b : out.block_a;
      const double ratio = out.interface >= 0 ? s.interfaces[out.interface].critical_distance_ratio : 0.01;
      p.critical_distance = ratio * block_length_along(s, length_block, out.tangent);
    }
    // Cohesion and tension act along the face the two points share, half each; a single
    // point (corner on corner, corner on face) has no bonded length.
    const double shared = m.point_count == 2 ? (m.points[0].point - m.points[1].point).norm() : 0.0;
    for (int q = 0; q < m.point_count; ++q) {
      SubstepPoint& p = out.points[q];
      p.bond_length = 0.5 * shared;
      if (settings.first_step && out.interface >= 0) {
        const Interface& face = s.interfaces[out.interface];
        p.bonded = p.separation <= settings.linear_slop && (face.cohesion > 0.0 || face.tensile_strength > 0.0);
      }
    }
  }
  std::string problem;
  for (const SubstepManifold& m : manifolds) {
    if (m.interface >= 0) continue;
    problem = "blocks '" + s.block_names[m.block_a] + "' and '" + s.block_names[m.block_b] + "' (groups '" +
              s.group_names[s.blocks[m.block_a].group] + "', '" + s.group_names[s.blocks[m.block_b].group] +
              "') touch but no interface is defined for that pair: add a contacts entry or default_interface";
    break;
  }
  return problem;
}

}  // namespace ddafit
