#include "forward/contact/face_axes.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace ddafit::face_axes {

bool flush_better(const FlushRank& face, const FlushRank& than, double eta, double slop) {
  if (face.slides != than.slides) return face.slides;
  const bool shallow = std::max(std::abs(face.gap), std::abs(than.gap)) <= kRideDepth * eta;
  if (shallow && std::abs(face.support - than.support) > kSupportTie) return face.support > than.support;
  return std::abs(face.gap) + slop < std::abs(than.gap);
}

Face grow_face(const Shape& p, int edge, double flat) {
  const Vec2 p0 = p.at(edge), t = (p.at(edge + 1) - p0).normalized();
  const auto on_line = [&](int from, int to, int test) {
    return std::abs(cross2(t, p.at(test) - p0)) <= flat && t.dot(p.at(to) - p.at(from)) > 0.0;
  };
  Face f{edge, (edge + 1) % p.n};
  // Leave at least two edges outside the face: beyond that the polygon has no area.
  for (int edges = 1; edges < p.n - 2; ++edges) {
    const int before = (f.first + p.n - 1) % p.n, after = (f.last + 1) % p.n;
    if (on_line(before, f.first, before)) {
      f.first = before;
    } else if (on_line(f.last, after, after)) {
      f.last = after;
    } else {
      break;
    }
  }
  return f;
}

Incident incident_edge(const Shape& inc, std::span<const char> solid, const Vec2& normal, double tiny) {
  Incident best;
  for (int j = 0; j < inc.n; ++j) {
    if (!solid.empty() && !solid[static_cast<size_t>(j)]) continue;
    const Vec2 edge = inc.at(j + 1) - inc.at(j);
    const double length = edge.norm();
    if (!(length > tiny)) continue;
    const double d = normal.dot(outward(edge)) / length;
    if (d < best.facing) best = {j, d};
  }
  return best;
}

namespace {

// A reflex corner of q's block within eta of the face's line, on either side, and within
// `reach` of the face along it (the face spans [from, to] on the tangent from p0): q's
// surface there is a hollow at the face's end, no face lying along the line.
bool hollow_near(const Shape& q, std::span<const char> q_reflex, const Vec2& p0, const Vec2& normal,
                 const Vec2& tangent, double from, double to, double eta, double reach) {
  for (int k = 0; k < q.n && !q_reflex.empty(); ++k) {
    if (!q_reflex[static_cast<size_t>(k)]) continue;
    const Vec2 x = q.at(k) - p0;
    const double u = tangent.dot(x);
    if (std::abs(normal.dot(x)) <= eta && u >= from - reach && u <= to + reach) return true;
  }
  return false;
}

// q's face most nearly opposite to the face (the incident face a contact with it would take)
// runs along the face, under it, for more than eta: q lies face to face with it, apart by
// more than eta there (else its part near the line would reach along the face), and comes
// within eta of the face's line only beyond the face's end. A slider tilted 1.6 deg over a
// 0.13 m block whose far top corner lies within eta of the slider's base line, extended, is
// such a pair: a contact of two points, not neighbours along one line (docs/verification.md,
// "Kinks of the ground"). Where q's most opposite face lies beside the face along its line
// (the face before a convex kink, under a slider that has just passed the kink), they are
// neighbours, whatever q's next face does under the face.
bool face_to_face(const Shape& q, std::span<const char> q_solid, const Vec2& normal, const Vec2& tangent,
                  const Vec2& p0, double from, double to, double eta, double tiny) {
  const Incident most = incident_edge(q, q_solid, normal, tiny);
  if (most.edge < 0 || !(most.facing < 0.0)) return false;
  const double u0 = tangent.dot(q.at(most.edge) - p0), u1 = tangent.dot(q.at(most.edge + 1) - p0);
  return std::min(to, std::max(u0, u1)) - std::max(from, std::min(u0, u1)) > eta;
}

// A corner of q within `band` of the face's line touched, in the last step, a face whose normal
// agrees with this face's (kRestsOn), and q's face most nearly opposite to it is not parallel to
// it: the face continues the surface that corner slides on (manifold.hpp, "Flush faces"). Two
// blocks face to face touch at corners of both, and which one a point sat on was the last step's
// choice of reference: ranked on it, a row of blocks swapped its references from step to step.
bool continues_a_slide(const Shape& q, std::span<const char> q_solid, const CornerHolds& held, const Vec2& p0,
                       const Vec2& normal, double band, double tiny) {
  if (held.ids.empty()) return false;
  for (int k = 0; k < q.n; ++k)
    if (std::abs(normal.dot(q.at(k) - p0)) <= band && held.at(k).dot(normal) >= kRestsOn)
      return incident_edge(q, q_solid, normal, tiny).facing > -kRestsOn;
  return false;
}

}  // namespace

