// Contact manifold between two convex polygons: the one or two points, with a shared
// normal, at which both solvers apply non-penetration and friction (docs/theory.md §3).
// The idea comes from Box2D v3's manifold (separating axis, reference face, clipping) and
// its smooth chain segments (ghost collisions); the code is our own.
#pragma once

#include <cstdint>
#include <span>

#include "forward/scene.hpp"

namespace ddafit {

struct ManifoldPoint {
  Vec2 point = Vec2::Zero();   // world position: midway between the incident vertex and the reference face
  double separation = 0.0;     // along the normal, m; negative = penetration
  std::uint32_t id = 0;        // feature key: equal ids in successive calls mean the same pair of features
  int owner = -1;              // 0 if the point sits on a vertex of polygon a, 1 if of polygon b
  int vertex = -1;             // index of that vertex in its polygon
};

struct Manifold {
  Vec2 normal = Vec2::Zero();  // unit, pointing from a towards b
  int point_count = 0;         // 0, 1 or 2
  ManifoldPoint points[2];
  // The two faces in contact: the reference face (whose normal is the contact normal) on
  // polygon `reference` (0 = a, 1 = b) and the incident face on the other, each named by
  // the index of its first vertex (a face is an edge grown over collinear neighbours).
  int reference = 0;
  int reference_face = -1;
  int incident_face = -1;
};

// Layout of ManifoldPoint::id. A vertex-face point: bit 30 = owner, bits 15-29 = the
// owner's vertex, bits 0-14 = first edge of the other polygon's face (the face is that
// edge plus any collinear edges after it). A vertex-vertex point additionally sets bit 31
// and stores the other polygon's vertex in bits 0-14. The key does not depend on which
// polygon was the reference, so it survives the reference flipping between a and b.
// Polygons are limited to 32768 vertices.
constexpr std::uint32_t kManifoldIdVertexVertex = 1u << 31;
constexpr std::uint32_t manifold_id(int owner, int vertex, int other_feature, bool vertex_vertex) {
  return (vertex_vertex ? kManifoldIdVertexVertex : 0u) | (static_cast<std::uint32_t>(owner) << 30) |
         (static_cast<std::uint32_t>(vertex) << 15) | static_cast<std::uint32_t>(other_feature);
}

// The faces a polygon's corners touched in the last step, for "Flush faces": normal[ids[k]] is
// the normal (unit, into the polygon's block) of the face corner k touched, where the faces it
// touched agree; zero for a corner that touched nothing. Empty: none known.
struct CornerHolds {
  std::span<const Vec2> normal;  // per vertex id (BlockSystem::vertices)
  std::span<const int> ids;      // the polygon's corners' vertex ids, in its order
  Vec2 at(int k) const {
    return ids.empty() ? Vec2::Zero() : normal[static_cast<size_t>(ids[static_cast<size_t>(k)])];
  }
};

struct ManifoldSettings {
  // m, > 0: points are kept while their separation is below this (the speculative margin).
  double max_distance = 0.0;
  // m, small (e.g. 1e-4 x block size): tolerance of the separating-axis comparisons; b
  // becomes the reference polygon only when its axis separates by more than a's by
  // 0.1 x linear_slop (a bias against flipping between equal axes).
  double linear_slop = 0.0;
  // m: where a piece has cuts, points are kept only while their overlap is below this
  // (< 0: max_distance); see "Solid edges".
  double max_depth = -1.0;
  // See "Solid edges": let the other polygon's face be the reference when the incident
  // piece turns only cuts towards the reference face.
  bool flip_for_cuts = true;
  // m, >= 0: the flush tolerance eta of "Flush neighbours"; 0 turns the rule off.
  double flush_tolerance = 0.0;
  // m, >= 0: "Proud edges" reads edges up to h = max(linear_slop, proud_floor) proud, in
  // overlaps up to 2h deep.
  double proud_floor = 0.0;
  // "Flush faces", and "Flush neighbours" judged on the part of a polygon near the line;
  // off, the whole polygon must lie beside a face and the separating axis decides the rest.
  bool flush_faces = true;
  // Unit or zero: the direction each polygon's block was held up from in the last step (the
  // mean normal of its touching contacts that push it up, from its supports towards it);
  // ranks flush faces.
  Vec2 support_a = Vec2::Zero(), support_b = Vec2::Zero();
  // Unit or zero: the normal of the surface each polygon's block rests on, for "Kink corners"
  // (supports.hpp); zero for a fixed block, or one held by faces that disagree.
  Vec2 rest_a = Vec2::Zero(), rest_b = Vec2::Zero();
  // The faces each polygon's corners touched in the last step: rank flush faces ("Flush faces").
  CornerHolds held_a, held_b;
};

// Convex counter-clockwise polygons a and b. When the polygons are apart by more than
// 0.1 x linear_slop and the closest features of the reference and incident faces are two
// vertices, the manifold has one point with the normal along the line joining the two corners
// (vertex-vertex branch) -- this is what makes corner-to-corner contact have a single normal.
//
// Faces: consecutive edges whose vertices lie within 1e-3 x linear_slop of one line act as
// one face (reference or incident), so a straight vertex in the middle of a side never
// halves the contact; the points sit at the face's end corners.
// Parallel faces: when the two faces are parallel (within 1e-5 rad) and overlap along
// the face, the contact is a face contact (two clipped points) even if the gap is open;
// only faces that do not overlap give the vertex-vertex point.
//
// Flush neighbours (the internal-edge or "ghost collision" rule). When one polygon lies
// against the line of a face T of the other -- its deepest point within eta = flush_tolerance
// of T's line, on either side -- and its part within eta of that line lies wholly beside T
// along the line, the two are neighbours along one surface: they can only overlap in a
// corner sliver no deeper and no longer than eta, and the manifold is empty. Only while
// the overlap is such a sliver: a polygon that lies along another face of the other (its
// part within eta / 10 of that face's line reaches more than eta along it), or a pair
// that overlaps deeper than eta / 4 along every axis of both, keeps its manifold (it rests
// on, or has sunk into, a face nearly collinear with T); nor a polygon whose face most
// nearly opposite to T runs under T for more than eta (face to face: a block tilted over a
// shorter one, its line passing near that one's far corner; face_axes.hpp). This is what lets a block slide
// across a joint between two blocks whose faces are flush (the slope surface, a row of
// blocks): before it crosses, its leading corner sits just below the next block's corner
// (by its own resting overlap), and the separating axis alone would take the joint face
// (or the slider's front face) as the contact face and throw the block back. Once it has
// crossed, the next block's face lies under it and the separating axis takes that face. It
// needs no knowledge of the block the slider rests on: the slider lies along the next
// block's face line, beside the face. A real step is higher than eta: the slider then reaches
// below T's line by the step's height, the rule does not apply, and the step's face stops it. A
// block above T by more than eta (a step down, a block in flight) is no neighbour either, and
// keeps its speculative contacts. A kink of the surface at the joint is covered too: at a concave kink
// the slider lies along the next face's line, at a convex one the next block lies along the
// slider's face. (Box2D's smooth segments reach the same answer with each segment's
// neighbours, its ghost vertices; Shi's entrance rule would take the joint face, since the
// slider's corner, below the surface by its overlap, crosses the joint's line first.)
//
// Flush faces: a polygon against the line of a face it is not beside (its corner has crossed
// the joint, or heads for it at a concave kink) touches that face: it is the reference face,
// and there is no corner-on-corner point, whose normal pointed back at such a joint. Of
// several such faces, first one whose line carries a corner of the other polygon that touched,
// in the last step, a face of the same direction (within kRestsOn; held_a, held_b), the other
// polygon not face to face with it: the face continues the surface that corner slides on.
// Then the one whose normal (from its polygon towards the other) agrees best with the supports
// of the last step (support_a, support_b: a block resting on a surface meets the next block of
// it through its face), while both corners lie within eta / 10 of their lines; else the one
// the polygon lies closer to the line of. The corner first: a 30 m slider set down at the foot
// of a 40 deg face, straddling the kink onto a floor of free blocks (its support between the
// face's normal and the floor's), had its rear corner come down the face to a joint, the next
// free block's corner 2 cm under its tilted base; ranked by the support the base was the
// contact, and its point at that corner kicked the slider up by 2.3 m/s (16 % of its run lost,
// tests/test_ground_joints.cpp). Not face to face: there both polygons' corners touch the
// other's face, and which one a point sat on was the last step's choice of reference (a row of
// blocks then swapped its references and threw a slow striker back). Beside a flush face: the
// incident face (the other polygon's most opposite) lying wholly beyond one end of the flush
// face gives way to the polygon's next face from that end, where that one runs under the flush
// face (a slider just past a convex kink of a fixed piece, whose face before the kink lies
// beside the slider's base).
//
// Proud edges: when the two polygons overlap by no more than 2h, h = max(linear_slop,
// proud_floor), along every axis (deepest separation in [-2h, 0]) and a face overlapped no
// deeper than 2h agrees clearly better (kSupportTie) with the supports of the last step than
// the separating axis's face, that face is the reference. A block on a row of free blocks presses
// the ones under it a little deeper into their own supports than the unloaded block ahead,
// whose edge then stands proud by micrometres (1.6 um for a 3 m x 1.5 m slider on 0.4 m blocks
// held by a soft contact). When the slider's corner has just crossed that joint, its front face overlaps
// the joint face by less than the proud edge overlaps its bottom, and the separating axis took
// the joint face: the two faces, parallel, made a face contact that held the slider at the
// joint for good (docs/theory.md §13). An edge that stands up to linear_slop proud is below
// the contact's resolution (the substep solver pushes out only overlaps deeper than the slop);
// proud_floor keeps h at a few micrometres a metre of block where a small displacement limit
// makes the slop smaller than such an edge. A real step (higher than 2h) still stops the block:
// its top face lies beyond the window. The window is 2h, not h, because blocks at rest overlap
// their supports by up to the slop before the push-out acts, and a corner that rests that deep
// can meet a proud edge besides; for the same reason the face may overlap by up to 2h however
// little the joint's face does. Until model revision 2026-12-05.1 it had to lie within h of the
// joint's face's overlap: a 1 x 0.5 m slider on 0.1 m cubes at 2 ms x 4, 9.9 um across a joint
// onto a cube standing proud of the loaded ones, overlapped the cube's top by 51 um (h 29.5 um),
// met its rear face instead and was thrown off the row (tests/test_free_row.cpp). Where four blocks of two
// layers meet at one corner on a joint leaning through both (model revision 2026-12-03.5), the
// top layer sinks into the bottom one by its resting overlap (and shears forward on it), and the
// two blocks that touch only at that corner overlap by about the slop along the layers' face and
// a little less along the leaning joint's: with the window at h the separating axis took the
// joint's face as soon as that overlap passed h (1.565e-5 m against h = 1.560e-5 m), pushed the
// two columns of the slab apart and left it 2.2 % off seed Eq. 4 (tests/test_stacked_slider.cpp).
// Without supports (the first step) the separating axis decides.
//
// Kink corners: while the two polygons are apart, a corner of one lying on the line of a face
// the other rests on (a free polygon whose rest_a or rest_b agrees with that face's normal by more
// than kRestsOn; the corner within eta / 10 of the line, beyond the face's end by less than the
// margin), where a face of the corner's polygon turns up from the line by less than 60 deg and
// runs on away from the face's end while its other face there goes down below the line, is the
// concave kink of the surface the resting polygon slides on: that polygon's corner at the face's
// end slides along the line into the kink. The contact is the face that turns up, the corner at
// the kink a reflex end of it ("Reflex corners"): the resting polygon's face there is clipped
// against it and its corner beside the kink is a point, at its distance from that face's line.
// It is where a slide leaves the block it rests on for the next block of the surface, turning up
// at the joint (a valley floor of free blocks below a slope). The separating axis was the slider's
// front face (or the line from corner to corner), whose normal points along the slide: its
// speculative contact threw a 30 m slider arriving at 21.6 m/s at a 30 deg kink back up the slope
// (tests/test_ground_joints.cpp). The same corner of a fixed ground, where two fixed blocks meet
// at the kink, is a reflex corner of the ground (ground_joints.hpp). Not a steeper face, which is
// a wall the front face meets face to face, nor a block whose other face at the corner runs
// along the line (the surface's own block), nor one apart by no more than 0.1 x linear_slop
// (blocks side by side on one surface touch at their joint, their corners at one place).
//
// Solid edges: a convex piece of a concave block has edges that run inside the block
// (the cuts of its decomposition). Such an edge is no face: a neighbour can only be
// across it by overlapping the block's other pieces, and taking it as the reference face
// pushed neighbours into the block (0.5 m deep on Vajont section I). `a_solid[i]` /
// `b_solid[i]` false marks edge i (vertex i to i + 1) as such a cut: it is never a
// reference face or an incident face. It only counts as a separating axis to rule a
// contact out: the other polygon wholly beyond a cut gives no manifold (it lies over or
// beside the block's other pieces, whose own manifolds hold it). A piece whose edges turned
// towards the reference face are all cuts has no incident face there; with `flip_for_cuts`
// the other polygon's best face is then the reference, or there is no contact if that fails
// the same way. The narrow phase asks for it when one of the blocks is fixed (the bedrock
// and the banks, concave and cut into pieces), where a lost contact lets a block fall through
// the model; between two free blocks it made Vajont sections VIII and X overlap by a third of
// a block (2 of 20 runs failed), and there the old reading stays.
// Empty spans: every edge is solid. Where a
// polygon has cuts, points deeper than max_depth are dropped: no step moves a block
// that far into another, and such a point is a corner read across a cut, inside the
// block (one read 18 m "deep" on Vajont section I).
//
// Cut ends: with `flip_for_cuts`, when the corner of the incident piece deepest across the
// reference face is a convex corner of its block at the end of a cut, there is no contact: the
// block's surface at that corner runs on along the piece across the cut, whose manifold holds the
// other polygon. Flipped to the piece's best solid face, the contact read a fixed block's joint
// face, perpendicular to the surface, under a slider that had just crossed the joint onto the
// block's other piece: 4 cm deep along the slope, it threw the slider back and stopped it, on both
// solvers (model revision 2026-12-06.24; a block spanning a convex kink, its reflex base corner cut
// off up to the joint's corner). At a reflex corner, or where the corners are not known
// (`a_reflex`/`b_reflex` empty), the flip stands: a toe block in the valley corner meets the
// bank's face there.
//
// Reflex corners: `a_reflex[i]` / `b_reflex[i]` true marks corner i as a reflex corner of
// its block (it turns inward there, and a cut starts there). Seen from outside, no corner:
// it is never the end of a corner-to-corner contact, an incident point there hands the
// reference to the other polygon, an incident corner beside a reflex end of the reference
// face within the margin is itself the point (its distance from the face's line), and no
// Flush neighbours beside a reflex end or with a reflex corner near the face's line. A cut
// separates only a polygon overlapping deeper than a sliver (docs/theory.md §3, "Reflex
// corners": a toe block sliding into the foot of Vajont section VII's bank lost its contact
// and went into the bank at 10 ms steps).
Manifold collide_polygons(std::span<const Vec2> a, std::span<const Vec2> b, const ManifoldSettings& settings,
                          std::span<const char> a_solid = {}, std::span<const char> b_solid = {},
                          std::span<const char> a_reflex = {}, std::span<const char> b_reflex = {});

}  // namespace ddafit
