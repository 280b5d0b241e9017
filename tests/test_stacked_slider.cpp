// A slab of blocks sliding across the joints of a slope: the commonest event of a jointed
// slide is not one block on the bedrock but a block that carries others. Each block of a
// rigid slab sliding on a plane at friction phi follows seed Eq. 4 whether the blocks above it
// ride with it or slip on it at their own cap (a block on top at Eq. 4's rate needs exactly
// tan(phi) of its weight's normal part from the one below, which passes it on to the plane),
// so every block of the slab is checked against Eq. 4. Asserted as a class: slabs cut into
// 1 x 2, 2 x 2, 3 x 1 and 1 x 3 blocks (columns x layers; the bottom layer half or a quarter
// of the height), their ends and cuts upright or leaning 30 deg either way; joints of the slope
// across it or oblique (from the slope's normal by -50 to 50 deg); four slopes and frictions;
// slabs 0.5-3 m long; joints every 0.3, 1 and 2.5 m; at rest and at 4 m/s; both solvers. A
// slab whose blocks would topple by themselves (the line of their weight, in the slab's frame
// sliding or at rest, outside the middle 60 % of their base) is left out.
//
// Found 2026-12-03 (model revision .12.03.3): a 2 x 0.125 m block carrying another as large
// stopped dead where its front corner first crossed a flush joint (substep solver; the
// implicit solver held it there 0.2 s, and it fell 0.28 m behind Eq. 4 in 1.5 s), while the
// same pair as one 2 x 0.25 m block crossed: the "Flush faces" and "Proud edges" rules
// (forward/contact/manifold.hpp) rank the faces a corner meets by the direction the block was
// pushed in the last step, and that direction counted each touching point once, so the push
// down from the block above cancelled the push up from the slope. Now only the points that
// push a block up count (forward/contact/collide.cpp, supports).
//
// Tolerances and why: test_joint_crossing.cpp's (1 % of Eq. 4 at every output where a block
// has moved 1 cm; the energy audit and overlaps of contact_scene_audit.hpp). A hooked block
// falls 10-100 % behind.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

struct Slab {
  Crossing c;               // slope, friction, the slab's length and height, joint spacing, speed
  double joint = 0.0;       // the slope's joints from its normal, deg (+: their foot downslope)
  double lean = 0.0;        // the slab's ends and cuts from the slope's normal, deg (+: top downslope)
  int columns = 1, layers = 2;
  double bottom_share = 0.5;  // the bottom layer's share of the height (two layers or more)
};

std::string describe(const Slab& s, Integrator integrator) {
  char text[360];
  std::snprintf(text, sizeof text, "%s, a slab of %d x %d blocks (bottom %.2f of it), leaning %+g deg, joints at %+g deg",
                describe(s.c, integrator).c_str(), s.columns, s.layers, s.bottom_share, s.lean, s.joint);
  return text;
}

// The bottom of layer l above the slope, as a share of the slab's height.
double layer_floor(const Slab& s, int l) {
  if (l == 0) return 0.0;
  const double rest = (1.0 - s.bottom_share) / (s.layers - 1);
  return s.bottom_share + (l - 1) * rest;
}

// The slab's blocks in the slope's frame (along, up), counter-clockwise, its rear foot at the origin.
std::vector<std::vector<Vec2>> slab_blocks(const Slab& s) {
  const double shear = std::tan(s.lean * kDegree), w = s.c.length / s.columns;
  std::vector<std::vector<Vec2>> out;
  for (int l = 0; l < s.layers; ++l) {
    const double h0 = s.c.height * layer_floor(s, l);
    const double top = l + 1 == s.layers ? s.c.height : s.c.height * layer_floor(s, l + 1);
    for (int m = 0; m < s.columns; ++m) {
      const double x = m * w;
      out.push_back({{x + shear * h0, h0}, {x + w + shear * h0, h0}, {x + w + shear * top, top}, {x + shear * top, top}});
    }
  }
  return out;
}