Axis best_axis(const Shape& p, std::span<const char> solid, std::span<const char> reflex, const Shape& q,
               std::span<const char> q_solid, std::span<const char> q_reflex, const AxisLimits& limits) {
  const double tiny = limits.tiny, apart = limits.apart, eta = limits.eta, flat = limits.flat;
  Axis best;
  for (int i = 0; i < p.n; ++i) {
    if (!solid.empty() && !solid[static_cast<size_t>(i)]) continue;
    const Vec2 p0 = p.at(i), edge = p.at(i + 1) - p0;
    const double length = edge.norm();
    if (!(length > tiny)) continue;
    const Vec2 normal = outward(edge) / length;
    double own = 0.0, gap = kInfinity;
    for (int k = 0; k < q.n; ++k) gap = std::min(gap, normal.dot(q.at(k) - p0));
    if (eta > 0.0 && std::abs(gap) <= eta) {
      // q lies against the face's line: beside the face (its part near the line does not
      // reach along the face), or on it.
      const Vec2 tangent = edge / length;
      const Face f = grow_face(p, i, flat);
      const double from = tangent.dot(p.at(f.first) - p0), to = tangent.dot(p.at(f.last) - p0);
      const Span near = near_line_span(q, p0, normal, tangent, limits.flush_faces ? eta : kInfinity);
      // No early exit here: the rule holds only for a sliver (collide_polygons), which
      // needs every face and the separation over every axis.
      const double along = std::min(near.hi, to) - std::max(near.lo, from);
      // Beside an end of the face that is a reflex corner of p's block, q is in the mouth of
      // a hollow (the foot of a bank, where the floor meets it); with a reflex corner of its
      // own near the line, q's hollow lies against the face's end. Either way the two are
      // no neighbours along one surface but a block arriving at a face (manifold.hpp,
      // "Reflex corners").
      const int end = near.hi <= from ? f.first : f.last;
      if (along <= 0.0 && (reflex.empty() || !reflex[static_cast<size_t>(end)]) &&
          !hollow_near(q, q_reflex, p0, normal, tangent, from, to, eta, apart) &&
          !(limits.flush_faces && face_to_face(q, q_solid, normal, tangent, p0, from, to, eta, tiny)))
        best.flush_beside = true;
      // Close to the line only: a joint meeting the surface at 30 deg has the slider's
      // bottom within eta of its line for 2 eta, which is no riding along it.
      if (along > eta && !best.rides) {
        const Span close = near_line_span(q, p0, normal, tangent, kRideDepth * eta);
        best.rides = std::min(close.hi, to) - std::max(close.lo, from) > eta;
      }
      // Only a face the polygon lies close against (a tenth of eta): in a packed mass many
      // blocks lie within eta of a neighbour's face line, and overriding the separating axis
      // for all of them let Vajont section IV overlap by 1 % of a block.
      if (limits.flush_faces && to - from >= eta && std::abs(gap) <= kRideDepth * eta) {
        const FlushRank rank{continues_a_slide(q, q_solid, limits.held_q, p0, normal, kRideDepth * eta, tiny),
                             support_agreement(normal, limits), gap};
        if (best.flush_edge < 0 ||
            flush_better(rank, {best.flush_slides, best.flush_support, best.flush_gap}, eta, 0.0)) {
          best.flush_edge = i;
          best.flush_gap = gap;
          best.flush_support = rank.support;
          best.flush_slides = rank.slides;
        }
      }
    }
    if (!(gap > best.separation) && !(gap > best.apart)) continue;  // own >= 0 cannot make it better
    for (int k = 0; k < p.n; ++k) own = std::max(own, normal.dot(p.at(k) - p0));
    const double separation = gap - own;
    best.apart = std::max(best.apart, separation);
    // A face shorter than eta (grown over collinear neighbours) is no reference face: the
    // depth of a corner metres away, measured from the line of a 6 cm face, means nothing
    // (a 2.5 cm and a 6 cm edge left where three joints met on Vajont section V read a
    // small block 0.36 m "deep" in the notch of its neighbour). It still separates.
    if (separation > best.separation && (length >= eta || face_length(p, i, flat) >= eta)) {
      best.edge = i;
      best.separation = separation;
    }
    if (best.apart > apart) break;
  }
  return best;
}

