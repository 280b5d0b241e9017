// The contact law, written once and called by both solvers (docs/theory.md §3-4): the
// implicit solver applies it to the forces of its springs (forward/step/check_contacts.cpp,
// assemble.cpp, update_blocks.cpp), the substep solver to the impulses of a substep
// (forward/substep/solve_contacts.cpp, prepare_contacts.cpp); the contact stage creates and
// carries its state (forward/contact/collide.cpp, slip_history.cpp).
//
//   tan phi = law(d + Delta d / 2, d_c, v)        friction at the slip d of the face, predicted
//                                                 half a (sub)step ahead, and its slip speed v
//                                                 over the last (sub)step (friction_law.hpp;
//                                                 seed Eq. 2-3 by default)
//   d_c = ratio x length of the overriding block  along the contact (seed Eq. 2)
//   |T| <= tan(phi) max(N, 0) + c l_c             Mohr-Coulomb cap; cohesion while bonded
//   N >= -T_s l_c                                 tension cut-off (T_s tensile strength) while bonded
//   d += |slip| while the face touches            seed Eq. 2
//
// A bond (cohesion c and tensile strength T_s over the length l_c) exists only between
// blocks touching at t = 0, and is lost for good once the point has slid or opened at its
// strength by more than the contact slop (wear_bond).
// Forces are per metre of thickness; the substep solver passes impulses (force x substep).
#pragma once

#include <algorithm>
#include <cmath>

#include "forward/contact/contact_types.hpp"
#include "forward/contact/friction_law.hpp"

namespace ddafit {

// d_c of seed Eq. 2 for an overriding block of `length` along the contact, m.
inline double critical_distance(const Interface& face, double length) {
  return face.critical_distance_ratio * length;
}

// tan(phi) of a face with slip history h, at the middle of the coming (sub)step: the last
// increment predicts the next to second order, and the (sub)step's own slip would feed
// back inside the solve (a trial that slips far degrades friction, which lets the next
// trial slip further). A rate law reads the slip speed at the middle of the coming
// (sub)step the same way, extrapolated from the mean speeds of the last two (sub)steps,
// v = 2 v_1 - v_0 (>= 0): the last speed alone lags by a (sub)step, which with a law as
// steep as v_w = 0.05 m/s put the implicit solver 2 % behind RK4 of the law's equation
// of motion (tests/test_friction_laws.cpp).
inline FrictionState friction_state(const SlipHistory& h) {
  return {h.slip + 0.5 * h.last_slip, std::max(2.0 * h.slip_rate - h.previous_slip_rate, 0.0), h.critical_distance,
          h.normal_stress, h.excess_pressure};
}
// The bilinear law (seed Eq. 3) bends at d_c. A (sub)step whose predicted slip crosses d_c
// takes the mean of the law over that slip, the midpoint of each part weighted by its share:
// at one midpoint, a 0.5 m block thrown at 1 m/s onto a jointed floor (d_c 5 mm, slipping
// 10 mm a 10 ms step) ran 1 % past where the work of friction stops it on the implicit solver
// (model revision 2026-12-06.22; tests/test_friction_start.cpp).
inline double friction_coefficient(const Interface& face, const SlipHistory& h) {
  FrictionState state = friction_state(h);
  const double d = h.slip, d_c = h.critical_distance, step = h.last_slip;
  if (face.law != FrictionLaw::Bilinear || !(d < d_c && d + step > d_c)) return friction_law(face, state);
  const double before = (d_c - d) / step;
  state.slip = 0.5 * (d + d_c);
  const double degrading = friction_law(face, state);
  state.slip = 0.5 * (d_c + d + step);
  return before * degrading + (1.0 - before) * friction_law(face, state);
}

// The cohesive part of the shear strength, c l_c, while bonded (N/m).
inline double cohesive_strength(const Interface& face, const ContactPoint& p) {
  return p.bonded ? face.cohesion * p.bond_length : 0.0;
}

// The largest tensile normal force (>= 0) before the point opens: T_s l_c while bonded.
inline double tensile_capacity(const Interface& face, const ContactPoint& p) {
  return p.bonded ? face.tensile_strength * p.bond_length : 0.0;
}

// Mohr-Coulomb: the largest shear a point carries before it slides, for normal load N
// (compression > 0), friction coefficient mu and cohesive strength C (in the same measure:
// forces, or impulses over a substep).
inline double coulomb_cap(double mu, double normal, double cohesive) {
  return mu * std::max(normal, 0.0) + cohesive;
}

// Whether a point touching at t = 0 forms a bond: only where the interface has strength
// to hold, and only where the blocks touch (separation within the slop).
inline bool forms_bond(const Interface& face, double separation, double slop) {
  return separation <= slop && (face.cohesion > 0.0 || face.tensile_strength > 0.0);
}

// Cohesion and tension are lost for good.
inline void break_bond(ContactPoint& p) { p.bonded = false; }

// Slides or opens: moves by more than `tolerance` (m, the solver's own position tolerance)
// while at its strength, counted from where the bond formed. `slip` is this (sub)step's signed
// slip if |T| is at the Mohr-Coulomb cap tan(phi) N + c l_c (else 0), `opening` its signed
// opening if N is at the tension cut-off -T_s l_c (else 0); each is summed with its sign, so a
// point that rocks to and fro at its cap (the implicit solver's elastic blocks do, by 0.1 um a
// step) has not moved, while one that creeps one way has. A point at its cap that does not move
// has not failed: where a block rests on several points the share each carries is the solver's
// to choose (statically indeterminate), and one point at its cap while the others hold the
// block is load passing to them. Broken at the cap, a block bonded to a jointed slope by three
// times the cohesion that holds it slid away on both solvers, bond after bond
// (tests/test_cohesive_slope.cpp). Nor is a move below the strength a failure: a hung chain's
// joints open by g h^2 in its first substep while the sweeps take up its weight.
inline void wear_bond(ContactPoint& p, double slip, double opening, double tolerance) {
  if (!p.bonded) return;
  p.bond_slip += slip;
  p.bond_opening += opening;
  if (std::abs(p.bond_slip) > tolerance || p.bond_opening > tolerance) break_bond(p);
}

// Seed Eq. 2: over a (sub)step of `duration` seconds a face's slip grows by the (sub)step's increment, the largest slip of its
// closed points (they share one face; one face can touch several blocks at once, as a block
// crossing a joint does, and its slip is not their sum).
inline void add_slip(SlipHistory& h, double duration) {
  h.slip += h.increment;
  h.last_slip = h.increment;
  h.previous_slip_rate = h.slip_rate;
  h.slip_rate = duration > 0.0 ? h.increment / duration : 0.0;
  h.increment = 0.0;
}

inline void gather_slip(SlipHistory& h, double point_slip) { h.increment = std::max(h.increment, point_slip); }

}  // namespace ddafit
