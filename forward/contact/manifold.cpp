#include "forward/contact/manifold.hpp"

#include <algorithm>
#include <cmath>

#include "forward/contact/face_axes.hpp"

namespace ddafit {
namespace {
using namespace face_axes;  // the separating axes and flush rules (face_axes.hpp)

// Faces closer to parallel than sin^2(angle) = 1e-10 (about 1e-5 rad) are treated as
// parallel: the closest-point formula divides by sin^2 and loses every digit there.
constexpr double kParallel = 1e-10;

// "Proud edges" (manifold.hpp) acts on overlaps up to this many times h = max(linear_slop,
// proud_floor) deep: a corner resting up to the slop deep that meets an edge up to h proud.
constexpr double kProudWindow = 2.0;

// Unit outward normal of the reference face grown from edge `edge` of `ref`.
Vec2 face_normal(const Shape& ref, int edge, double flat) {
  const Face f = grow_face(ref, edge, flat);
  return outward((ref.at(f.last) - ref.at(f.first)).normalized());
}

// When the closest points of segments [p1, q1] and [p2, q2] are an end of each, which
// ends (0 = p, 1 = q); {-1, -1} when a closest point is inside a segment.
struct Ends {
  int on1 = -1;
  int on2 = -1;
};

Ends closest_ends(const Vec2& p1, const Vec2& q1, const Vec2& p2, const Vec2& q2) {
  const Vec2 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double aa = d1.squaredNorm(), ee = d2.squaredNorm(), bb = d1.dot(d2);
  const double cc = d1.dot(r), ff = d2.dot(r), denominator = aa * ee - bb * bb;
  if (denominator <= kParallel * aa * ee) {
    // Parallel: if the faces overlap along their common direction the closest points are
    // not unique and the contact is face to face (even across a gap); otherwise the
    // nearest two ends. Positions of p2 and q2 along segment 1, in its length units:
    const double s_p2 = -cc / aa, s_q2 = (bb - cc) / aa;
    if (std::max(s_p2, s_q2) < 0.0) return {0, s_p2 > s_q2 ? 0 : 1};
    if (std::min(s_p2, s_q2) > 1.0) return {1, s_p2 < s_q2 ? 0 : 1};
    return {};
  }
  // Closest points of the two lines, then clamped into the segments (s on 1, t on 2).
  double s = std::clamp((bb * ff - cc * ee) / denominator, 0.0, 1.0);
  double t = (bb * s + ff) / ee;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-cc / aa, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((bb - cc) / aa, 0.0, 1.0);
  }
  if ((s == 0.0 || s == 1.0) && (t == 0.0 || t == 1.0)) return {s == 1.0, t == 1.0};
  return {};
}

// The face contact of reference face `rf` of `ref` against incident face `incf` of `inc`:
// the incident face cut to the slab between the lines through the reference face's ends
// along the normal. A cut end is the reference polygon's corner pressing on the incident
// face; an uncut end is the incident polygon's corner. An incident face wholly beside the
// slab gives its end nearest the slab (overlapping corners, or round-off). Points deeper
// than `max_depth` are dropped when `limit_depth` (see "Solid edges" in manifold.hpp).
void clip_face_contact(const Shape& ref, const Face& rf, const Shape& inc, const Face& incf, int ref_owner,
                       const ManifoldSettings& settings, bool limit_depth, const bool reflex_end[2], Manifold& m) {
  struct Candidate {
    Vec2 at;
    int owner, vertex, other;
  };
  const int inc_owner = 1 - ref_owner;
  const Vec2 v11 = ref.at(rf.first), v12 = ref.at(rf.last);
  const double ref_length = (v12 - v11).norm();
  const Vec2 tangent = (v12 - v11) / ref_length, normal = outward(tangent);
  const Vec2 v21 = inc.at(incf.first), v22 = inc.at(incf.last);
  Candidate c[2];
  int count = 0;
  const double u21 = (v21 - v11).dot(tangent), u22 = (v22 - v11).dot(tangent);
  const Candidate inc_first{v21, inc_owner, incf.first, rf.first};
  const Candidate inc_last{v22, inc_owner, incf.last, rf.first};
  if (u21 <= 0.0 || u22 >= ref_length) {
    // Only a corner within the margin of the face's end, along the face: one further off
    // is no contact of this face, and its depth from the face's line extended is meaningless
    // (the thin piece of a pinched Vajont block, section V, read a corner 2.2 m past the end
    // of a neighbour's face 0.57 m "deep" below that face's line).
    const double beyond = u21 <= 0.0 ? -u21 : u22 - ref_length;
    if (beyond < settings.max_distance) c[count++] = u21 <= 0.0 ? inc_first : inc_last;
  } else {
    // The incident face runs against the tangent: v22 is the end near v11. Past an end of
    // the face that is a reflex corner the face's polygon continues in another face (the
    // floor at the foot of a bank): an incident corner there within the margin is itself
    // the point, at its distance from the face's line, the speculative contact of a corner
    // sliding along that other face into this one (manifold.hpp, "Reflex corners").
    if (u22 < 0.0 && !(reflex_end[0] && -u22 < settings.max_distance)) {
      c[count++] = {v22 + (-u22 / (u21 - u22)) * (v21 - v22), ref_owner, rf.first, incf.first};
    } else {
      c[count++] = inc_last;
    }
    if (u21 > ref_length && !(reflex_end[1] && u21 - ref_length < settings.max_distance)) {
      c[count++] = {v21 + ((u21 - ref_length) / (u21 - u22)) * (v22 - v21), ref_owner, rf.last, incf.first};
    } else {
      c[count++] = inc_first;
    }
  }
  const double max_depth = settings.max_depth < 0.0 ? settings.max_distance : settings.max_depth;
  for (int k = 0; k < count; ++k) {
    const double separation = (c[k].at - v11).dot(normal);
    // Deeper than the margin is not a contact a step can make: with cuts (solid edges
    // only as reference faces) it is a corner read across a cut, inside the block.
    if (!(separation < settings.max_distance) || (limit_depth && !(separation > -max_depth))) continue;
    m.points[m.point_count++] = {ref.origin + c[k].at - 0.5 * separation * normal, separation,
                                 manifold_id(c[k].owner, c[k].vertex, c[k].other, false), c[k].owner, c[k].vertex};
  }
  m.normal = ref_owner == 1 ? Vec2(-normal) : normal;  // always from a to b
  m.reference = ref_owner;
  m.reference_face = rf.first;
  m.incident_face = incf.first;
}


// Beside a flush face (manifold.hpp): the incident face, the face of `inc` most nearly
// opposite to the reference face, lies wholly beyond one end of it along its line, and the
// next face of `inc` from the end nearest the reference face runs under it. The contact is
// that next face: the first lies beside the reference face, a neighbour along its line. A
// slider just past a convex kink of a fixed piece, its base along the face before the kink,
// lies against its base's line through the kink's corner; the face before the kink, beside
// the base, gave a point at the corner, behind the slider (tests/test_flush_neighbours.cpp).
Incident under_flush_face(const Shape& ref, int ref_edge, const Shape& inc, std::span<const char> solid,
                          Incident incident, double flat) {
  const Face rf = grow_face(ref, ref_edge, flat), incf = grow_face(inc, incident.edge, flat);
  const Vec2 v11 = ref.at(rf.first), span = ref.at(rf.last) - v11;
  const double length = span.norm();
  const Vec2 tangent = span / length, normal = outward(tangent);
  const auto u = [&](int k) { return tangent.dot(inc.at(k) - v11); };
  // The incident face runs against the tangent: from incf.first (far along) to incf.last.
  int next = -1;
  if (u(incf.first) <= 0.0) next = (incf.first + inc.n - 1) % inc.n;  // beside the first end
  if (u(incf.last) >= length) next = incf.last;                         // beside the last end
  if (next < 0 || (!solid.empty() && !solid[static_cast<size_t>(next)])) return incident;
  const Vec2 edge = inc.at(next + 1) - inc.at(next);
  const double facing = normal.dot(outward(edge)) / edge.norm();
  const double lo = std::min(u(next), u(next + 1)), hi = std::max(u(next), u(next + 1));
  if (!(facing < 0.0) || hi <= 0.0 || lo >= length) return incident;
  return {next, facing};
}

}  // namespace