ProudFace proud_face(const Shape& p, std::span<const char> solid, const Shape& q, const AxisLimits& limits,
                     double depth) {
  ProudFace best;
  for (int i = 0; i < p.n; ++i) {
    if (!solid.empty() && !solid[static_cast<size_t>(i)]) continue;
    const Vec2 p0 = p.at(i), edge = p.at(i + 1) - p0;
    const double length = edge.norm();
    if (!(length > limits.tiny)) continue;
    const Vec2 normal = outward(edge) / length;
    double gap = kInfinity, own = 0.0;
    for (int k = 0; k < q.n; ++k) gap = std::min(gap, normal.dot(q.at(k) - p0));
    if (gap > 0.0 || gap < -depth) continue;
    for (int k = 0; k < p.n; ++k) own = std::max(own, normal.dot(p.at(k) - p0));
    const double separation = gap - own;
    if (separation < -depth || !(length >= limits.eta || face_length(p, i, limits.flat) >= limits.eta)) continue;
    const double support = support_agreement(normal, limits);
    if (support > best.support) best = {i, separation, support};
  }
  return best;
}

KinkCorner kink_corner(const Shape& p, std::span<const char> p_solid, const Vec2& rest_p, const Shape& q,
                       std::span<const char> q_solid, double eta, double flat, double reach) {
  const auto solid = [](std::span<const char> s, int i) { return s.empty() || s[static_cast<size_t>(i)] != 0; };
  KinkCorner best;
  for (int i = 0; i < p.n; ++i) {
    if (!solid(p_solid, i)) continue;
    const Vec2 p0 = p.at(i), edge = p.at(i + 1) - p0;
    const double length = edge.norm();
    if (!(length > 0.0) || -outward(edge).dot(rest_p) < kRestsOn * length) continue;
    const Vec2 tangent = edge / length, normal = outward(tangent);
    const Face f = grow_face(p, i, flat);
    const double from = tangent.dot(p.at(f.first) - p0), to = tangent.dot(p.at(f.last) - p0);
    for (int k = 0; k < q.n; ++k) {
      const int before = (k + q.n - 1) % q.n;
      if (!solid(q_solid, k) || !solid(q_solid, before)) continue;
      const Vec2 c = q.at(k) - p0;
      const double u = tangent.dot(c), beyond = std::max(from - u, u - to);
      if (std::abs(normal.dot(c)) > kRideDepth * eta || !(beyond > 0.0) || !(beyond < std::min(reach, best.beyond)))
        continue;
      const double ahead = u > to ? 1.0 : -1.0;
      // q's faces at the corner: edge k (to the next vertex) and edge `before` (from the last).
      // One turns up, the other goes down below the line: q is the next block of the surface p
      // rests on, not that surface's own block (a voussoir whose joint with p opens at a hinge).
      const Vec2 to_next = q.at(k + 1) - q.at(k), to_last = q.at(before) - q.at(k);
      for (const auto& [e, d, other] : {std::tuple{k, to_next, to_last}, std::tuple{before, to_last, to_next}}) {
        const double rise = -normal.dot(d), on = ahead * tangent.dot(d), other_rise = -normal.dot(other);
        if (rise > kKinkSine * d.norm() && rise < kKinkSteepest * on && other_rise < -kKinkSine * other.norm() &&
            face_length(q, e, flat) >= eta)
          best = {k, e, u > to ? f.last : f.first, beyond};
      }
    }
  }
  return best;
}

bool cut_separates(const Shape& p, const Shape& q, double tiny, std::span<const char> solid, double slop) {
  for (int i = 0; i < p.n && !solid.empty(); ++i) {
    if (solid[static_cast<size_t>(i)]) continue;
    const Vec2 p0 = p.at(i), edge = p.at(i + 1) - p0;
    const double length = edge.norm();
    if (!(length > tiny)) continue;
    const Vec2 normal = outward(edge) / length;
    double gap = kInfinity;
    for (int k = 0; k < q.n; ++k) gap = std::min(gap, normal.dot(q.at(k) - p0));
    if (gap > -slop) return true;
  }
  return false;
}

double face_length(const Shape& p, int i, double flat) {
  const Face f = grow_face(p, i, flat);
  return (p.at(f.last) - p.at(f.first)).norm();
}

Span near_line_span(const Shape& q, const Vec2& p0, const Vec2& normal, const Vec2& tangent, double eta) {
  Span span{kInfinity, -kInfinity};
  const auto add = [&](const Vec2& x) {
    const double u = tangent.dot(x);
    span.lo = std::min(span.lo, u);
    span.hi = std::max(span.hi, u);
  };
  for (int k = 0; k < q.n; ++k) {
    const Vec2 x0 = q.at(k) - p0, x1 = q.at(k + 1) - p0;
    const double h0 = normal.dot(x0) - eta, h1 = normal.dot(x1) - eta;
    if (h0 <= 0.0) add(x0);
    if ((h0 < 0.0) != (h1 < 0.0) && h0 != h1) add(x0 + (h0 / (h0 - h1)) * (x1 - x0));
  }
  return span;
}

}  // namespace ddafit::face_axes
