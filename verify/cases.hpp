// The analytic verification scenes, defined once in code and shared by `ddafit verify`,
// the GoogleTest suite and the benchmarks. cases/verification/*.yaml are the same
// scenes for users to open and edit; a test keeps the two in step.
#pragma once

#include "forward/scene.hpp"

namespace ddafit::verification {

// Seed section 2.3: a 2.23 m x 2.05 m block on a 2:1 slope (alpha = 26.565 deg),
// peak friction phi, roughness i, d_c = 1 % of the block length along the slope.
struct InclineSetup {
  double friction_angle = 25.0;  // deg
  double roughness_angle = 0.0;  // deg
  double slope_ratio = 0.5;      // tan(alpha)
  double duration = 2.0;         // s
  double time_step = 1.0e-3;     // s
  double output_interval = 0.01; // s
};
constexpr double kInclineBlockLength = 2.23;  // m, along the slope
constexpr double kInclineBlockHeight = 2.05;  // m
Scene incline_scene(const InclineSetup& setup);

// A free block thrown under gravity, no contacts: a parabola, integrated exactly.
Scene thrown_block_scene();
// A square spinning freely without gravity at 2 pi rad/s.
Scene spinning_block_scene(double turns);
// Five 1 m blocks stacked on a fixed base.
Scene stack_scene();
// Two blocks in free space, one moving into the other at rest.
Scene collision_scene();

// A column of `blocks` equal b x H/blocks blocks (one: Housner's rocking block) tilted by
// tilt_share of its critical angle alpha = atan(b / H) about its right base corner (it leans
// right and falls back left), released from rest on a fixed floor 20 b wide (friction 42 deg:
// no slip); steps of `step` (of four substeps, the default). Material points at the column's
// base and top centres, 0.05 b inside it, give its tilt (verification::rocking_trace).
struct RockingSetup {
  double base = 1.0, height = 4.5;  // b, H (m)
  double tilt_share = 0.5;          // theta0 / alpha
  int blocks = 1;
  double duration = 6.0, step = 5.0e-3;  // s
};
Scene rocking_column_scene(const RockingSetup& setup);
// The verification case: RockingSetup's defaults, a 1 x 4.5 m block tilted alpha / 2.
Scene rocking_block_scene();

// Heyman's masonry arch (Int. J. Mech. Sci. 11, 1969): a semicircular arch of 15 voussoirs of
// mean radius 1 m and thickness `thickness_ratio` m on a fixed floor, friction 40 deg, no
// cohesion, 2 s at 1 ms. It stands under its own weight only if thickness_ratio >= 0.1075.
// A material point at the crown, on the mean radius.
Scene arch_scene(double thickness_ratio);

// A running-bond wall of `courses` x `per_course` bricks (1 m x 0.5 m) on a fixed floor:
// the benchmark's many-contact scene (100 blocks for 10 x 10).
Scene brick_wall_scene(int courses, int per_course, double duration);

// A scene with no blocks yet: one rock (E 5 GPa, nu 0.25) of `density` (kg/m^3) and one
// joint interface of `friction_angle` (deg), the default for every pair; gravity as Scene's.
Scene rock_scene(double density, double friction_angle, double duration, double step, double output_interval);

// A block of material 0 in its own group, named `name`.
BlockInput block(const std::string& name, std::vector<Vec2> polygon, bool fixed);

}  // namespace ddafit::verification
