// A back-analysis study: which scene, which scene values are free, what was observed,
// and how to search. Plain data; read_study() fills it from YAML and checks it once, at
// the boundary, so the optimisers never see an impossible setting.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "forward/io/scene_reader.hpp"

namespace ddafit::inverse {

// A study file that cannot be used. what() is one line, "FILE: KEY: PROBLEM".
struct StudyError : std::runtime_error {
  explicit StudyError(const std::string& message) : std::runtime_error(io::SceneReadError::one_line(message)) {}
};

// A scene value the search may change, set through the scene reader's overrides.
struct Parameter {
  std::string name;          // the study's name, used in reports
  std::string key;           // scene key it sets, e.g. "interfaces.clay.degradation_percent"
  double lower = 0.0;        // bounds, in the parameter's units; lower < upper
  double upper = 0.0;
  double start = 0.0;        // first guess, inside [lower, upper]
  double resolution = 0.0;   // > 0: the smallest change that matters; sets steps and stopping
  // Non-empty: a discrete parameter (block size), fitted level by level. A block size's first
  // level may be `sled` (kSledLevel): the study's sled at fidelity 0 (forward/sled/), cut at the
  // next level's block size for its slices and d_c.
  std::vector<double> levels;
  bool sled_first = false;  // levels[0] is `sled` (written so in the study), not a block size

  bool discrete() const { return !levels.empty(); }
  // The level a single model run stands for (a study's spread, a scan): the first, or the
  // first block size after `sled`.
  double first_model_level() const { return sled_first ? levels[1] : levels.front(); }
};

// How an observation enters the misfit. Equal: ((sim - value)/sigma)^2 always. AtMost and
// AtLeast are one-sided field limits ("45 s or less"): the same term, but only when the
// limit is violated, so a simulation inside the limit adds nothing.
enum class ObservationKind { Equal, AtMost, AtLeast };

struct Observation {
  std::string point;     // a measure point of the scene
  std::string quantity;  // a PointSummary field, e.g. "max_lateral_displacement"
  double value = 0.0;
  double sigma = 0.0;    // > 0, same units as value
  ObservationKind kind = ObservationKind::Equal;
  // The model's own spread in the simulated value (a chaotic run's scatter, issue "Trust
  // the answer"), added to sigma in quadrature: sigma_eff = sqrt(sigma^2 + model_sigma^2).
  // Given in the study, or measured (model_sigma: ensemble) as the standard deviation over
  // the study's ensemble at the start point, once, before the fit.
  double model_sigma = 0.0;
  bool model_sigma_from_ensemble = false;
  // quantity deposit_rms (no point): the RMS of the run's final ground surface
  // (SimulationSummary::final_surface) against `surface`, over columns with x in [from, to], m.
  std::vector<Vec2> surface;
  double from = 0.0, to = 0.0;
  bool is_deposit() const { return quantity == kDepositQuantity; }
  static constexpr const char* kDepositQuantity = "deposit_rms";
  double effective_sigma() const { return std::sqrt(sigma * sigma + model_sigma * model_sigma); }
};

enum class Optimizer { Nlopt, Ceres };

// The level `sled` of a mesh.block_size parameter (no block size is 0).
inline constexpr double kSledLevel = 0.0;

struct MethodOptions {
  Optimizer optimizer = Optimizer::Nlopt;
  std::string algorithm = "LN_BOBYQA";  // NLopt only: LN_BOBYQA, LN_SBPLX or GN_DIRECT_L
  int budget = 100;                     // objective evaluations per fit (per level), cached or run
  double step_tolerance = 0.5;          // stop when a step is below this x each resolution
  double chi2_tolerance = 1e-4;         // stop when chi^2 changes by less than this (absolute)
  // How the levels of a discrete parameter are fitted:
  //   independent     every level from the study's start; the best chi^2 is reported;
  //   coarse_to_fine  in the order listed (coarse first), each level starting from the last
  //                   one's best point with `fine_budget` runs; the last (finest) level is
  //                   reported. Needs exactly one parameter with levels.
  //   multi_fidelity  fit and profile on the first (coarse) level; `fine_runs` runs of the
  //                   last (fine) level correct the coarse model, observable by observable,
  //                   by a + b p along the profiled parameter p (multi_fidelity.hpp); the
  //                   profile and the bounding friction are the corrected model's. Needs
  //                   exactly one parameter with two levels, and a profile.
  bool coarse_to_fine = false;
  bool multi_fidelity = false;
  int fine_budget = 0;  // runs per level after the first under coarse_to_fine; 0 = budget
  int fine_runs = 3;    // multi_fidelity: runs of the fine level (two spread, one at the optimum)
};

// The profile behind the bounding friction: chi^2 along the degradation parameter.
struct ProfileOptions {
  std::string parameter;    // a parameter name; "" = the first *.degradation_percent parameter
  int points = 11;          // scan points from lower to upper (the best point is added)
  bool reoptimize = false;  // false: the other parameters stay at the best fit (cheap);
                            // true: they are re-fitted at every scan point (budget/2 each)
};

// One explanation of the observations to fit and rank against the others (hypotheses.hpp):
// its own scene settings (a friction law and its fixed numbers) and, if given, its own
// fitted parameters instead of the study's.
struct Hypothesis {
  std::string name;  // a file-name-safe word: its results go to OUT/hypotheses/NAME
  std::vector<std::pair<std::string, std::string>> settings;  // after the study's settings
  std::vector<Parameter> parameters;                          // empty: the study's
};

struct Study {
  std::string path;        // the study file, used as FILE in messages
  std::string scene_path;  // resolved against the study file's folder
  std::vector<std::pair<std::string, std::string>> settings;  // fixed scene overrides for every run
  std::vector<Parameter> parameters;
  std::vector<Observation> observations;
  MethodOptions method;
  ProfileOptions profile;
  int ensemble = 8;  // realisations that measure a `model_sigma: ensemble` (forward/perturb.hpp)
  std::vector<Hypothesis> hypotheses;  // none: one fit of the study as it stands
  bool has_model_sigma() const {
    for (const Observation& o : observations)
      if (o.model_sigma > 0.0 || o.model_sigma_from_ensemble) return true;
    return false;
  }
};

// The PointSummary fields an observation may name.
const std::vector<std::string>& summary_quantities();

// Reads and checks a study file. Throws StudyError.
Study read_study(const std::string& path);

// Checks the parts that need the scene: measure point names, and that the parameter keys
// are scene values (by reading the scene at the start point of the first level, which also
// meshes region scenes at that block size). Throws StudyError naming the study's key.
void check_study_against_scene(const Study& study);

// Index of the profiled parameter (ProfileOptions::parameter or the first continuous
// *.degradation_percent / *.roughness_angle parameter), or -1 when there is none.
int profile_parameter(const Study& study);

}  // namespace ddafit::inverse
