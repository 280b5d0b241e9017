#include "forward/substep/quiet_start.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

#include "forward/common/supported_blocks.hpp"
#include "forward/contact/slip_history.hpp"
#include "forward/parallel.hpp"
#include "forward/substep/advance_step.hpp"

namespace ddafit {
namespace {

// The quiet start stops once no point's normal impulse changes over a step by more than
// kQuietStartTolerance of the largest, or after control.quiet_start_steps steps (options.hpp
// says why a landslide runs them all). A heavy block on a light one (mass ratio 100) needs
// the 1e-4: stopped at 1e-3 it rocked itself up within 0.06 s (test_substep_scenes.cpp); at
// 1e-4 it settles within 100 steps and moves 2 um.
constexpr double kQuietStartTolerance = 1e-4;

// The normal impulses of the last substep, two slots per manifold (a manifold has at most two
// points). Both passes run on all threads: each reads every 576-byte manifold, in every quiet
// step, and a largest change is the same whatever the order it is found in.
void last_normal_impulses(const std::vector<ContactManifold>& manifolds, std::vector<double>& out) {
  const long n = static_cast<long>(manifolds.size());
  out.resize(2 * manifolds.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k)
    for (int q = 0; q < manifolds[k].point_count; ++q) out[2 * k + q] = manifolds[k].points[q].impulse.normal;
}

// Largest change of any point's normal impulse over the step, relative to the largest:
// `before` holds the impulses each point carried into the step (last_normal_impulses).
double impulse_change(const std::vector<ContactManifold>& manifolds, const std::vector<double>& before) {
  const long n = static_cast<long>(manifolds.size());
  double largest = 0.0, change = 0.0;
#pragma omp parallel for schedule(static) reduction(max : largest, change) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k)
    for (int q = 0; q < manifolds[k].point_count; ++q) {
      const double normal = manifolds[k].points[q].impulse.normal;
      largest = std::max(largest, std::abs(normal));
      change = std::max(change, std::abs(normal - before[2 * k + q]));
    }
  return largest > 0.0 ? change / largest : 0.0;
}

// Quiet start: the contacts touching at t = 0 take up the weight before the clock runs, for
// the blocks resting on the ground (common/supported_blocks.hpp).
// Steps of the scene's length with those blocks at rest before each (a given velocity
// waits for the clock: until revision 2026-11-27.7 the first step carried a touching block
// v dt before t = 0, 5 cm for a block given 5 m/s at 10 ms, tests/test_impact_depth.cpp), their
// strain following their contacts, until no normal impulse changes by more than
// kQuietStartTolerance of the largest. Blocks in flight stay exactly as given, held still:
// through revision 2026-11-27.8 they kept their velocity while held, so a block given 2 m/s
// 1 mm above a stack pressed it down 5.6 mm through the quiet start and the impulses built up
// launched everything at the first step (tests/test_impact_rebound.cpp); the
// measurement points' origins move with the blocks, and no slip is counted: the slide
// starts from rest, not with a bounce.
std::string settle_from_rest(SubstepContext& w, double step) {
  BlockSystem& s = w.system;
  CollideSettings& settings = w.detection.settings;
  ScopedTimer timer(w.profile->settle);
  StepProfile* const run_profile = w.profile;
  StepProfile ignored;
  w.profile = &ignored;
  const auto restore = [&] { w.profile = run_profile; };
  if (std::string problem = find_step_contacts(w); !problem.empty()) {
    restore();
    return problem;
  }
  const std::vector<char> resting = supported_blocks(s, w.contacts.manifolds, settings.linear_slop);
  std::vector<Vec6> initial(s.blocks.size());
  std::vector<char> was_fixed(s.blocks.size());
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    initial[b] = s.blocks[b].velocity;
    was_fixed[b] = s.blocks[b].fixed;
    if (!resting[b]) s.blocks[b].fixed = true;  // in flight: takes no part
  }
  std::vector<double> before;
  w.settling = true;
  w.report.quiet_start_steps = 0;
  w.report.quiet_start_change = 0.0;
  for (int k = 0; k < w.options.quiet_start_steps; ++k) {
    w.threads.begin_step();
    if (k > 0) find_step_contacts(w);
    last_normal_impulses(w.contacts.manifolds, before);
    for (size_t b = 0; b < s.blocks.size(); ++b)  // held blocks too: a held block's velocity
      if (!was_fixed[b]) s.blocks[b].velocity.setZero();  // still drives its contacts
    advance_step(w, step, false);
    w.threads.end_step();
    w.report.quiet_start_steps = k + 1;
    w.report.quiet_start_change = impulse_change(w.contacts.manifolds, before);
    if (w.report.quiet_start_change <= kQuietStartTolerance) break;
  }
  w.settling = false;
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    s.blocks[b].fixed = was_fixed[b];
    s.blocks[b].velocity = initial[b];
  }
  reset_histories(s, w.contacts);
  settings.first_step = true;  // bonds form between the blocks touching once settled
  restore();
  return {};
}