// Whether every block stands by itself on what is under it: the line of its weight through its
// centroid, tilted from the slope's normal by `tilt` degrees downslope, meets its base (within
// the slab's length) in the middle 60 %.
bool blocks_stand(const Slab& s, double tilt) {
  for (const std::vector<Vec2>& b : slab_blocks(s)) {
    const Vec2 c = centroid_of(b);
    const double foot = c.x() + (c.y() - b[0].y()) * std::tan(tilt * kDegree);
    const double lo = std::max(b[0].x(), 0.0), hi = std::min(b[1].x(), s.c.length), w = b[1].x() - b[0].x();
    if (foot < lo + 0.2 * w || foot > hi - 0.2 * w) return false;
  }
  return true;
}

Scene slab_scene(const Slab& s, Integrator integrator) {
  const Crossing& c = s.c;
  Scene scene = base_scene(kDuration, kStep, kOutput, integrator);
  scene.default_interface = add_interface(scene, "slope", c.friction);
  // Between the slab's blocks a rougher joint, so that they ride together.
  const int slab = add_interface(scene, "slab", std::min(c.friction + 15.0, 50.0));
  scene.contact_rules = {{"slab", "slab", slab}};
  const Slope slope(c.slope);
  const double travel = c.speed * kDuration + 0.5 * std::max(eq4_acceleration(c.slope, c.friction), 1.0) * kDuration * kDuration;
  int k = 1;
  while (k * c.spacing - c.front_gap - c.length < 0.2) ++k;
  const double rear = k * c.spacing - c.front_gap - c.length;
  const int blocks = static_cast<int>(std::ceil((rear + c.length + travel + 1.0) / c.spacing));
  const double foot = std::tan(s.joint * kDegree);
  for (int j = 0; j < blocks; ++j) {
    const double s0 = j * c.spacing, s1 = s0 + c.spacing;
    scene.blocks.push_back(block("base_" + std::to_string(j),
                                 {slope.at(s0, 0), slope.at(s0 + foot, -1), slope.at(s1 + foot, -1), slope.at(s1, 0)},
                                 true, 0, "base"));
  }
  int n = 0;
  for (const std::vector<Vec2>& b : slab_blocks(s)) {
    std::vector<Vec2> world;
    for (const Vec2& p : b) world.push_back(slope.at(rear + p.x(), p.y()));
    BlockInput piece = block("slab_" + std::to_string(n++), world, false, 0, "slab");
    piece.velocity = c.speed * slope.along;
    scene.measure.push_back({piece.name, centroid_of(world)});
    scene.blocks.push_back(piece);
  }
  return scene;
}

// The sweep: every joint angle with every cut and slope; sizes, spacings, leans, bottom shares
// and speeds rotated through them at different periods, so that each value meets several others.
std::vector<Slab> slab_sweep() {
  const double slopes[][2] = {{28, 18}, {20, 12}, {40, 25}, {35, 33}};
  const double sizes[][2] = {{1.2, 0.6}, {2.0, 0.25}, {3.0, 0.8}, {0.5, 0.5}, {2.0, 1.0}};
  const double spacings[] = {0.3, 1.0, 2.5};
  const int cuts[][2] = {{1, 2}, {2, 2}, {3, 1}, {1, 3}};
  const double leans[] = {0.0, 30.0, -30.0};
  std::vector<Slab> out;
  int n = 0;
  for (const double joint : {-50.0, -25.0, 0.0, 25.0, 50.0})
    for (const auto& cut : cuts)
      for (const auto& slope : slopes) {
        Slab s;
        s.c = sweep_case(slope, sizes[n % 5], spacings[n % 3], n);
        s.c.speed = (n / 2) % 2 ? 4.0 : 0.0;
        s.joint = joint;
        s.columns = cut[0];
        s.layers = cut[1];
        s.lean = leans[(n / 4) % 3];
        s.bottom_share = s.layers > 1 && (n / 3) % 2 ? 0.25 : 0.5;
        ++n;
        if (blocks_stand(s, s.c.slope) && blocks_stand(s, s.c.friction)) out.push_back(s);
      }
  return out;
}

