// An energy audit of the run. DDA's contacts and time scheme can only dissipate, so the
// kinetic energy may never exceed the initial kinetic energy plus the work gravity has
// done since t = 0, plus what the contacts' overlaps at t = 0 can give back as they open and
// lift blocks (EnergyAudit::stored_contact). A run that breaks this is creating energy (a
// contact pumping blocks apart) and its results are garbage however smoothly it continues.
#pragma once

#include <string>
#include <vector>

#include "forward/block_system.hpp"

namespace ddafit {

struct EnergyAudit {
  double initial_kinetic = 0.0;  // J per metre of thickness
  // Each block's mass and centroid at t = 0, per block id. Gravity's work is counted with
  // these masses over the centroids' moves: a block's current mass, density x area, changes
  // with its strain, and times m g y that change depends on where the origin is. With the
  // current masses (until revision 2026-11-28.3) the implicit Vajont section I run's blocks
  // swelled by 5.5 m2 in all in its first 0.1 s, which at 1000 m of elevation read as
  // 1.3e8 J/m of potential energy gained: the audit saw the slide's kinetic energy as created.
  std::vector<double> mass;
  std::vector<Vec2> centroid;
  // The work the contacts can do on the blocks as the overlaps they start the run with open
  // to the run's own depths: at most each point's load times its depth, sum F delta (a linear
  // spring gives back half of that). The substep solver's quiet start leaves its overlaps
  // deeper than its run keeps them at long steps (a two-block stack at 20 ms x 4: 69 um at the
  // floor against 12.5 um once running), so a wall rises as its joints open: the 100-brick
  // wall of verification::brick_wall_scene by 0.6 mm on average over 1.6 s at 20 ms x 4, which
  // at 1.3e5 kg/m debits the budget by hundreds of J/m, more than a brick toppling off its
  // end releases (67 J/m), and the topple read as energy created. It is credited only against
  // the lift (lifted_energy): the overlaps may raise blocks, not set them moving. J/m; 0 when
  // not measured.
  double stored_contact = 0.0;
  double initial_water = 0.0;  // the water's potential at t = 0 (water_potential)
  // Floor of the energy scale: 1e-4 of sum m |g| x half the model size. The audit does
  // not count the energy stored in contact springs and strains, which moves blocks by
  // micrometres at rest (a settled stack rises 2 um); the floor covers that.
  double floor = 0.0;
  // Work done on the free blocks since t = 0 by the ground's inertial load -m a_g (an
  // earthquake): the runner adds -a_g . (sum m dx over the step) after each step
  // (add_load_work).
  double load_work = 0.0;
};

// The free blocks' kinetic energy, J/m: sum 1/2 rho V^T M V over each block's six rates V with
// its mass matrix (unit_mass_matrix), strain rates included (model revision 2026-12-06.17).
// M couples the rotation to the shear rate by (S_xx - S_yy) / 2, and on a block much longer than
// wide they move its long faces alike: a 1 cm plate squeezed under a dropped block rang with
// w = -49.75 rad/s and gamma' = 99.5 /s, and 1/2 I w^2 alone read as 2784 J/m against 2650 J/m
// of gravity's work (tests/test_thin_plate.cpp).
double kinetic_energy(const BlockSystem& system);
// One free block's kinetic energy at rates v (vx, vy, omega, and the strain rates), J/m:
// 1/2 rho v^T M v (above).
double block_kinetic_energy(const BlockSystem& system, int block, const Vec6& v);
// The audit's floor (EnergyAudit::floor): 1e-4 x sum m |g| x half the model size.
double energy_floor(const BlockSystem& system, const Vec2& gravity);
// The work gravity (and the water, when there is some) has done on the free blocks since
// t = 0, J/m: sum m0 g . (c - c0) over the blocks, with their masses and centroids of t = 0.
double released_energy(const EnergyAudit& audit, const BlockSystem& system, const Vec2& gravity);

// The potential energy gained by the free blocks that have risen since t = 0, J/m: sum over
// them of m0 |g . (c - c0)|. What the starting overlaps give back is credited against this only
// (check_energy): the overlaps may lift blocks as they open, but the kinetic energy must come
// from gravity's work on the blocks that fell.
double lifted_energy(const EnergyAudit& audit, const BlockSystem& system, const Vec2& gravity);

// Adds the work of a uniform acceleration load -a on every free block over a step whose
// moves of the free blocks' centroids sum, each times its mass, to `moved` (kg m / m).
void add_load_work(EnergyAudit& audit, const Vec2& acceleration, const Vec2& moved);

EnergyAudit start_energy_audit(const BlockSystem& system, const Vec2& gravity);

// Allowed excess over the budget, as a fraction of the energy scale: the first-order
// rotational and strain terms make the kinetic energy approximate to about a percent.
constexpr double kEnergyTolerance = 0.05;

// Empty when the budget holds, else a diagnosis naming the fastest block.
std::string check_energy(const EnergyAudit& audit, const BlockSystem& system, const Vec2& gravity);

}  // namespace ddafit
