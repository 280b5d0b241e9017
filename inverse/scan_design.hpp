// `ddafit scan --design grid|lhs|morris`: a design over the study's continuous parameters,
// crossed with every combination of its discrete levels (block sizes), each point through
// the evaluation cache, `jobs` forward runs at a time. What a scan tells the user: the runs
// whose chi2 lies within Delta chi2 <= 1 and <= 4 of the best, and the residual basal
// friction over them; for Morris, which parameters matter.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "inverse/designs.hpp"
#include "inverse/inversion.hpp"

namespace ddafit::inverse {

enum class DesignKind { Grid, LatinHypercube, Morris };

struct DesignOptions {
  DesignKind kind = DesignKind::LatinHypercube;
  int points = 5;         // grid: values per parameter (>= 2)
  int samples = 20;       // lhs: points
  int trajectories = 10;  // morris: r
  int levels = 4;         // morris: grid levels (even)
  std::uint64_t seed = 1; // lhs, morris
};

// The study's parameter values of every point, design by level combination (the design
// repeated for each combination of the discrete parameters' levels, first level first).
std::vector<std::vector<double>> design_values(const Study& study, const DesignOptions& options);
int continuous_count(const Study& study);

struct FrictionSpread {
  bool available = false;
  std::string interface, parameter, why_not;
  double mu_low = 0.0, mu_high = 0.0;  // over the runs within the threshold
  long runs = 0;
};

struct DesignResult {
  std::vector<Evaluation> runs;  // in design order
  long best = -1;                // index of the lowest chi2 among completed runs
  FrictionSpread within1, within4;
  bool with_model_sigma = false;        // observations carry a model_sigma:
  FrictionSpread within4_observations;  // then this is within4 with their sigma alone
  std::vector<MorrisEffects> effects;  // morris: one per level combination
  long cached = 0, run = 0;
  std::string cache_path;
};

DesignResult run_design(const Study& study, const InversionOptions& options, const DesignOptions& design,
                        const ForwardModel& forward = run_forward);

// Before running: the points a design (or a profile's `points`) asks for, how many the
// cache in options.out_dir already holds, and the mean wall time of the cached runs (0 when
// none), for an estimate of what is left.
struct DesignPlan {
  long points = 0, distinct = 0, cached = 0;
  double mean_cached_seconds = 0.0;
};
DesignPlan plan_points(const Study& study, const InversionOptions& options, const std::vector<std::vector<double>>& points);

}  // namespace ddafit::inverse
