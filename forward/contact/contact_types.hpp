// Plain data of the contact stage both solvers share (docs/theory.md §3): the convex
// pieces contact is detected on, the manifolds between pieces of different blocks, the
// state each contact point carries from step to step, and the slip history of the faces
// that slide (seed Eq. 2-3).
#pragma once

#include <cstdint>
#include <vector>

#include "forward/contact/laws/thermal_pressurization.hpp"
#include "forward/kinematics.hpp"
#include "forward/scene.hpp"

namespace ddafit {

// A convex piece of a block, for contact only (a concave block is split; its unknowns
// stay one set). Its corners are vertex ids of BlockSystem::vertices, counter-clockwise,
// stored in ContactShapes::corners[first .. first + count).
struct ConvexPiece {
  int block = -1;
  int first = 0;
  int count = 0;
  double width = 0.0;  // m: its least width at t = 0, across the narrowest strip that holds it
};

struct ContactShapes {
  std::vector<ConvexPiece> pieces;
  std::vector<int> corners;
  // Per corner: 1 if the edge to the next corner is part of the block's boundary, 0 if it
  // is a cut between two pieces of the block (manifold.hpp, solid edges).
  std::vector<char> solid;
  // Per corner: 1 if the block's polygon turns inward there (a reflex corner, where the
  // block is concave and a cut starts). Seen from outside the block such a corner is no
  // corner: the faces on either side of it meet in a hollow (manifold.hpp, "Reflex corners").
  std::vector<char> reflex;
};

enum class ContactState : std::uint8_t { Open, Sliding, Locked };

const char* to_string(ContactState state);

// The implicit solver's springs at a point (forward/step/): the open-close state and what
// the shear spring holds. The normal spring acts on the gap along the manifold's normal,
// the shear spring on the offset along its tangent (docs/theory.md §3).
struct SpringState {
  ContactState state = ContactState::Open;       // current open-close iterate
  ContactState step_state = ContactState::Open;  // state at the start of the step
  // N/m: the compression the point carried into the step (its normal force at the end of the
  // last one; 0 if it started open or is new). Its overlap at that load, start_force / penalty,
  // is held, not pushed out (spring_reference, forward/step/assemble.hpp). A float in the
  // padding after the two states, so that ContactPoint does not grow.
  float start_force = 0.0f;
  // d_s0: elastic offset of the shear spring at the start of the step, m. A locked contact
  // carries it from step to step; a sliding one sets it to the friction force over the
  // shear stiffness, so that should it lock, its spring takes over at that force.
  double shear_offset = 0.0;
  double slip_direction = 0.0;  // s = +1/-1: sign of the slip of b relative to a along the tangent
  double normal_force = 0.0;    // N >= 0 from the last iterate (compression), N/m
  int state_changes = 0;        // in this step's open-close iteration (check_contacts.cpp)
  // The share of the shear stiffness a locked point keeps this step: 1, or less once it is
  // frozen locked past its Coulomb cap (check_contacts.cpp, "Capped locks"). A float fills
  // the padding after state_changes, so that ContactPoint does not grow.
  float shear_scale = 1.0f;
  // The last iterate's kinematics, from the step's unknowns.
  double normal_gap = 0.0;  // d_n at the end of the step, m (< 0 = penetration)
  double step_slip = 0.0;   // relative tangential motion over the step, m
};

// The substep solver's impulses at a point (forward/substep/). The fields the sweeps read
// come first (they stream through every point several times per substep).
struct ImpulseState {
  double normal = 0.0;    // N s/m, accumulated over the last substep (warm start)
  double tangent = 0.0;   // N s/m
  double normal_mass = 0.0;   // 1 / (J W J^T) along the normal, kg/m
  double tangent_mass = 0.0;  // along the tangent
  double tension = 0.0;   // largest tensile impulse per substep while bonded
  double cohesion = 0.0;  // cohesive shear impulse per substep while bonded
  double step_normal = 0.0;   // N s/m, summed over the substeps of this step
  double step_tangent = 0.0;
  double push_out = 0.0;  // N s/m: this substep's push-out impulse (control.split_impulses)
  double carried = 0.0;   // N s/m: the normal impulse the last warm start applied (substep solver)
};

// A contact point. Laid out for the substep solver's sweeps: what they read first.
struct ContactPoint {
  // The point about each block's centroid at the start of the step: the relative motion
  // of the two blocks there is T_b(p) D_b - T_a(p) D_a (Shi 1993 eq. 2.2).
  Vec2 ra = Vec2::Zero(), rb = Vec2::Zero();
  double separation = 0.0;     // along the normal at the start of the step, m (< 0: penetration)
  ImpulseState impulse;        // substep solver

