#include "forward/contact/collide.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "forward/contact/contact_law.hpp"
#include "forward/contact/manifold.hpp"
#include "forward/contact/slip_history.hpp"
#include "forward/contact/supports.hpp"
#include "forward/parallel.hpp"

namespace ddafit {
namespace {

// The pieces of meshed blocks have a few dozen corners at most (merged Vajont blocks): copies of
// two pieces' corners live on the stack of the narrow phase up to this many each, and beyond it
// on the heap (gather).
constexpr int kMaxCorners = 128;

// Contacts whose normal is within this of horizontal (|n . g| / |g| below it) are side by
// side: neither block is above the other, and the lower block id overrides.
constexpr double kSideBySide = 1e-3;

// A piece's corners, copied into `stack` (kMaxCorners long) or, for a larger piece, into
// `spill`. A fixed ground given by a surface digitised every few metres keeps all its straight
// vertices in one convex piece; cut at 128 corners, the piece read as its first 128 let a 30 m
// slider sink into the ground (model revision 2026-12-06.25; tests/test_ground_joints.cpp).
std::span<const Vec2> gather(const BlockSystem& s, const ContactShapes& shapes, int piece, Vec2* stack,
                             std::vector<Vec2>& spill) {
  const ConvexPiece& p = shapes.pieces[piece];
  Vec2* out = stack;
  if (p.count > kMaxCorners) spill.resize(static_cast<size_t>(p.count)), out = spill.data();
  for (int k = 0; k < p.count; ++k) out[k] = s.vertices[shapes.corners[p.first + k]];
  return {out, static_cast<size_t>(p.count)};
}

// The last step's manifold of the same pair of pieces, if any (both lists are sorted).
const ContactManifold* previous_of(const std::vector<ContactManifold>& previous, int a, int b) {
  const auto it = std::lower_bound(previous.begin(), previous.end(), std::make_pair(a, b),
                                   [](const ContactManifold& m, const std::pair<int, int>& key) {
                                     return std::make_pair(m.piece_a, m.piece_b) < key;
                                   });
  return it != previous.end() && it->piece_a == a && it->piece_b == b ? &*it : nullptr;
}

void start_step(SpringState& c) {
  c.step_state = c.state;
  c.start_force = c.state == ContactState::Open ? 0.0f : static_cast<float>(std::max(c.normal_force, 0.0));
  c.state_changes = 0;
  c.shear_scale = 1.0f;
}

void take_state(const ContactPoint& o, ContactPoint& p) {
  p.impulse.normal = o.impulse.normal;
  p.impulse.tangent = o.impulse.tangent;
  p.impulse.carried = o.impulse.carried;
  p.spring = o.spring;
  p.bonded = o.bonded;
  p.bond_slip = o.bond_slip;
  p.bond_opening = o.bond_opening;
  p.fresh = false;
  start_step(p.spring);
}

// The share of the new points' spacing within which a bonded point of the last step is the
// same point found again by place (carry_over).
constexpr double kPlaceShare = 0.25;

// A point of the last step carries its state into this step: the substep solver's impulses
// (warm start), the implicit solver's spring state, and its bond; its spring's state is the
// state at the start of this step. A new point starts unloaded and unbonded; the implicit solver
// takes it as locked where it touches (within the slop: blocks tiled flush at t = 0 touch at
// separations of +-1e-15 m).
// A point is the last step's point with its features, or else, if that point was bonded, the
// nearest bonded point not taken within kPlaceShare of the new points' spacing and within the
// margin (the most two blocks move against each other in a step). Where two faces lie flush
// (a block hung under another, equal blocks stacked) either face may be the reference, and the
// choice flips between steps as the blocks turn by micro-radians: the clipped points then carry
// the other block's features at the same places. Matched by features alone, a flip broke every
// bond of the joint (model revision 2026-12-03.2): the substep solver dropped all 96 chains of
// 1-8 blocks hung under a roof by bonds of 1.5-10 times their weight, at the first step
// (tests/test_bonds.cpp). An unbonded point keeps the features-only match: carried across a
// flip by place, its load is the resting column's warm start, but also the blow of an impact
// that the impact groups' margins were measured without (docs/theory.md §13, "A flipped face
// drops its load").
void carry_over(const ContactManifold* old, double slop, double margin, ContactManifold& m) {
  bool taken[2] = {false, false}, matched[2] = {false, false};
  for (int q = 0; old && q < m.point_count; ++q)
    for (int k = 0; k < old->point_count; ++k)
      if (!taken[k] && old->points[k].id == m.points[q].id) {
        take_state(old->points[k], m.points[q]);
        taken[k] = matched[q] = true;
        break;
      }
  if (matched[0] && (m.point_count < 2 || matched[1])) return;  // the common case: nothing to seek
  const double spacing = m.point_count == 2 ? (m.points[0].anchor - m.points[1].anchor).norm()
                                            : std::numeric_limits<double>::infinity();
  const double reach = std::min(kPlaceShare * spacing, margin);
  for (int q = 0; q < m.point_count; ++q) {
    if (matched[q]) continue;
    ContactPoint& p = m.points[q];
    int nearest = -1;
    double best = reach;
    for (int k = 0; old && k < old->point_count; ++k)
      if (!taken[k] && old->points[k].bonded)
        if (const double d = (old->points[k].anchor - p.anchor).norm(); d <= best) best = d, nearest = k;
    if (nearest >= 0) {
      take_state(old->points[nearest], p);
      taken[nearest] = true;
      continue;
    }
    p.spring.state = p.separation <= slop ? ContactState::Locked : ContactState::Open;
    start_step(p.spring);
  }
}

// Seed Eq. 2's overriding block of a pair: the free one if the other is fixed, else the
// upper one, else (side by side) the lower id. Its face in the manifold is the face that
// slides, and its length along the contact sets d_c.
int overriding_block(const BlockSystem& s, const ContactManifold& m, const Vec2& gravity) {
  const bool fa = s.blocks[m.block_a].fixed, fb = s.blocks[m.block_b].fixed;
  if (fa != fb) return fa ? m.block_b : m.block_a;
  const double g = gravity.norm();
  const double up = g > 0.0 ? -m.normal.dot(gravity) / g : 0.0;  // > 0: b lies above a
  if (std::abs(up) <= kSideBySide) return std::min(m.block_a, m.block_b);
  return up > 0.0 ? m.block_b : m.block_a;
}

double block_size(const BlockSystem& s, int b) { return std::sqrt(std::abs(s.blocks[b].area)); }

// The deepest point kept on a piece with cuts, as a share of the smaller free block's size:
// twice the flush tolerance, four times the 1 % overlap the runs are held to.
constexpr double kCutDepthRatio = 2.0 * kFlushRatio;

// One corner where two flush fixed blocks meet (a joint's end on the surface) touches a
// block lying across the joint once, not twice: both blocks' manifolds with it put a point there,
// with one normal. The later manifold's copy is dropped; a manifold left without points
// goes. Two springs at one place doubled the implicit solver's stiffness where a block
// landed on such a corner, and the landing threw it (docs/theory.md §3, Flush neighbours).
// `free_on_fixed`, per manifold: its free block where the other is fixed, else -1 (set where the
// manifolds are built, in parallel: a scan of the manifolds here read a 576-byte manifold for
// its two block ids, on one thread, every step).
void drop_shared_corners(std::vector<ContactManifold>& manifolds, const std::vector<int>& free_on_fixed, double slop) {
  // (free block, manifold) for the manifolds between a free and a fixed block, by block.
  std::vector<std::pair<int, int>> on_fixed;
  for (int k = 0; k < static_cast<int>(manifolds.size()); ++k)
    if (free_on_fixed[k] >= 0) on_fixed.emplace_back(free_on_fixed[k], k);
  std::sort(on_fixed.begin(), on_fixed.end());
  constexpr double kSameNormal = 1e-6;  // 1 - cos of the angle between the two normals
  bool dropped = false;
  for (size_t i = 0; i < on_fixed.size(); ++i)
    for (size_t j = i + 1; j < on_fixed.size() && on_fixed[j].first == on_fixed[i].first; ++j) {
      const int b = on_fixed[i].first;
      ContactManifold& first = manifolds[on_fixed[i].second];
      ContactManifold& second = manifolds[on_fixed[j].second];
      if (first.block_a == second.block_a && first.block_b == second.block_b) continue;  // pieces of one pair
      // Both normals seen from block b (pointing towards it).
      const Vec2 n1 = first.block_b == b ? first.normal : Vec2(-first.normal);
      const Vec2 n2 = second.block_b == b ? second.normal : Vec2(-second.normal);
      if (n1.dot(n2) < 1.0 - kSameNormal) continue;
      for (int p = 0; p < first.point_count; ++p)
        for (int q = 0; q < second.point_count; ++q) {
          if ((first.points[p].anchor - second.points[q].anchor).norm() > slop) continue;
          // The copy kept carries the bond of both: each stood for half of its own face's
          // length (collide), and without the dropped half a block bonded across short
          // joints held by little more than half its bonded length.
          first.points[p].bond_length += second.points[q].bond_length;
          second.points[q] = second.points[second.point_count - 1];
          --second.point_count;
          --q;
          dropped = true;
        }
    }
  if (dropped)
    manifolds.erase(std::remove_if(manifolds.begin(), manifolds.end(),
                                   [](const ContactManifold& m) { return m.point_count == 0; }),
                    manifolds.end());
}

}  // namespace

const char* to_string(ContactState state) {
  switch (state) {
    case ContactState::Open: return "open";
    case ContactState::Sliding: return "sliding";
    case ContactState::Locked: return "locked";
  }
  return "?";
}

std::string collide(const BlockSystem& s, ContactDetection& detection, const std::vector<std::pair<int, int>>& pairs,
                    ContactSet& contacts) {
  const ContactShapes& shapes = detection.shapes;
  const CollideSettings& settings = detection.settings;
  std::vector<Manifold>& geometry = detection.geometry;
  // Pass 1, the geometry of every pair of boxes; pass 2 builds the manifolds of the pairs
  // that touch, in place (no full manifold per pair of boxes, no copy).
  const long n = static_cast<long>(pairs.size());
  geometry.resize(pairs.size());
  const auto [support, rest, corner_held] =
      read_supports(s, contacts.manifolds, settings.linear_slop, settings.gravity);
  // Handed out in chunks: a pair of boxes that barely overlap costs little, one whose pieces
  // touch a full manifold, and they are not spread evenly along the sorted pairs. In two
  // static halves one thread waited for the other (on Vajont section VII degraded's first
  // 10 s, busy 4.5 s against 6.7 s). Alternating the two step by step in one run, this pass
  // took 2.9 s in static halves and 2.6-2.7 s in chunks of 64 (docs/performance.md).
  // Per pair of boxes, whether its pieces touch: read below on one thread from these bytes, not
  // from the pairs' geometry (a Manifold each).
  std::vector<char> touches(pairs.size());
#pragma omp parallel for schedule(dynamic, 64) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    const auto [a, b] = pairs[k];
    const int block_a = shapes.pieces[a].block, block_b = shapes.pieces[b].block;
    Vec2 corners_a[kMaxCorners], corners_b[kMaxCorners];
    thread_local std::vector<Vec2> spill_a, spill_b;
    const std::span<const Vec2> piece_a = gather(s, shapes, a, corners_a, spill_a);
    const std::span<const Vec2> piece_b = gather(s, shapes, b, corners_b, spill_b);
    const int na = static_cast<int>(piece_a.size()), nb = static_cast<int>(piece_b.size());
    const std::span<const char> solid(shapes.solid), reflex(shapes.reflex);
    const double reach =
        settings.extra_reach.empty() ? 0.0 : settings.extra_reach[block_a] + settings.extra_reach[block_b];
    ManifoldSettings ms;
    ms.max_distance = settings.margin + reach;
    ms.linear_slop = settings.linear_slop;
    // Points deeper than this on a piece with cuts are dropped: no step moves a block that
    // far into another, so such a point is a corner read across a cut (manifold.hpp, "Solid
    // edges"). The margin (metres on Vajont) let a block nestled in the notch of a pinched
    // neighbour be read 0.28-0.33 m (6 % of its size) deep and pushed out at once, which
    // is how Vajont section V (degraded) overlapped by 3.5-3.9 % elsewhere in the mass.
    const double size = std::min(s.blocks[block_a].fixed ? 1e300 : block_size(s, block_a),
                                 s.blocks[block_b].fixed ? 1e300 : block_size(s, block_b));
    ms.max_depth = std::min(settings.margin, kCutDepthRatio * size);
    ms.flip_for_cuts = s.blocks[block_a].fixed || s.blocks[block_b].fixed;
    // Flush faces, and "beside" judged on the part near a face's line, for every pair (model
    // revision 2026-12-07.3). Until then for pairs with a fixed block only: between free
    // blocks of a packed mass many lie within eta of a neighbour's face line, and at revision
    // 2026-11-25.3 overriding the separating axis there let Vajont section V (degraded) overlap
    // by 3.9 % (the sliver and depth limits since keep it under 0.8 %). Without it a slider
    // crossing a kink of a surface of free blocks met the next block's joint face as a wall
    // (a jointed slide's surface: tests/test_ground_joints.cpp, 26-85 % of the travel lost).
    // Tried alone (2026-12-07.2) it overlapped Vajont section X by 3 %, through a sliver piece
    // of the old convex decomposition (convex_pieces.cpp), which this revision also mends.
    ms.flush_faces = true;
    // Within half the thinner piece's width: a 200 m block resting on a fixed plate 1 m thick
    // (eta 4 m) had the plate's top, end and bottom faces grown into one face along its
    // diagonal (grow_face's flatness is eta / 4), read itself 0.5 m above it and fell freely
    // for 0.2 s at t = 0, on both solvers.
    const double fixed_width = std::min(s.blocks[block_a].fixed ? shapes.pieces[a].width : 1e300,
                                        s.blocks[block_b].fixed ? shapes.pieces[b].width : 1e300);
    ms.flush_tolerance = std::min(settings.flush_ratio * size, kFlushWidthShare * fixed_width);
    ms.proud_floor = std::max(size < 1e299 ? kProudRatio * size : 0.0, settings.sag);
    ms.support_a = support[block_a];
    ms.support_b = support[block_b];
    ms.rest_a = rest[block_a];
    ms.rest_b = rest[block_b];
    const int first_a = shapes.pieces[a].first, first_b = shapes.pieces[b].first;
    const std::span<const int> corners(shapes.corners);
    ms.held_a = {corner_held, corners.subspan(first_a, na)};
    ms.held_b = {corner_held, corners.subspan(first_b, nb)};
    geometry[k] = collide_polygons(piece_a, piece_b, ms,
                                   solid.subspan(first_a, na), solid.subspan(first_b, nb), reflex.subspan(first_a, na),
                                   reflex.subspan(first_b, nb));
    touches[k] = geometry[k].point_count > 0;
  }
  std::vector<int> touching;
  for (long k = 0; k < n; ++k)
    if (touches[k]) touching.push_back(static_cast<int>(k));

