// The directions the blocks were held up from in the last step, read from its manifolds in one
// pass: the supports that rank flush and proud faces (manifold.hpp) and the surfaces "Kink
// corners" takes the blocks to rest on. Internal to the contact stage (collide.cpp).
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/kinematics.hpp"

namespace ddafit {

// Per block, unit or zero.
// support (ManifoldSettings::support_a/b): the direction it was held up from, the mean normal,
// pointing into it, of its touching points that push it up (their normal against gravity by
// more than a tenth). A block none of whose points does (or a scene without gravity) takes all
// its touching points; a free block that touched nothing, the normal of its nearest point that
// would push it up (it lands: the rest below). Without it a 30 m slider landing at the foot of a
// 40 deg face had no support, and of two flush faces of the pair with the floor's first free
// block the one it lay closer to the line of was its own front face (the floor's corner 1 cm
// behind that face's line): a wall along the slide, which took 2 of its 18.7 m/s.
// Why only the points that push up: a block that carries another is pushed down by it as
// often as up by what it rests on, and counted together the two cancelled (until revision
// 2026-12-03.4): the block had no support, and at the first flush joint its front face took
// the joint face and held it there, a 2 x 0.125 m block carrying one as large stopped dead
// (docs/theory.md §3, "Flush faces"). Weighting every point by its load instead is not robust
// either: the implicit solver's loads swing by half within a step's open-close iterations,
// and a thin block under a heavy one (3 x 0.375 m under 3 x 1.125 m on a free row, 35 deg)
// was then pushed down on balance, took a joint face and fell 19 % behind seed Eq. 4.
// rest (ManifoldSettings::rest_a/b): the direction it rests along for "Kink corners"
// (manifold.hpp), the normal of the surface it is held up by: the same touching points that push
// it up where their normals agree (their mean at least kRestsOn long: one surface); if none
// touched, the normal of the nearest point that pushes it up, the surface it comes down on (it
// lands); none for a fixed block or one held by faces that disagree. A slider set down 0.1 mm
// above a 30 deg face, 2 cm before a 30 deg concave kink of free blocks, met the kink in the
// step it landed in and was thrown back. Not simply up: a 30 m slider flying tilted 45 deg past
// a convex kink has its base and its front face turned down alike, and the front face's line
// passed a joint's corner of the face below. Nor the mean of disagreeing supports: a voussoir
// of a falling arch, held at its two joints, read its intrados as the face it rested on.
// corner_held (ManifoldSettings::held_a/b), per vertex id of BlockSystem::vertices: the normal,
// into the corner's block, of the touching points that sit on that corner, where they agree
// (their mean at least kRestsOn long); zero for a corner that touched nothing or faces that
// disagree. A block straddling a concave kink (its rear corner on the face, its front on the
// floor) has a support between the two, and ranked by it the flush faces of its pair with the
// face's next block took its base; its rear corner still slides on the face (manifold.hpp,
// "Flush faces").
struct Supports {
  std::vector<Vec2> support;
  std::vector<Vec2> rest;
  std::vector<Vec2> corner_held;
};
Supports read_supports(const BlockSystem& s, const std::vector<ContactManifold>& previous, double slop,
                       const Vec2& gravity);

}  // namespace ddafit
