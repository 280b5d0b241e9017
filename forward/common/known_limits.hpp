// The classes of scenes in which the implicit solver is known to run off seed Eq. 4, found at
// t = 0 so that `time.integrator: auto` can avoid them and a run can say so.
//
// Tall sliders (docs/theory.md, Known limits (i)). A free block resting on a fixed face steeper
// than its friction angle slides from rest, and one given a velocity along the face slides until
// its friction stops it. Sliding, its base reaction lies r = tan(phi) H / L of its half-length
// ahead of its centre (H and L: the block's extents along the face's normal and along the face;
// r = 1: it topples rather than slides), and at r near 1 it rests on its front corner, which
// meets every joint of the face first. Measured on tests/test_tall_sliders.cpp's class (slopes of 20-40 deg at 1 deg steeper
// than the friction, joints every 0.1-1 of the slider's length, 1 ms steps): the implicit solver
// keeps 0.3 m sliders within 1 % of seed Eq. 4 at r = 0.8 and takes them 12-17 % off at r =
// 0.85, 28-30 % at 0.88 and up to 70 % at 0.9; the substep solver keeps every run within 1.3e-4.
// Sliders given 3 m/s on faces 5 deg gentler than their friction (20 and 30 deg; decelerating):
// 11-51 % off at r = 0.9 and 0.95 over joints every 0.1 of their length, none at r = 0.5; the
// substep solver none.
//
// Heavy blocks on much lighter ones (Known limits (j)). A free block resting on a free block
// kHeavyOnLightRatio or more times lighter. Measured on tests/test_heavy_sliders.cpp's class
// (a 0.3 m slider, 1 deg steeper than its friction, on rows of free blocks, from rest): where
// the slider outweighs the row blocks 30 times or more, the implicit solver took 29 of 38 runs
// more than 1 % off seed Eq. 4 (up to 32 %), and 20-440 s for a second of 24 row blocks; the
// substep solver 18 of 38 (tall sliders; none at r = 0.5), in under a second. 20-30 times:
// implicit 5 of 8, substep 4 of 8; below 20 times: implicit 3 of 26 (1.2-1.3 %), substep none.
//
// (Stacks with a weaker joint, Known limits (l), were a third class from model revision
// 2026-12-06.8 to .13: a lower block held narrowly crept on the implicit solver until .14.)
#pragma once

#include "forward/block_system.hpp"
#include "forward/scene.hpp"

namespace ddafit {

// r from which a slider counts as tall: the largest r at which the class above stays within 1 %.
inline constexpr double kTallSliderReach = 0.8;

// The mass ratio from which a block resting on a lighter one counts as heavy on light: the
// substep solver's own (converge_heavy.hpp, kHeavyMassRatio).
inline constexpr double kHeavyOnLightRatio = 30.0;

struct TallSlider {
  int block = -1;         // the free block with the largest r, or -1 if none slides
  double reach = 0.0;     // its r = tan(phi_p) H / L
  double slope = 0.0;     // its face's inclination, degrees
  double friction = 0.0;  // the face's peak friction angle phi_p, degrees
  bool launched = false;  // given a velocity along the face (else it slides from rest)
};

struct HeavyOnLight {
  int heavy = -1, light = -1;  // the pair with the largest mass ratio, or -1 if none
  double ratio = 0.0;          // mass of heavy / mass of light
};

struct KnownLimits {
  // The free block with the largest r among those resting at t = 0 (a contact point within the
  // slop) on a fixed block's face, without cohesion or tensile strength, that is steeper than
  // the face's peak friction angle or along which the block is given a velocity.
  TallSlider slider;
  // Of the free blocks resting at t = 0 on a free block (a contact point within the slop, its
  // normal more than a tenth against gravity), the pair with the largest mass ratio.
  HeavyOnLight heavy;
};

// Whether the scene holds a known limit's class: a tall slider (r above kTallSliderReach, a
// rounding's worth above: a slider built at exactly 0.8 measures 0.8 to about 1e-15) or a
// block heavy on a light one (kHeavyOnLightRatio).
bool is_tall(const TallSlider& slider);
bool is_heavy_on_light(const HeavyOnLight& heavy);

// The classes from one contact detection, as a run's first step would do it.
KnownLimits find_known_limits(const Scene& scene, const BlockSystem& s);

}  // namespace ddafit
