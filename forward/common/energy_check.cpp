#include "forward/common/energy_check.hpp"

#include "forward/mass_matrix.hpp"
#include "forward/water/hydrostatic.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ddafit {

double block_kinetic_energy(const BlockSystem& s, int b, const Vec6& v) {
  const Block& block = s.blocks[b];
  return 0.5 * s.density[block.material] * v.dot(unit_mass_matrix(block) * v);
}

double kinetic_energy(const BlockSystem& s) {
  double energy = 0.0;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
    if (!s.blocks[b].fixed) energy += block_kinetic_energy(s, b, s.blocks[b].velocity);
  return energy;
}

double energy_floor(const BlockSystem& s, const Vec2& gravity) {
  double weight = 0.0;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
    if (!s.blocks[b].fixed) weight += s.mass(b) * gravity.norm();
  return 1e-4 * weight * s.half_model_size;
}

double released_energy(const EnergyAudit& audit, const BlockSystem& s, const Vec2& gravity) {
  double work = 0.0;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
    if (!s.blocks[b].fixed) work += audit.mass[b] * gravity.dot(s.blocks[b].centroid - audit.centroid[b]);
  return work + audit.initial_water - water_potential(s, gravity.norm());
}

double lifted_energy(const EnergyAudit& audit, const BlockSystem& s, const Vec2& gravity) {
  double lifted = 0.0;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
    if (!s.blocks[b].fixed)
      lifted += std::max(0.0, -audit.mass[b] * gravity.dot(s.blocks[b].centroid - audit.centroid[b]));
  return lifted;
}

void add_load_work(EnergyAudit& audit, const Vec2& acceleration, const Vec2& moved) {
  audit.load_work -= acceleration.dot(moved);
}

EnergyAudit start_energy_audit(const BlockSystem& s, const Vec2& gravity) {
  EnergyAudit audit;
  audit.initial_kinetic = kinetic_energy(s);
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    audit.mass.push_back(s.mass(b));
    audit.centroid.push_back(s.blocks[b].centroid);
  }
  audit.initial_water = water_potential(s, gravity.norm());
  audit.floor = energy_floor(s, gravity);
  return audit;
}

std::string check_energy(const EnergyAudit& audit, const BlockSystem& s, const Vec2& gravity) {
  const double kinetic = kinetic_energy(s);
  const double released = released_energy(audit, s, gravity);
  // Nothing stored (the implicit solver, a scene at rest on nothing): no sum over the blocks.
  const double returned =
      audit.stored_contact > 0.0 ? std::min(audit.stored_contact, lifted_energy(audit, s, gravity)) : 0.0;
  const double budget = audit.initial_kinetic + released + audit.load_work + returned;
  const double scale = audit.initial_kinetic + std::abs(released) + std::abs(audit.load_work) + returned +
                       audit.floor + 1e-300;
  if (kinetic <= std::max(budget, 0.0) + kEnergyTolerance * scale) return {};
  int fastest = -1;
  double speed = -1.0;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const Vec2 v(s.blocks[b].velocity[0], s.blocks[b].velocity[1]);
    if (!s.blocks[b].fixed && v.norm() > speed) {
      speed = v.norm();
      fastest = b;
    }
  }
  std::ostringstream out;
  // The wording of runs without an earthquake stays as it always was.
  out << "kinetic energy " << kinetic << " J/m exceeds what gravity "
      << (audit.load_work != 0.0 ? "and the loads have" : "has") << " supplied (" << budget
      << " J/m): contacts are creating energy (fastest block '" << s.block_names[fastest] << "' at " << speed
      << " m/s); results from here on would be meaningless. Lower time.step or control.max_displacement_ratio; "
         "with the implicit solver, tighten control.max_penetration_ratio; with the substep solver, raise "
         "time.substeps";
  return out.str();
}

}  // namespace ddafit