// Every block's run down the slope against Eq. 4 (slide_error, test_joint_crossing.cpp's rule).
double worst_block_error(const SimulationResult& r, const Crossing& c, size_t blocks, std::string* which) {
  const Slope slope(c.slope);
  const double a = eq4_acceleration(c.slope, c.friction);
  double worst = 0.0;
  for (size_t q = 0; q < blocks; ++q) {
    SimulationResult one;
    for (const HistoryRow& h : r.history)
      if (h.point == static_cast<int>(q)) one.history.push_back(h);
    const SlideError e = slide_error(one, slope, [&](const std::vector<double>& times) {
      std::vector<double> exact;
      for (const double t : times) exact.push_back(c.speed * t + 0.5 * a * t * t);
      return exact;
    });
    if (e.worst > worst) {
      worst = e.worst;
      char text[96];
      std::snprintf(text, sizeof text, "block %zu at t = %.2f s", q, e.when);
      *which = text;
    }
  }
  return worst;
}

// How a slab is run: the sweep's own 1 ms steps and 10 ms outputs unless set.
struct SlabRun {
  double step = 0.0;  // s, with `substeps` (0: the sweep's 1 ms)
  int substeps = 0;
  bool mirrored = false;  // descending to the left
  double output = 0.0;    // s between outputs (0: the sweep's 10 ms); a step is cut to land on each
  bool even_joints = false;  // the slab's own joints as rough as the slope, not rougher
};

// One slab's run: the checks of contact_scene_audit.hpp, then every block against Eq. 4; returns
// the worst block's error and names it in *label.
double expect_slab_follows_eq4(const Slab& s, Integrator integrator, const SlabRun& run, std::string* label) {
  Scene scene = slab_scene(s, integrator);
  *label = describe(s, integrator);
  char text[160];
  if (run.step > 0.0) {
    scene.max_step = run.step;
    scene.options.substeps = run.substeps;
    std::snprintf(text, sizeof text, ", %g ms x %d", 1e3 * run.step, run.substeps);
    *label += text;
  }
  if (run.output > 0.0) {
    scene.output_interval = run.output;
    std::snprintf(text, sizeof text, ", outputs every %g ms", 1e3 * run.output);
    *label += text;
  }
  if (run.even_joints) {  // slab_scene's one rule is the slab's own joints
    scene.interfaces[scene.contact_rules[0].interface].friction_angle = s.c.friction;
    *label += ", even joints";
  }
  if (run.mirrored) scene = mirrored_scene(scene), *label += ", descending to the left";
  RunAudit audit;
  SimulationResult r = simulate(scene, audit_hooks(audit, scene.gravity));
  if (run.mirrored) unmirror_history(r.history);
  expect_contact_physics(r, audit, integrator, *label);
  std::string which;
  const double error = worst_block_error(r, s.c, scene.measure.size(), &which);
  EXPECT_LT(error, kDisplacementTolerance) << *label << ": " << which;
  *label += ", " + which;
  return error;
}

class StackedSlider : public ::testing::TestWithParam<Integrator> {};

TEST_P(StackedSlider, EveryBlockOfASlabFollowsSeedEq4AcrossJoints) {
  const Integrator integrator = GetParam();
  const std::vector<Slab> sweep = slab_sweep();
  ASSERT_GE(sweep.size(), 50u) << "the sweep lost its cases to the toppling filter";
  double worst = 0.0;
  std::string worst_case, label;
  for (const Slab& s : sweep) {
    const double error = expect_slab_follows_eq4(s, integrator, SlabRun{}, &label);
    if (error > worst) worst = error, worst_case = label;
  }
  std::printf("[measured] %s: %zu slabs, every block within %.2g of seed Eq. 4 (worst: %s)\n", name_of(integrator).c_str(),
              sweep.size(), worst, worst_case.c_str());
}

