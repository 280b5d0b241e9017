// Water in the slope: the hydrostatic pore pressure of a fixed water surface z_w(x),
//   p(x, y) = rho_w g (z_w(x) - y)   below the surface, 0 above it,   g = |gravity|,
// acting normal to every block face below the surface, those in contact included. Summed
// over a block's boundary it is the force -∮ p n ds = -∫_B grad p dA: buoyancy (rho_w g V_sub
// upwards) under a level surface, plus a push down the gradient of a sloping one. On a face
// in contact the pressure acts on both blocks, so the contact carries only what the solids
// press on each other: the effective normal force N' = N - p l that the Coulomb cap then
// uses (joint water pressure, Terzaghi's effective stress) without a rule of its own.
//
// Left out (docs/scene-format.md, "Water"): seepage flow and its change of the surface while
// the slide moves, drag, added mass, pressure changes from the blocks' own motion (undrained
// loading, thermal pressurization), water held in open joints above the surface.
#pragma once

#include "forward/block_system.hpp"

namespace ddafit {

// z_w(x): the table interpolated (flat beyond its ends), raised to the level where both are
// given (the reservoir floods whatever of the table lies below it).
double water_surface(const Water& water, double x);

// The pressure's load on free block b as DDA's six generalised forces (∫ T^T (-p n) ds,
// T of forward/kinematics.hpp): force, moment and the strain terms. Exact for a piecewise
// linear surface (each face is cut where the surface bends or crosses it; p is then linear
// along each piece and two Gauss points integrate it).
//
// `ahead` moves the block rigidly (dx, dy, dtheta about its centroid) before the load is
// taken: the solvers take it half a step ahead, at x0 + v0 dt / 2, which with their
// constant-acceleration step (x1 = x0 + v0 dt + a dt^2/2, v1 = v0 + a dt) is the
// drift-kick-drift leapfrog, energy-stable for the water's spring; taken at x0 the step is
// explicit Euler for it and a floating block bobbed higher every cycle until the energy
// audit tripped (tests/test_water.cpp).
Vec6 water_load(const BlockSystem& system, int block, double gravity, const Vec3& ahead = Vec3::Zero());

// The loads' potential, U = sum over free blocks of ∫_B p dA (its gradient under a rigid
// move of a block is minus the load above), for the energy audit.
double water_potential(const BlockSystem& system, double gravity);

}  // namespace ddafit