  std::vector<ContactManifold>& previous = detection.previous;
  previous.swap(contacts.manifolds);
  std::vector<ContactManifold>& manifolds = contacts.manifolds;
  // Cleared in the parallel loop rather than on one thread before it: about 12 MB of
  // manifolds a step on Vajont section VII (docs/performance.md).
  manifolds.resize(touching.size());
  const long t = static_cast<long>(touching.size());
  std::vector<int> free_on_fixed(touching.size());  // drop_shared_corners
  bool no_interface = false;                        // a pair touches with no interface defined
#pragma omp parallel for schedule(static) reduction(|| : no_interface) if (t >= kParallelMinimum)
  for (long j = 0; j < t; ++j) {
    const int k = touching[j];
    const auto [a, b] = pairs[k];
    const Manifold& m = geometry[k];
    ContactManifold& out = manifolds[j];
    out = ContactManifold{};
    out.piece_a = a;
    out.piece_b = b;
    out.block_a = shapes.pieces[a].block;
    out.block_b = shapes.pieces[b].block;
    out.interface = s.interface_between(out.block_a, out.block_b);
    no_interface = no_interface || out.interface < 0;
    const bool fixed_a = s.blocks[out.block_a].fixed, fixed_b = s.blocks[out.block_b].fixed;
    free_on_fixed[j] = fixed_a == fixed_b ? -1 : fixed_a ? out.block_b : out.block_a;
    out.normal = m.normal;
    out.tangent = Vec2(m.normal.y(), -m.normal.x());
    out.point_count = m.point_count;
    const ContactManifold* old = previous_of(previous, a, b);
    for (int q = 0; q < m.point_count; ++q) {
      const ManifoldPoint& mp = m.points[q];
      ContactPoint& p = out.points[q];
      p.id = mp.id;
      p.anchor = mp.point;
      p.separation = mp.separation;
      p.ra = mp.point - s.blocks[out.block_a].centroid;
      p.rb = mp.point - s.blocks[out.block_b].centroid;
      p.owner = shapes.corners[shapes.pieces[mp.owner == 0 ? a : b].first + mp.vertex];
    }
    carry_over(old, settings.linear_slop, settings.margin, out);
    // The sliding face: the overriding block's face in this manifold, through this interface.
    out.overriding_block = overriding_block(s, out, settings.gravity);
    const bool on_a = out.overriding_block == out.block_a;
    const int face = (m.reference == 0) == on_a ? m.reference_face : m.incident_face;
    out.face_key = slip_history_key(shapes.corners[shapes.pieces[on_a ? a : b].first + face], out.interface);
    // The last step's history of this face, when the same pair touched through it
    // (assign_histories() finds the others by key).
    out.history = old && old->face_key == out.face_key ? old->history : -1;
    // Cohesion and tension act along the face the two points share, half each; a single
    // point (corner on corner, corner on face) has no bonded length.
    const double shared = m.point_count == 2 ? (m.points[0].point - m.points[1].point).norm() : 0.0;
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = out.points[q];
      p.bond_length = 0.5 * shared;
      if (settings.first_step && out.interface >= 0) {
        // Formed afresh (at t = 0, after the quiet start): nothing of it has worn yet.
        p.bonded = forms_bond(s.interfaces[out.interface], p.separation, settings.linear_slop);
        p.bond_slip = p.bond_opening = 0.0;
      }
    }
  }
  drop_shared_corners(manifolds, free_on_fixed, settings.linear_slop);
  assign_histories(s, contacts, detection.previous_histories);
  predict_first_slip(s, contacts, settings.slip_step);
  std::string problem;
  for (size_t k = 0; no_interface && k < manifolds.size(); ++k) {
    const ContactManifold& m = manifolds[k];
    if (m.interface >= 0) continue;
    problem = "blocks '" + s.block_names[m.block_a] + "' and '" + s.block_names[m.block_b] + "' (groups '" +
              s.group_names[s.blocks[m.block_a].group] + "', '" + s.group_names[s.blocks[m.block_b].group] +
              "') touch but no interface is defined for that pair: add a contacts entry or default_interface";
    break;
  }
  return problem;
}

}  // namespace ddafit