// Every other slab of the sweep, run each way of `runs`; prints the worst block as `what`.
void expect_every_other_slab_follows_eq4(Integrator integrator, const std::vector<SlabRun>& runs, const char* what) {
  const std::vector<Slab> sweep = slab_sweep();
  double worst = 0.0;
  int count = 0;
  std::string worst_case, label;
  for (size_t k = 0; k < sweep.size(); k += 2)
    for (const SlabRun& run : runs) {
      const double error = expect_slab_follows_eq4(sweep[k], integrator, run, &label);
      if (error > worst) worst = error, worst_case = label;
      ++count;
    }
  std::printf("[measured] %s: %d slabs %s, every block within %.2g of seed Eq. 4 (worst: %s)\n",
              name_of(integrator).c_str(), count, what, worst, worst_case.c_str());
}

// Every other slab of the sweep at the Vajont scenes' steps (5 ms x 4 substeps, 10 ms x 3; the
// implicit solver takes the step alone), descending to the right and, mirrored, to the left: a
// coarse step lets a corner cross further into a joint in one step, and the mirror puts the
// blocks' corners and the pairs in the other order.
void expect_slabs_follow_eq4_at_coarse_steps(Integrator integrator) {
  std::vector<SlabRun> runs;
  for (const auto& [step, substeps] : {std::pair{0.005, 4}, {0.01, 3}})
    for (const bool mirrored : {false, true}) runs.push_back({step, substeps, mirrored});
  expect_every_other_slab_follows_eq4(integrator, runs, "at 5 and 10 ms steps, both ways down");
}

// The implicit solver: 116 runs, every block within 5.4e-3 (a 2 x 1 m slab of 2 x 2 blocks
// leaning -30 deg at 20/12 deg, 5 ms, descending to the left: 65 um at 1 cm travelled).
TEST(StackedSliderCoarseSteps, EveryBlockOfASlabFollowsSeedEq4BothWaysDownImplicit) {
  expect_slabs_follow_eq4_at_coarse_steps(Integrator::Implicit);
}

// The substep solver: 116 runs, every block within 5.0e-3 (a 2 x 0.25 m slab of 2 x 2 blocks
// leaning -30 deg at 20/12 deg over joints at -25 deg, 10 ms x 3, descending to the left).
// Found 2026-12-03 (revision .12.03.4, fixed at .12.03.5): a 3 x 0.8 m slab of 2 x 2 blocks
// (bottom layer a quarter of the height) leaning +30 deg at 28/18 deg over joints at +25 deg,
// 10 ms x 3, fell 2.2 % off Eq. 4 (0.6 mm at 0.18 s; 1.9e-3 now). Its four blocks meet at one
// corner on the cut leaning through both layers, and the bottom front block and the top rear one
// touch only there. The top layer rests 16 um deep in the bottom one (about the slop), so the
// top rear block's corner overlaps the bottom front one by that along the layers' face and, as
// the top layer also shears forward, by a little less along the leaning cut's. "Proud edges"
// (manifold.hpp), which keeps the face the blocks are held up through, acted only up to h = the
// slop, and once the overlap passed it (1.565e-5 m against 1.560e-5 m) the separating axis took
// the cut's face and pushed the two columns apart (9 mm after 0.8 s). The rule now acts up to 2h.
TEST(StackedSliderCoarseSteps, EveryBlockOfASlabFollowsSeedEq4BothWaysDownSubstep) {
  expect_slabs_follow_eq4_at_coarse_steps(Integrator::Substep);
}