  std::uint32_t id = 0;  // feature key of the manifold (forward/contact/manifold.hpp)
  int owner = -1;        // vertex id of the corner the point sits on
  Vec2 anchor = Vec2::Zero();  // the point at the start of the step, world
  double slip = 0.0;  // |tangential slip| of the last (sub)step while closed, m
  double normal_load = 0.0;  // N/m, compression carried over the last (sub)step (0 when open)
  bool fresh = true;  // its features did not touch in the last step

  // Strength of the contact law (contact_law.hpp): cohesion and tension act on
  // bond_length while the bond holds; it forms only between blocks touching at t = 0.
  bool bonded = false;
  double bond_length = 0.0;  // m
  // Signed slip and opening at strength since the bond formed, m (contact_law.hpp, wear_bond).
  double bond_slip = 0.0;
  double bond_opening = 0.0;

  SpringState spring;    // implicit solver
};

// One touching pair of convex pieces of different blocks: one normal, at most two points.
// The fields the sweeps read come first.
struct ContactManifold {
  int block_a = -1, block_b = -1;
  int point_count = 0;
  double friction = 0.0;        // tan(phi) at the history's slip (contact_law.hpp)
  double deep_overlap = 0.0;    // m: an overlap beyond this is corrected in position (substep solver)
  Vec2 normal = Vec2::Zero();   // unit, from a to b
  Vec2 tangent = Vec2::Zero();  // normal turned 90 degrees clockwise
  ContactPoint points[2];

  int piece_a = -1, piece_b = -1;
  int interface = -1;
  // The slip history of the face that slides (slip_history.hpp): index into the step's
  // histories, and its key (the overriding block's face and the interface).
  int history = -1;
  std::uint64_t face_key = 0;
  int overriding_block = -1;  // whose length sets d_c (seed Eq. 2)
};

// d of seed Eq. 2-3, kept per sliding face: the face of the overriding block that touches
// through one interface. Its points share it, in every manifold the face has, so a block
// crossing a joint onto the next block of a flush surface carries its slip with it
// (docs/theory.md §4).
struct SlipHistory {
  std::uint64_t key = 0;
  int interface = -1;
  double slip = 0.0;               // accumulated while the face touches, m
  double last_slip = 0.0;          // of the last (sub)step: the mid-step predictor
  double slip_rate = 0.0;          // m/s over the last (sub)step (rate laws)
  double previous_slip_rate = 0.0; // m/s over the (sub)step before: the rate predictor
  double critical_distance = 0.0;  // d_c, m
  double increment = 0.0;          // this (sub)step's slip, gathered from the points
  double friction = 0.0;           // tan(phi) at the predicted slip (contact_law.hpp)
  bool settled = false;            // no further slip changes the friction
  bool changed = true;             // the friction changed in the last update
  // law: thermal_pressurization (laws/thermal_pressurization.hpp): the face's shear band.
  double face_length = 0.0;        // l, the overriding block's length along the contact, m
  double normal_load = 0.0;        // N/m, this (sub)step's, gathered from the points
  double normal_stress = 0.0;      // sigma_n' = normal load / l over the last (sub)step, Pa
  double excess_pressure = 0.0;    // Delta p in the band, Pa
  std::vector<double> band_column; // T and Delta p across the band and the rock beside it
};

// What the contact stage hands a solver each step.
struct ContactSet {
  std::vector<ContactManifold> manifolds;  // sorted by piece pair
  std::vector<SlipHistory> histories;      // sorted by key
  // Per interface, the grid of its shear band's diffusion columns (law: thermal_pressurization),
  // else empty; set once per run (prepare_shear_bands, slip_history.hpp).
  std::vector<laws::DiffusionGrid> shear_bands;
};

}  // namespace ddafit
