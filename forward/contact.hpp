// A vertex-edge contact: vertex P1 of block i against edge P2->P3 of block j.
// Vertex-vertex situations are reduced to one vertex-edge contact when detected.
#pragma once

#include <cstdint>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit {

enum class ContactState : std::uint8_t { Open, Sliding, Locked };

const char* to_string(ContactState state);

struct Contact {
  int vertex = -1;   // P1, a vertex id of block i
  int block_i = -1;  // owner of the vertex: the overriding block of seed section 2.2
  int block_j = -1;  // owner of the edge
  int edge = -1;     // vertex id of P2 on block j; P3 is the next vertex of j
  int interface = -1;

  ContactState state = ContactState::Open;       // current open-close iterate
  ContactState step_state = ContactState::Open;  // state at the start of the step

  // Shear reference point P0, fixed to block j, as a fraction of the edge P2->P3.
  double reference_ratio = 0.0;
  double slip_direction = 0.0;  // s = +1/-1, sign of the slip of P1 relative to j along t

  double accumulated_slip = 0.0;   // d of seed Eq. 2: sum of |slip| over accepted steps
  double last_step_slip = 0.0;     // |slip| of the last accepted step (the mid-step predictor)
  double critical_distance = 0.0;  // d_c of seed Eq. 2
  double normal_force = 0.0;       // N >= 0 from the last iterate (compression)
  double bond_length = 0.0;        // l_c: length that cohesion and tension act on
  bool bonded = false;             // cohesion and tensile strength still intact

  // State changes in the current step's open-close iteration; a contact that keeps
  // cycling is frozen (check_contacts.cpp).
  int state_changes = 0;

  // Last iterate's kinematics, used to classify and to accept the step.
  double start_gap = 0.0;    // d_n at the start of the step (m)
  double normal_gap = 0.0;   // d_n at the end of the step (m, < 0 = penetration)
  double step_slip = 0.0;    // relative tangential motion of P1 over the step (m)
  double shear_offset = 0.0; // d_s: offset of P1 from P0 along t at the end of the step (m);
                             // for a sliding contact, its slip over the step
};

// Slip of P1 relative to block j that counts as sliding in the current iterate. A
// contact that was sliding at the start of the step carries its friction force as the
// pre-load of its reference point, so its slip is the step's relative motion; for one
// that was locked, the slip is the whole offset from the reference (the elastic offset
// its spring releases when it lets go is part of the same motion).
inline double sliding_slip(const Contact& c) {
  return c.step_state == ContactState::Sliding ? c.step_slip : c.shear_offset;
}

// Key of a contact that survives from step to step: the vertex and the block it touches.
// The accumulated slip follows the vertex across edges of the same block (seed 2.2).
inline std::uint64_t contact_key(int vertex, int block_j) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(vertex)) << 32) |
         static_cast<std::uint32_t>(block_j);
}

}  // namespace ddafit