// Steps of unequal length. The step control shortens a step where a block in contact would
// move too far, and a step ends on each output time, so a run's steps are seldom equal; the
// answer must not depend on where they are cut. Every other slab of the sweep at 10 ms x 3 with
// outputs every 10 ms (the step control's own cuts), 10.4 ms and 13 ms, both ways down.
// Found 2026-12-03 (model revision .12.03.5, mended at .12.03.6): the substep solver handed each
// point's impulse of the last substep to the next step unscaled, and cut the last step before an
// output to a sliver (0.4 ms after 10 ms), whose impact margins (|g| h) were so tight that the
// sweeps' ordinary residuals counted as impacts. A 3 x 0.8 m slab of 2 x 2 blocks leaning +30 deg
// at 28/18 deg with outputs every 10.4 ms fell 4.2 % off Eq. 4 at 0.11 s (2.4 % with the
// impulses scaled, 2.5 % with the steps evened alone, 0.5 % with both: rescale_warm_start in
// forward/substep/solve_contacts.hpp, RunRecorder::even_step in forward/run_record.hpp).
void expect_slabs_follow_eq4_whatever_cuts_the_steps(Integrator integrator) {
  std::vector<SlabRun> runs;
  for (const double output : {0.01, 0.0104, 0.013})
    for (const bool mirrored : {false, true}) runs.push_back({0.01, 3, mirrored, output});
  expect_every_other_slab_follows_eq4(integrator, runs, "with steps cut by outputs");
}

TEST(StackedSliderStepLengths, EveryBlockOfASlabFollowsSeedEq4WhereverItsStepsAreCutSubstep) {
  expect_slabs_follow_eq4_whatever_cuts_the_steps(Integrator::Substep);
}

TEST(StackedSliderStepLengths, EveryBlockOfASlabFollowsSeedEq4WhereverItsStepsAreCutImplicit) {
  expect_slabs_follow_eq4_whatever_cuts_the_steps(Integrator::Implicit);
}

// The slab that found it (model revision .12.03.5): upright, 1.2 x 0.6 m cut into 2 x 2 blocks,
// at 40/25 deg over joints at -55 deg 1 m apart, its own joints as rough as the slope (each
// block then needs exactly its cap from the one below, so a kick between the blocks is never
// taken back), 10 ms x 3, descending to the left: the rear bottom block fell 1.46 % behind seed
// Eq. 4 from where the front crossed a joint (a 9.4 ms step and a 0.6 ms one before each output,
// the short one warm-started with 16 times the load); 1e-4 since. With its neighbours: front gaps
// of 1, 3 and 5 cm, joints at +-30 and +-55 deg, 5 ms x 4 and 10 ms x 3, both ways down.
TEST(StackedSliderStepLengths, AnUprightSlabOnEvenJointsFollowsSeedEq4AcrossObliqueJointsSubstep) {
  double worst = 0.0;
  int runs = 0;
  std::string worst_case, label;
  for (const double gap : {0.01, 0.03, 0.05})
    for (const double joint : {-55.0, -30.0, 30.0, 55.0})
      for (const auto& [step, substeps] : {std::pair{0.005, 4}, {0.01, 3}})
        for (const bool mirrored : {false, true}) {
          Slab s;
          s.c.slope = 40.0, s.c.friction = 25.0, s.c.length = 1.2, s.c.height = 0.6, s.c.spacing = 1.0;
          s.c.front_gap = gap;
          s.joint = joint;
          s.columns = 2;
          const double error =
              expect_slab_follows_eq4(s, Integrator::Substep, SlabRun{step, substeps, mirrored, 0.0, true}, &label);
          if (error > worst) worst = error, worst_case = label;
          ++runs;
        }
  std::printf("[measured] %d upright slabs on even joints, every block within %.2g of seed Eq. 4 (worst: %s)\n", runs,
              worst, worst_case.c_str());
}

