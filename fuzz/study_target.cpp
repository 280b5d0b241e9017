// The study reader through to the objective: the path where NaN, 1e308 and denormal
// numbers once passed --check and then crashed `invert` after Ceres reported an error.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz/targets.hpp"
#include "inverse/inversion.hpp"
#include "inverse/study.hpp"

namespace ddafit::fuzz {
namespace {

namespace fs = std::filesystem;

// Stand-in for the forward model: every summary value of every point is smooth in the
// numbers a study parameter can set on the two-slider scene, so the fit, the profile and
// the covariance all have work to do, in microseconds. A value the scene refuses never
// reaches it: StudyScene::run() reports that run as an invalid scene, as for the real model.
SimulationResult stand_in(const Scene& scene) {
  SimulationResult r;
  double sum = scene.max_step + scene.duration;
  for (const Interface& f : scene.interfaces)
    sum += f.friction_angle + f.roughness_angle + f.cohesion + f.critical_distance_ratio;
  for (const MeasurePoint& m : scene.measure) {
    const double v = 1.0 + 0.01 * sum;
    r.summary.points.push_back({m.name, v, 1.1 * v, 0.5 * v, 0.6 * v, 2.0 + std::sin(sum), false});
  }
  r.summary.run.simulated_time = scene.duration;
  return r;
}

}  // namespace

int study(const std::uint8_t* data, std::size_t size) {
  const fs::path dir = scratch_folder();
  static const bool scene_copied = [&] {
    fs::copy_file(fs::path(DDAFIT_CASES_DIR) / "inverse" / "two_sliders.yaml", dir / "two_sliders.yaml",
                  fs::copy_options::overwrite_existing);
    return true;
  }();
  (void)scene_copied;
  {
    std::ofstream out(dir / "study.yaml", std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  inverse::Study s;
  try {
    s = inverse::read_study((dir / "study.yaml").string());
    inverse::check_study_against_scene(s);
  } catch (const inverse::StudyError& e) {
    check_message(e.what());
    return 0;
  }
  // Keep one input to a fraction of a second: a few runs per fit, two levels at most.
  s.method.budget = std::min(s.method.budget, 6);
  s.method.fine_budget = std::min(s.method.fine_budget, 6);
  s.profile.points = std::min(s.profile.points, 3);
  for (inverse::Parameter& p : s.parameters)
    if (p.levels.size() > 2) p.levels.resize(2);
  inverse::InversionOptions options;
  options.out_dir = (dir / "out").string();
  fs::remove_all(options.out_dir);
  try {
    const inverse::InversionSummary summary = inverse::run_inversion(s, options, stand_in);
    for (const inverse::LevelFit& level : summary.levels)
      if (std::isnan(level.best.chi2)) finding("a NaN chi2 in the report");
  } catch (const inverse::InversionError& e) {
    check_message(e.what());
  }
  return 0;
}

}  // namespace ddafit::fuzz
