// Slip histories (seed Eq. 2-3, docs/theory.md §4): the slip d that degrades friction
// belongs to the face of the overriding block that slides, through one interface, not to
// a pair of blocks. A block crossing a joint between two blocks of a flush surface keeps
// sliding on the same face, so it carries its slip onto the next block and the joint is
// invisible to the law as it is to the geometry. A face that touches nothing within the
// contact margin loses its history: the next contact starts fresh.
#pragma once

#include <cstdint>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"

namespace ddafit {

// The key of a face (the block vertex id where it starts) sliding through an interface.
inline std::uint64_t slip_history_key(int face_vertex, int interface) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(face_vertex)) << 32) |
         static_cast<std::uint32_t>(interface);
}

// Gives every manifold of `contacts` (with face_key, overriding_block, and in `history` the
// index of the last step's history of the same pair and face or -1) its history: the one its
// key had in contacts.histories (the last step's), or a new one with no slip and d_c from the
// overriding block's length along the contact. Replaces contacts.histories with the
// histories in use, sorted by key, and sets each manifold's friction coefficient.
// `previous` is scratch: it holds the last step's histories meanwhile (its memory is reused
// between calls).
void assign_histories(const BlockSystem& system, ContactSet& contacts, std::vector<SlipHistory>& previous);

// A face that has not slid yet (no slip) but whose blocks slide past each other now predicts its
// first (sub)step's slip from its fastest point's sliding speed v_t: the increment v_t x `step`
// and the slip speed v_t, as if it had slid so over the last (sub)step (contact_law.hpp,
// friction_state), and its manifolds' friction follows. Called again with a shorter step (the
// implicit solver's attempt cut or fitted to an output), it predicts for that step instead. Before
// (model revision 2026-12-06.22) it took its peak friction for the whole (sub)step: a 0.5 m
// block thrown at 1 m/s onto a jointed floor (d_c 5 mm) at 10 ms stopped 3 % short of where the
// work of friction stops it on the implicit solver, which crossed d_c in that one step
// (tests/test_friction_start.cpp).
void predict_first_slip(const BlockSystem& system, ContactSet& contacts, double step);

// The diffusion grid of every thermal_pressurization interface for a run of `duration` s.
void prepare_shear_bands(const BlockSystem& system, double duration, ContactSet& contacts);

// Forgets every face's slip (the quiet start's settling is not part of the slide).
void reset_histories(const BlockSystem& system, ContactSet& contacts);

// After a (sub)step of `duration` seconds whose points have their `slip` set (0 for an open
// point): each face's slip grows by the largest of its points' (contact_law.hpp, add_slip),
// its slip speed is that over the duration, and the friction of every manifold follows.
void advance_histories(const BlockSystem& system, ContactSet& contacts, double duration);

}  // namespace ddafit
