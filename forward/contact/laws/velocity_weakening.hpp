// Velocity weakening, the flash-heating family (Rice 2006; Di Toro et al. 2011, Nature 471;
// Goldsby & Tullis 2011, Science 334): friction falls with the slip speed v of the contact,
// not with the slip so far,
//   mu(v) = mu_r + (mu_p - mu_r) / (1 + |v| / v_w),   mu = tan(phi),  phi_r = phi_p - i,
// with v_w the interface's weakening_velocity (m/s): at v = v_w half the roughness is gone.
// A face at rest has its peak friction; a face that slows down regains it.
//
// v is the face's slip speed predicted for the middle of the coming (sub)step from its mean
// speeds over the last two (contact_law.hpp, friction_state): the substep solver's last
// substeps, the implicit solver's last accepted steps. The implicit solver holds it fixed
// through the step's open-close iterations (friction from the start-of-step prediction,
// not iterated: a friction that moved with each trial would let open-close chase its own
// tail, as the slip laws' mid-step predictor avoids for the same reason).
#pragma once

#include <cmath>

#include "forward/contact/laws/friction_state.hpp"

namespace ddafit::laws {

inline double velocity_weakening(const Interface& face, const FrictionState& state) {
  const double mu_p = peak_coefficient(face), mu_r = residual_coefficient(face);
  return mu_r + (mu_p - mu_r) / (1.0 + std::abs(state.slip_rate) / face.weakening_velocity);
}

// Never settled while it has roughness: a face that slows down regains friction.
inline bool velocity_weakening_settled(const Interface& face, const FrictionState&) {
  return face.roughness_angle == 0.0;
}

}  // namespace ddafit::laws
