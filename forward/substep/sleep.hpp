// Sleeping (Box2D's islands): a group of touching free blocks that has been at rest for
// control.sleep_time seconds sleeps: its blocks take no part in the contact sweeps and are
// not integrated (the solver treats them as fixed), until a moving block comes within the
// contact margin of one of them; then the whole group wakes. Off by default (sleep_time 0):
// a run that never sleeps is the model revision's reference. Not used under an earthquake,
// whose load changes every step. docs/theory.md §13, "Sleeping".
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/substep/substep_types.hpp"

namespace ddafit {

struct SleepState {
  double sleep_time = 0.0;   // s at rest before a group sleeps; 0 = never
  double sleep_speed = 0.0;  // m/s: a block slower than this (every vertex) is at rest
  std::vector<double> rest_time;  // per block, s
  std::vector<char> asleep;       // per block
  long block_steps_asleep = 0;    // summed over steps: the work sleeping saved
  long wakes = 0;                 // groups woken
  bool enabled() const { return sleep_time > 0.0; }
};

// Before a step's sweeps: wakes every sleeping group that a moving awake block has come
// within the contact margin of (a manifold joins them).
void wake_touched_groups(const BlockSystem& s, const ContactSet& contacts, const std::vector<double>& reach,
                         SleepState& sleep);

// The sweeps' view of a sleeping block: no mass to move (as a fixed block).
void mask_sleeping(const SleepState& sleep, std::vector<BlockMass>& masses);

// The manifolds the sweeps solve: those with at least one block that moves.
void drop_sleeping_manifolds(const std::vector<ContactManifold>& manifolds, const std::vector<BlockMass>& masses,
                             std::vector<std::vector<int>>& colours);

// Every free block asleep: with no block moving, nothing wakes a group again, and while no
// load changes with time (no earthquake: sleeping is off under one) the blocks stay where they
// are to the end of the run.
bool everything_asleep(const BlockSystem& s, const SleepState& sleep);

// After a measured step of dt: each awake block's time at rest, and the groups whose blocks
// have all rested sleep_time fall asleep (their velocities set to zero).
void update_sleep(BlockSystem& s, const ContactSet& contacts, const std::vector<double>& reach, double dt,
                  SleepState& sleep);

}  // namespace ddafit