Manifold collide_polygons(std::span<const Vec2> a, std::span<const Vec2> b, const ManifoldSettings& settings,
                          std::span<const char> a_solid, std::span<const char> b_solid,
                          std::span<const char> a_reflex, std::span<const char> b_reflex) {
  Manifold m;
  const double max_distance = settings.max_distance, linear_slop = settings.linear_slop;
  if (a.size() < 3 || b.size() < 3) return m;
  const Vec2 origin = a[0];
  ShapeStore store_a, store_b;
  const Shape sa = make_shape(a, origin, store_a), sb = make_shape(b, origin, store_b);
  double extent = 0.0;
  for (int k = 0; k < sa.n; ++k) extent = std::max(extent, sa.at(k).cwiseAbs().maxCoeff());
  for (int k = 0; k < sb.n; ++k) extent = std::max(extent, sb.at(k).cwiseAbs().maxCoeff());
  const double tiny = 1e-12 * extent;  // an edge shorter than round-off has no direction

  // Separating axes of both polygons; apart along any axis by more than the margin
  // means no contact at all.
  // Edges whose vertices lie within `flat` of one line make one face (grow_face). A quarter
  // of the flush tolerance: the mesher leaves vertices 0.5 mm off straight on 8 m Vajont
  // blocks (where joints met a side), and a face split there gave a sliver lying along it
  // contact on one half only: its tip sank 18 cm into the other half.
  const double eta = settings.flush_tolerance, flat = std::max(1e-3 * linear_slop, 0.25 * eta);
  const AxisLimits limits_a{tiny, max_distance, eta, flat, settings.flush_faces, settings.support_a, settings.support_b,
                            settings.held_b};
  const Axis axis_a = best_axis(sa, a_solid, a_reflex, sb, b_solid, b_reflex, limits_a);
  if (axis_a.apart > max_distance) return m;
  const AxisLimits limits_b{tiny, max_distance, eta, flat, settings.flush_faces, settings.support_b, settings.support_a,
                            settings.held_a};
  const Axis axis_b = best_axis(sb, b_solid, b_reflex, sa, a_solid, a_reflex, limits_b);
  if (axis_a.edge < 0 && axis_b.edge < 0) return m;
  if (axis_b.apart > max_distance) return m;
  const auto cut_in = [](std::span<const char> solid) {
    return std::find(solid.begin(), solid.end(), char{0}) != solid.end();
  };
  const bool has_cuts = cut_in(a_solid) || cut_in(b_solid);
  // A cut is no face, but it still separates: a polygon wholly beyond a piece's cut lies
  // over the block's other pieces (or outside the block next to them) and cannot overlap
  // this piece; its contact with the block is the other pieces'. Without this test a
  // small block sliding on one piece past the reflex corner where a cut starts was read
  // 0.62 m "deep" in the neighbouring piece (no solid axis separated them) and stopped
  // Vajont sections VI, IX and X with overlaps of 25 % of a block that did not exist.
  // Not for a polygon that no solid axis finds deeper than a sliver (kSliverDepth x eta):
  // beyond a cut but within the margin of the face that starts where the cut meets the
  // surface, it is the speculative contact with that face. A block sliding along a valley
  // floor towards a bank lies beyond the cut from the bank's foot (for a bank at 30 deg the
  // cut runs down under the floor) and met the bank only once its corner was in it.
  const bool overlapped = std::max(axis_a.apart, axis_b.apart) <= -kSliverDepth * eta;
  if (has_cuts && overlapped &&
      (cut_separates(sa, sb, tiny, a_solid, linear_slop) || cut_separates(sb, sa, tiny, b_solid, linear_slop)))
    return m;

  // Kink corners (manifold.hpp): the face that turns up at a corner ahead on the line of the
  // face a free polygon rests on is the contact, the corner a reflex end of it. Only while the
  // two are apart: blocks side by side on one surface touch at their joint, their corners at one
  // place, and there the separating axis reads them.
  const bool apart = std::max(axis_a.apart, axis_b.apart) > 0.1 * linear_slop;
  for (const bool b_rests : {false, true}) {
    const Vec2& rest = b_rests ? settings.rest_b : settings.rest_a;
    if (!apart || !(eta > 0.0)) break;
    if (rest.isZero()) continue;
    const Shape& rests = b_rests ? sb : sa;
    const Shape& other = b_rests ? sa : sb;
    const std::span<const char> rests_solid = b_rests ? b_solid : a_solid, other_solid = b_rests ? a_solid : b_solid;
    const KinkCorner kink = kink_corner(rests, rests_solid, rest, other, other_solid, eta, flat, max_distance);
    if (kink.corner < 0) continue;
    const Face rf = grow_face(other, kink.face, flat);
    const Incident incident = incident_edge(rests, rests_solid, face_normal(other, kink.face, flat), tiny);
    // The resting polygon's corner at its face's end meets the kink: its face there, no other.
    const Face incf = incident.edge < 0 ? Face{} : grow_face(rests, incident.edge, flat);
    if (incident.edge < 0 || (incf.first != kink.end && incf.last != kink.end)) continue;
    const bool reflex_end[2] = {rf.first == kink.corner, rf.last == kink.corner};
    Manifold out;
    clip_face_contact(other, rf, rests, incf, b_rests ? 0 : 1, settings, has_cuts, reflex_end, out);
    if (out.point_count > 0) return out;
  }

  // Flush neighbours: two polygons along one surface line touch only at a corner sliver.
  // Only while their overlap is one, no longer and no deeper than eta: not when one lies
  // along another face of the other (rides), nor when they overlap deeper than
  // kSliverDepth x eta along every axis of both. Otherwise a block resting on a face next
  // to a slight kink of its polygon (the two faces not grown into one) lies beside the
  // face across the kink and had no contact: on Vajont section V (reference) a 125 m2
  // block lay beside the end of a bedrock face within eta (22 cm for it) and sank 20 cm
  // into the bedrock piece's next face unseen.
  const bool sliver =
      !axis_a.rides && !axis_b.rides && std::max(axis_a.apart, axis_b.apart) > -kSliverDepth * eta;
  if ((axis_a.flush_beside || axis_b.flush_beside) && sliver) return m;

  // Flush faces (manifold.hpp): a polygon lying against the line of a face (within eta),
  // not beside it, touches that face, whatever the separating axis says; of two such
  // faces, the one whose line it lies closer to (least |gap|). The reference polygon
  // otherwise: a unless b's axis is clearly better, so that two equally good axes do not
  // swap the reference (and the point ids) from one call to the next.
  const bool flush_face = axis_a.flush_edge >= 0 || axis_b.flush_edge >= 0;
  int edge_a = flush_face ? axis_a.flush_edge : axis_a.edge;
  int edge_b = flush_face ? axis_b.flush_edge : axis_b.edge;
  const auto rank = [](const Axis& x) { return FlushRank{x.flush_slides, x.flush_support, x.flush_gap}; };
  const bool better_b = flush_face ? axis_b.flush_edge >= 0 &&
                                         flush_better(rank(axis_b), rank(axis_a), eta, 0.1 * linear_slop)
                                   : axis_b.separation > axis_a.separation + 0.1 * linear_slop;
  bool flip = edge_a < 0 || (edge_b >= 0 && better_b);
  // Proud edges (manifold.hpp): a corner just across a joint whose far block stands up to
  // proud_depth proud overlaps it along its own face and along the joint's face alike; the
  // face along which the two blocks were held up in the last step is the contact. That face
  // may overlap by the window, however little the joint's face does (proud_face's depth):
  // the corner rests up to h deep in the blocks it is held up by, and the edge stands up to h
  // proud of those.
  const double deepest = std::max(axis_a.separation, axis_b.separation);
  const double proud_depth = std::max(linear_slop, settings.proud_floor);
  if (!flush_face && deepest <= 0.0 && deepest >= -kProudWindow * proud_depth) {
    const ProudFace proud_a = proud_face(sa, a_solid, sb, limits_a, kProudWindow * proud_depth);
    const ProudFace proud_b = proud_face(sb, b_solid, sa, limits_b, kProudWindow * proud_depth);
    const bool from_b = proud_b.support > proud_a.support;
    const ProudFace& proud = from_b ? proud_b : proud_a;
    const auto chosen_support = [&] {
      return support_agreement(face_normal(flip ? sb : sa, flip ? edge_b : edge_a, flat), flip ? limits_b : limits_a);
    };
    if (proud.edge >= 0 && proud.support > chosen_support() + kSupportTie) {
      (from_b ? edge_b : edge_a) = proud.edge;
      flip = from_b;
    }
  }
  const auto incident_for = [&](bool f) {
    return incident_edge(f ? sa : sb, f ? a_solid : b_solid, face_normal(f ? sb : sa, f ? edge_b : edge_a, flat), tiny);
  };
  Incident incident = incident_for(flip);
  if (incident.edge < 0) return m;
  if (flush_face) incident = under_flush_face(flip ? sb : sa, flip ? edge_b : edge_a, flip ? sa : sb,
                                              flip ? a_solid : b_solid, incident, flat);
  const auto reflex_at = [&](int owner, int vertex) {
    const std::span<const char> r = owner == 0 ? a_reflex : b_reflex;
    return !r.empty() && r[static_cast<size_t>(vertex)] != 0;
  };
  // Cut ends (manifold.hpp): the incident piece's corner deepest across the reference face
  // (of `ref_edge` on polygon `f ? b : a`) is a convex corner of its block where a cut ends.
  const auto cut_end_under = [&](bool f, int ref_edge) {
    const Shape& ref = f ? sb : sa;
    const Shape& inc = f ? sa : sb;
    const std::span<const char> solid = f ? a_solid : b_solid, reflex = f ? a_reflex : b_reflex;
    if (solid.empty() || reflex.empty()) return false;  // no cuts, or no corners known to be convex
    const Vec2 normal = face_normal(ref, ref_edge, flat), p0 = ref.at(ref_edge);
    int deepest_corner = 0;
    for (int k = 1; k < inc.n; ++k)
      if (normal.dot(inc.at(k) - p0) < normal.dot(inc.at(deepest_corner) - p0)) deepest_corner = k;
    const int before = (deepest_corner + inc.n - 1) % inc.n;
    const bool on_cut = !solid[static_cast<size_t>(deepest_corner)] || !solid[static_cast<size_t>(before)];
    return on_cut && !reflex_at(f ? 0 : 1, deepest_corner);
  };
  // An incident piece whose faces towards the reference face are all cuts (facing > 0)
  // offers no face there: across its cuts lie the block's other pieces. The contact, if
  // any, is then one of its solid faces against the other polygon: take the other
  // polygon's best axis as the reference, or no contact if that fails the same way.
  // Without this, a toe block on Vajont section VII whose corner sat in the valley corner
  // read the opposite bank's face as turned away from it, got no point, and went into the
  // bank (the first axis was its own face; the bank piece's side facing it was a cut).
  if (settings.flip_for_cuts && incident.facing > 0.0) {
    if (cut_end_under(flip, flip ? edge_b : edge_a)) return m;
    // The other polygon's flush face, else its best axis: a toe block lying against the
    // line of its own face through the foot of Vajont section VII's bank (which has no
    // face the block lies against) met only the bank piece's cut, and lost the contact.
    int& other = flip ? edge_a : edge_b;
    if (other < 0) other = flip ? axis_a.edge : axis_b.edge;
    if (other < 0) return m;
    flip = !flip;
    incident = incident_for(flip);
    if (incident.edge < 0 || incident.facing > 0.0) return m;
  }
  // The contact with the reference face of polygon `flip ? b : a` and the incident face.
  // `hollow` is set when the closest feature of the incident polygon is a reflex corner.
  bool hollow = false;
  const auto contact = [&](bool f, const Incident& incident_face) {
    Manifold out;
    const Shape& ref = f ? sb : sa;
    const Shape& inc = f ? sa : sb;
    const int ref_owner = f ? 1 : 0, inc_owner = 1 - ref_owner;
    const Face rf = grow_face(ref, f ? edge_b : edge_a, flat);
    const Face incf = grow_face(inc, incident_face.edge, flat);
    // Apart, corner facing corner: one point, normal along the line joining the corners.
    // The gap exceeds 0.1 x linear_slop here, so that line has a well-defined direction.
    // Not against a flush face: a corner arriving at the joint of a concave kink heads
    // straight at the next block's corner, and the line joining them points back. Not at a
    // reflex corner (manifold.hpp): a block's corner arriving along a valley floor at the
    // foot of a bank faced the bank piece's end, and the level line joining them stopped
    // it as a wall would instead of the bank's face turning it up the slope.
    if (!flush_face && std::max(axis_a.apart, axis_b.apart) > 0.1 * linear_slop) {
      const Ends ends = closest_ends(ref.at(rf.first), ref.at(rf.last), inc.at(incf.first), inc.at(incf.last));
      // closest_ends sets both ends or neither (on1 < 0: a closest point inside a face).
      const int ref_vertex = ends.on1 == 1 ? rf.last : rf.first;
      const int inc_vertex = ends.on2 == 1 ? incf.last : incf.first;
      if (ends.on1 >= 0 && reflex_at(inc_owner, inc_vertex)) hollow = true;  // the face contact, then re-flipped
      if (ends.on1 >= 0 && !reflex_at(inc_owner, inc_vertex) && !reflex_at(ref_owner, ref_vertex)) {
        const Vec2 corner = ref.at(ref_vertex), d = inc.at(inc_vertex) - corner;
        const double distance = d.norm();
        if (!(distance < max_distance)) return out;
        out.normal = (f ? Vec2(-d) : d) / distance;
        out.points[0] = {origin + corner + 0.5 * d, distance,
                         manifold_id(inc_owner, inc_vertex, ref_vertex, true), inc_owner, inc_vertex};
        out.point_count = 1;
        out.reference = ref_owner;
        out.reference_face = rf.first;
        out.incident_face = incf.first;
        return out;
      }
    }
    const bool reflex_end[2] = {reflex_at(ref_owner, rf.first), reflex_at(ref_owner, rf.last)};
    clip_face_contact(ref, rf, inc, incf, ref_owner, settings, has_cuts, reflex_end, out);
    for (int k = 0; k < out.point_count; ++k)
      hollow = hollow || (out.points[k].owner == inc_owner && reflex_at(inc_owner, out.points[k].vertex));
    return out;
  };
  m = contact(flip, incident);
  // Reflex corners (manifold.hpp): a point at a reflex corner of the incident polygon is
  // that polygon's hollow pressing on the reference face, which no body can do; the
  // contact there is the incident block's face against the other's corner. A toe block
  // whose corner had passed the foot of a vertical bank was pushed off the foot's "corner"
  // along its own leaning face, down and back, instead of out of the bank's face.
  if (!hollow) return m;
  int& other = flip ? edge_a : edge_b;
  if (other < 0) other = flip ? axis_a.edge : axis_b.edge;
  if (other < 0) return m;
  const Incident turned = incident_for(!flip);
  if (turned.edge < 0 || turned.facing > 0.0) return m;
  // The first reading stays when the other face gives no point (within the margin and the
  // depth kept): a contact read at a hollow is better than none.
  const Manifold other_face = contact(!flip, turned);
  return other_face.point_count > 0 ? other_face : m;
}

}  // namespace ddafit