// The step, as a share of sqrt(L / |g|) (L a block's size, the square root of its area), up to
// which a block resting on its corner keeps its tilt through the quiet start: at 0.03 every block
// of the class of tests/test_rocking.cpp (0.1-10 m, H/b 3 and 6, tilted 0.1-0.6 of its critical
// angle, one and four substeps) starts within 0.7 % of its tilt; at 0.05 those tilted 0.1 fall.
constexpr double kKeepsTiltStepRatio = 0.03;

// The free block turned most since `given` (the vertices before the quiet start), and by how
// much, rad (-1 and 0 if none turned).
std::pair<int, double> most_turned(const BlockSystem& s, const std::vector<Vec2>& given) {
  double most = 0.0;
  int which = -1;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const Block& block = s.blocks[b];
    if (block.fixed) continue;
    const Vec2 before = given[block.first_vertex + 1] - given[block.first_vertex];
    const Vec2 after = s.vertices[block.first_vertex + 1] - s.vertices[block.first_vertex];
    const double turn = std::abs(std::atan2(before.x() * after.y() - before.y() * after.x(), before.dot(after)));
    if (turn > most) most = turn, which = b;
  }
  return {which, most};
}

// The step up to which a block of size `size` (m) resting on its corner keeps its tilt through
// the quiet start under gravity `g` (m/s^2); infinite without gravity.
double keeps_tilt_step(double size, double g) {
  return g > 0.0 ? kKeepsTiltStepRatio * std::sqrt(size / g) : std::numeric_limits<double>::infinity();
}

// That step for the smallest free block, or the scene's step if that is shorter.
double tilt_keeping_step(const Scene& scene, const BlockSystem& s) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Block& b : s.blocks)
    if (!b.fixed) smallest = std::min(smallest, std::sqrt(b.area));
  if (!std::isfinite(smallest)) return scene.max_step;
  return std::min(scene.max_step, keeps_tilt_step(smallest, scene.gravity.norm()));
}

// What the quiet start changes, as given, so that it can be done again.
struct GivenState {
  BlockSystem system;
  ContactSet contacts;
  SweepState state;
  SleepState sleep;
  WorstOverlap worst;
  SolverReport report;
};

}  // namespace

std::string settle_before_the_clock(SubstepContext& w, std::vector<std::string>& warnings) {
  BlockSystem& s = w.system;
  const Scene& scene = w.scene;
  const std::vector<Vec2> given_vertices = s.vertices;
  // A block turned by the quiet start at the scene's step: settle again from the given scene at
  // steps that keep a block on its corner where it is (model revision 2026-12-06.2). Stacks and
  // Vajont's sections turn no block that far (1.0e-3 and 7.1e-3 rad at most) and keep their
  // quiet start; at the shorter steps a standing stack would sink after t = 0 from the shorter
  // steps' joint depth, about 1.5 g h^2 (docs/theory.md, Known limits (k)). Where the scene's
  // step is already that short (every Vajont section) nothing is kept to do it again.
  const double keeps = tilt_keeping_step(scene, s);
  std::optional<GivenState> given;
  if (keeps < scene.max_step) given = GivenState{s, w.contacts, w.state, w.sleep, w.worst, w.report};
  if (std::string problem = settle_from_rest(w, scene.max_step); !problem.empty()) return problem;
  if (given && most_turned(s, given_vertices).second > kQuietStartTurnLimit) {
    s = std::move(given->system);
    w.contacts = std::move(given->contacts);
    w.state = std::move(given->state);
    w.sleep = std::move(given->sleep);
    w.worst = given->worst;
    w.report = std::move(given->report);
    w.last_substep = 0.0;
    if (std::string problem = settle_from_rest(w, keeps); !problem.empty()) return problem;
  }
  if (std::string turned = quiet_start_warning(scene, s, given_vertices); !turned.empty())
    warnings.push_back(std::move(turned));
  return {};
}

std::string quiet_start_warning(const Scene& scene, const BlockSystem& s, const std::vector<Vec2>& given) {
  const auto [which, most] = most_turned(s, given);
  if (which < 0 || most <= kQuietStartTurnLimit) return {};
  const double size = std::sqrt(s.blocks[which].area);
  std::ostringstream out;
  out.precision(3);
  out << "block '" << s.block_names[which] << "' turned " << most * 180.0 / M_PI
      << " deg before t = 0, while the contacts took up the weight from rest (the quiet start): it is not in "
         "equilibrium where it was given, and the run starts it turned (docs/theory.md, known limits (k)); ";
  const double keeps = keeps_tilt_step(size, scene.gravity.norm());
  if (scene.max_step > keeps)
    out << "time.step " << scene.max_step << " s is long for it (a block of its size, " << size
        << " m, resting on a corner keeps its tilt at steps up to about " << keeps << " s), or use ";
  else
    out << "use ";
  out << "time.integrator: implicit, whose settling holds a falling block where it was given";
  return out.str();
}

}  // namespace ddafit
