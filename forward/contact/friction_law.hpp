// The friction law behind the contact law: tan(phi) of a sliding face from its slip history
// and slip speed, by the interface's `law` (docs/scene-format.md, "Friction laws"). Each law
// is a small file in forward/contact/laws/ with its equation and source; contact_law.hpp and
// slip_history.cpp are the only callers, so a new law plugs in here and nowhere else.
//
//   bilinear            phi(d) = phi_p - i min(d/d_c, 1)                      seed Eq. 2-3
//   exponential         mu(d) = mu_r + (mu_p - mu_r) exp(-d/d_c)
//   velocity_weakening  mu(v) = mu_r + (mu_p - mu_r) / (1 + |v|/v_w)          flash heating
//   thermal_pressurization  mu = mu_p (1 - Delta p / sigma_n')                 heat in a shear band
#pragma once

#include "forward/contact/laws/bilinear.hpp"
#include "forward/contact/laws/exponential.hpp"
#include "forward/contact/laws/thermal_pressurization.hpp"
#include "forward/contact/laws/velocity_weakening.hpp"

namespace ddafit {

using laws::FrictionState;

// tan(phi) of a face in `state` through `face`.
inline double friction_law(const Interface& face, const FrictionState& state) {
  switch (face.law) {
    case FrictionLaw::Exponential: return laws::exponential(face, state);
    case FrictionLaw::VelocityWeakening: return laws::velocity_weakening(face, state);
    case FrictionLaw::ThermalPressurization: return laws::thermal_pressurization(face, state);
    case FrictionLaw::Bilinear: break;
  }
  return laws::bilinear(face, state);
}

// Whether more slip (or any change of slip speed) can change the friction of a face in
// `state`. Lets the solvers skip the law for the many contacts at their residual friction.
inline bool friction_law_settled(const Interface& face, const FrictionState& state) {
  switch (face.law) {
    case FrictionLaw::Exponential: return laws::exponential_settled(face, state);
    case FrictionLaw::VelocityWeakening: return laws::velocity_weakening_settled(face, state);
    case FrictionLaw::ThermalPressurization: return false;  // the band cools and drains while it rests
    case FrictionLaw::Bilinear: break;
  }
  return laws::bilinear_settled(face, state);
}

// Whether the law reads the slip speed (and so the (sub)step's duration matters).
inline bool rate_dependent(const Interface& face) { return face.law == FrictionLaw::VelocityWeakening; }

}  // namespace ddafit
