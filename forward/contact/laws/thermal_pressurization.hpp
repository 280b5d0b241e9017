// Thermal pressurization of a shear band (Lachenbruch 1980; Rice 2006, J. Geophys. Res. 111,
// B05311; for Vaiont Vardoulakis 2002, Veveakis, Vardoulakis & Di Toro 2007, Pinyol &
// Alonso 2010): frictional heat in a band of thickness h raises its temperature, the pore
// water expands more than the pores and its pressure rises, and the effective normal stress
// the friction acts on falls:
//   tau = tan(phi_p) (sigma_n' - Delta p)
//   dT/dt = tau v / (rho c h) [inside the band] + alpha_th d2T/dy2
//   dp/dt = Lambda dT/dt + alpha_hy d2p/dy2
// with y normal to the band, both fields diffusing into the rock either side.
//
// What is whose:
// - The ambient pore pressure p0 (the `water:` of the scene) is already in the contact force:
//   the water's load acts on every face in contact, so the normal force a solver hands the
//   law is the effective one, sigma_n' = N' / l. The equations are linear in p with a
//   uniform p0, so the law carries only the excess Delta p = p - p0, and T above ambient.
// - One diffusion column per slip patch: the face of the overriding block that slides through
//   the interface, the same object that carries the slip of seed Eq. 2 (slip_history.hpp).
//   The face's points share one slip, so they share one heating history; a column per point
//   would be reset each time a point is created anew (every joint a corner crosses), and the
//   patch is carried across joints as the slip is. Its sigma_n' is the face's normal load
//   over l, the overriding block's length along the contact (the length that sets d_c).
// - Each (sub)step the column takes the heat tau Delta d of the (sub)step's slip Delta d at
//   the friction the (sub)step slid with, spread evenly over the band, then both fields
//   diffuse by backward Euler on a grid fine in the band and growing geometrically outwards
//   (mid-plane symmetric: zero flux there; ambient at the far end, beyond the distance either
//   field diffuses over the run). The friction of the next (sub)step reads the band's mean
//   Delta p: explicit in the coupling, as the slip laws are in the slip.
//
// Without diffusion the band's Delta p obeys dDelta p/dd = Lambda tan(phi_p)(sigma_n' -
// Delta p)/(rho c h): the strength decays as exp(-d / L), L = rho c h / (tan(phi_p) Lambda),
// the exponential law's shape with residual zero. Diffusion bleeds heat and pressure out of
// the band and slows the loss: on a plane (h -> 0) at constant slip rate V, Rice (2006)
// gives tau = tan(phi_p) sigma_n' exp(d/L*) erfc(sqrt(d/L*)), L* = (4/f^2)(rho c/Lambda)^2
// (sqrt(alpha_hy) + sqrt(alpha_th))^2 / V (tests/test_thermal_pressurization.cpp).
#pragma once

#include <vector>

#include "forward/contact/laws/friction_state.hpp"

namespace ddafit::laws {

// Cells of the half space y >= 0 from the band's mid-plane, shared by every column of one
// interface.
struct DiffusionGrid {
  std::vector<double> width;  // m, cell k's thickness
  std::vector<double> gap;    // m, from cell k's centre to cell k+1's (the last: to the far boundary)
  int band_cells = 0;         // the first band_cells cells make up the half band h/2
  bool empty() const { return width.empty(); }
};

// The grid for an interface over a run of `duration` seconds: 8 cells across the half band,
// then cells 5 % thicker each, to 6 diffusion lengths sqrt(alpha duration) of the faster
// field (and at least 4 h).
DiffusionGrid make_diffusion_grid(const Interface& face, double duration);

// A column at ambient: T then Delta p in each cell (2 x cells values, K and Pa above ambient).
void start_column(const DiffusionGrid& grid, std::vector<double>& column);

// Advances a column by `dt` seconds that brought `heat` J/m^2 into the band (the shear stress
// times the slip); returns the band's mean excess pore pressure Delta p, Pa.
double advance_column(const Interface& face, const DiffusionGrid& grid, double heat, double dt,
                      std::vector<double>& column);

// tan(phi) = tan(phi_p) (1 - Delta p / sigma_n'), between 0 and tan(phi_p). A face that carried
// no load in its last (sub)step keeps tan(phi_p) while it has no excess pressure, and has no
// friction if it has (the band's water holds it open).
inline double thermal_pressurization(const Interface& face, const FrictionState& state) {
  const double mu_p = peak_coefficient(face);
  if (!(state.normal_stress > 0.0)) return state.excess_pressure > 0.0 ? 0.0 : mu_p;
  const double share = 1.0 - state.excess_pressure / state.normal_stress;
  return mu_p * std::min(std::max(share, 0.0), 1.0);
}

}  // namespace ddafit::laws
