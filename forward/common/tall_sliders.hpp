// Tall sliders: the class of scenes in which the implicit solver is known to run off seed
// Eq. 4 (docs/theory.md, Known limits (i)), found at t = 0 so that a run can say so.
//
// A free block resting on a fixed face steeper than its friction angle slides from rest, and one
// given a velocity along the face slides until its friction stops it. Sliding,
// its base reaction lies r = tan(phi) H / L of its half-length ahead of its centre (H and L: the
// block's extents along the face's normal and along the face; r = 1: it topples rather than
// slides), and at r near 1 it rests on its front corner, which meets every joint of the face
// first. Measured on tests/test_tall_sliders.cpp's class (slopes of 20-40 deg at 1 deg steeper
// than the friction, joints every 0.1-1 of the slider's length, 1 ms steps): the implicit solver
// keeps 0.3 m sliders within 1 % of seed Eq. 4 at r = 0.8 and takes them 12-17 % off at r =
// 0.85, 28-30 % at 0.88 and up to 70 % at 0.9; the substep solver keeps every run within 1.3e-4.
// Sliders given 3 m/s on faces 5 deg gentler than their friction (20 and 30 deg; decelerating):
// 11-51 % off at r = 0.9 and 0.95 over joints every 0.1 of their length, none at r = 0.5; the
// substep solver none.
#pragma once

#include "forward/block_system.hpp"
#include "forward/scene.hpp"

namespace ddafit {

// r from which a slider counts as tall: the largest r at which the class above stays within 1 %.
inline constexpr double kTallSliderReach = 0.8;

struct TallSlider {
  int block = -1;         // the free block with the largest r, or -1 if none slides
  double reach = 0.0;     // its r = tan(phi_p) H / L
  double slope = 0.0;     // its face's inclination, degrees
  double friction = 0.0;  // the face's peak friction angle phi_p, degrees
  bool launched = false;  // given a velocity along the face (else it slides from rest)
};

// The free block with the largest r among those resting at t = 0 (a contact point within the
// slop) on a fixed block's face, without cohesion or tensile strength, that is steeper than the
// face's peak friction angle or along which the block is given a velocity. Detects the contacts
// once, as a run's first step would.
TallSlider tallest_slider(const Scene& scene, const BlockSystem& s);

}  // namespace ddafit