// A two-layer slider on a row of free blocks 0.3 m thick that rest on a fixed plane (held to it
// and to each other at 60 deg): the row's blocks under the slider sink micrometres deeper than
// the one ahead (test_free_row.cpp, "Proud edges"). Slopes 15/8, 28/18 and 35/5 deg; rows of
// 0.4 and 1.0 m blocks; sliders 3 x 1.5, 1.2 x 0.6 and 2 x 0.5 m, the bottom block a quarter,
// half and 0.3 of the height. Both blocks within 1 % of Eq. 4 and overlaps under 1 %. Found
// while choosing the support rule: weighted by the points' loads, the implicit solver's 3 x
// 0.375 m block under a 3 x 1.125 m one at 35/5 deg, row of 1.0 m, took a joint face at 2.9 m
// and fell 19 % behind Eq. 4 (docs/theory.md §3). The implicit solver's rows of 0.4 m at 28
// and 35 deg are left out (a minute of the suite's time; its single-block row tests cover them).
TEST_P(StackedSlider, ATwoLayerSliderCrossesARowOfFreeBlocks) {
  const Integrator integrator = GetParam();
  double worst = 0.0;
  int runs = 0;
  for (const auto& [slope_angle, friction] : {std::pair{15.0, 8.0}, {28.0, 18.0}, {35.0, 5.0}})
    for (const double row_length : {0.4, 1.0})
      for (const auto& [length, height, bottom] : {std::tuple{3.0, 1.5, 0.25}, {1.2, 0.6, 0.5}, {2.0, 0.5, 0.3}}) {
        if (integrator == Integrator::Implicit && row_length < 0.5 && slope_angle > 20.0) continue;
        Scene s = base_scene(kDuration, kStep, kOutput, integrator);
        const int holds = add_interface(s, "holds", 60.0);
        const int slides = add_interface(s, "slides", friction);
        const int rough = add_interface(s, "rough", std::min(friction + 15.0, 50.0));
        s.contact_rules = {{"plane", "row", holds}, {"row", "row", holds}, {"slider", "row", slides},
                           {"slider", "slider", rough}};
        s.default_interface = slides;
        const Slope slope(slope_angle);
        const double row_height = 0.3, plane = 14.0, rear = 0.1;
        int row_blocks = 0;
        while (row_blocks * row_length < plane - 1e-9) ++row_blocks;
        add_plane_and_free_row(s, slope, plane, row_length, row_height, row_blocks);
        const double h0 = bottom * height;
        s.blocks.push_back(
            block("bottom", box(slope.at(rear, row_height), slope.along, slope.up, length, h0), false, 0, "slider"));
        s.blocks.push_back(block("top", box(slope.at(rear, row_height + h0), slope.along, slope.up, length, height - h0),
                                 false, 0, "slider"));
        s.measure.push_back({"bottom", slope.at(rear + 0.5 * length, row_height + 0.5 * h0)});
        s.measure.push_back({"top", slope.at(rear + 0.5 * length, row_height + 0.5 * (h0 + height))});
        const SimulationResult r = simulate(s);
        char label[200];
        std::snprintf(label, sizeof label, "%s: %g/%g deg, row of %g m, slider %g x %g m (bottom %g of it)",
                      name_of(integrator).c_str(), slope_angle, friction, row_length, length, height, bottom);
        ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
        EXPECT_LT(r.summary.solver.worst_penetration_ratio, kMaxPenetrationRatio) << label;
        Crossing c;
        c.slope = slope_angle, c.friction = friction, c.speed = 0.0;
        std::string which;
        const double error = worst_block_error(r, c, s.measure.size(), &which);
        EXPECT_LT(error, kDisplacementTolerance) << label << ": " << which;
        worst = std::max(worst, error);
        ++runs;
      }
  std::printf("[measured] %s: %d two-layer sliders over free rows, both blocks within %.2g of seed Eq. 4\n",
              name_of(integrator).c_str(), runs, worst);
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, StackedSlider, ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& info) { return name_of(info.param); });

}  // namespace
}  // namespace ddafit
