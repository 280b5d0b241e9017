// `ddafit invert`: reads a study, runs the back-analysis (inverse/), prints progress and
// the result, and leaves the report in --out.
#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "forward/model_revision.hpp"
#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "batch/stop_signals.hpp"
#include "apps/ddafit/clock_text.hpp"
#include "forward/io/run_files.hpp"
#include "batch/thread_budget.hpp"
#include "inverse/evaluation_cache.hpp"
#include "inverse/forward_call.hpp"
#include "inverse/hypotheses.hpp"
#include "inverse/inversion.hpp"
#include "inverse/report.hpp"
#include "inverse/study.hpp"

namespace ddafit::app {

namespace {

// The plan of --check: what would run, without running it.
void print_plan(const inverse::Study& study, int budget, const std::string& out) {
  long levels = 1;
  std::cout << "study " << study.path << "\nscene " << study.scene_path << " (input hash "
            << inverse::scene_input_hash(study) << ")\n";
  for (const auto& [k, v] : study.settings) std::cout << "  setting " << k << " = " << v;
  if (!study.settings.empty()) std::cout << "\n";
  for (const inverse::Parameter& p : study.parameters) {
    if (p.discrete()) {
      levels *= static_cast<long>(p.levels.size());
      std::string list;
      for (double v : p.levels) list += (list.empty() ? "" : ", ") + fmt::format("{:g}", v);
      std::cout << fmt::format("  parameter {} ({}): levels {}\n", p.name, p.key, list);
    } else {
      std::cout << fmt::format("  parameter {} ({}): [{:g}, {:g}], start {:g}, resolution {:g}\n", p.name, p.key, p.lower,
                               p.upper, p.start, p.resolution);
    }
  }
  for (const inverse::Observation& o : study.observations)
    std::cout << fmt::format("  observation point {} {} {} {:g} +- {:g}\n", o.point, o.quantity,
                             o.kind == inverse::ObservationKind::AtMost    ? "<="
                             : o.kind == inverse::ObservationKind::AtLeast ? ">="
                                                                           : "=",
                             o.value, o.sigma);
  const int profiled = inverse::profile_parameter(study);
  const long scan = profiled >= 0 ? study.profile.points : 0;
  const long per_point = study.profile.reoptimize ? std::max(1, budget / 2) : 1;
  std::cout << fmt::format("method {} {}, budget {} per level, {} level(s); profile over {} with {} points\n",
                           study.method.optimizer == inverse::Optimizer::Ceres ? "ceres" : "nlopt",
                           study.method.optimizer == inverse::Optimizer::Ceres ? "levenberg_marquardt"
                                                                               : study.method.algorithm,
                           budget, levels, profiled >= 0 ? study.parameters[profiled].name : "(none)", scan);
  if (study.method.multi_fidelity) {
    // The coarse level's fit and profiles (the bisections come on top), and the fine runs.
    std::cout << fmt::format("multi_fidelity: fit and profile on the first level, {} runs of the last correct it\n",
                             study.method.fine_runs);
    std::cout << fmt::format("about {} coarse evaluations and {} fine; cache {}/evaluations.sqlite\n",
                             budget + 2 * scan, study.method.fine_runs, out);
    return;
  }
  std::cout << fmt::format("at most {} evaluations; cache {}/evaluations.sqlite\n", levels * budget + scan * per_point,
                           out);
}

}  // namespace

bool load_study(const std::string& path, inverse::Study& study) {
  try {
    study = inverse::read_checked_study(path);
    return true;
  } catch (const inverse::StudyError& e) {
    std::cerr << e.what() << "\n";
    return false;
  }
}

namespace {

inverse::InversionOptions make_options(const InvertArgs& args, const std::string& out) {
  inverse::InversionOptions options;
  options.out_dir = out;
  options.resume = args.resume;
  options.budget = args.budget;
  options.model_version = std::string(DDAFIT_VERSION) + "+" + kModelRevision;
  options.jobs = args.jobs;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int per_run = args.threads > 0 ? args.threads : std::max(1, cores / args.jobs);
  options.on_worker_start = [per_run] { batch::set_worker_threads(per_run); };
  if (!args.quiet) {
    options.on_progress = [](const inverse::Progress& p) {
      // The plan counts the fits and the profile grid; the bisection of the profile's
      // crossings comes on top (a few runs each), so past the plan there is no ETA.
      const std::string where = p.evaluations <= p.planned
                                    ? fmt::format("of <= {}", p.planned)
                                    : fmt::format("(refining the profile past the {} planned)", p.planned);
      const std::string eta = p.evaluations <= p.planned ? "ETA " + clock_text(p.eta_seconds) : "";
      std::cerr << fmt::format("\r  evaluation {} {} ({} cached)  best chi2 {:.4g}  {:.1f} s/run  {}   ",
                               p.evaluations, where, p.cached, p.best_chi2, p.mean_run_seconds, eta)
                << std::flush;
    };
  }
  options.on_log = [quiet = args.quiet](const std::string& line) {
    if (!quiet) std::cerr << "\n  note: " << line << "\n";
  };
  return options;
}

// Fits `study` with its cache and report in `out`. Returns an exit code; kExitSuccess
// leaves the result in `summary`.
int fit_and_report(const InvertArgs& args, const inverse::Study& study, const std::string& out,
                   inverse::InversionSummary& summary) {
  try {
    summary = inverse::run_inversion(study, make_options(args, out));
  } catch (const inverse::InversionError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  } catch (const inverse::CacheError& e) {
    std::cerr << "\n" << e.what() << "\n";
    return kExitRunFailed;
  }
  if (!args.quiet) std::cerr << "\n";
  try {
    for (const std::string& note : inverse::write_report(out, study, summary)) std::cerr << "note: " << note << "\n";
  } catch (const std::exception& e) {
    std::cerr << out << ": --out: " << e.what() << "\n";
    return kExitBadInput;
  }
  const inverse::LevelFit& best = summary.levels[summary.best_level];
  if (best.best.failed) {
    std::cerr << study.path << ": every forward run failed; the last reason: " << best.best.message << "\n";
    return kExitRunFailed;
  }
  return kExitSuccess;
}

void print_result(const inverse::Study& study, const inverse::InversionSummary& summary, const std::string& out) {
  std::cout << fmt::format("{} evaluations ({} run, {} cached), {:.1f} s\n", summary.evaluations, summary.run,
                           summary.cached, summary.wall_seconds);
  for (size_t l = 0; l < summary.levels.size(); ++l) {
    std::string line = fmt::format("level {}{}:", l + 1, static_cast<int>(l) == summary.best_level ? " (best)" : "");
    for (size_t k = 0; k < study.parameters.size(); ++k)
      line += fmt::format(" {} = {:.6g}", study.parameters[k].name, summary.levels[l].best.values[k]);
    std::cout << line << fmt::format("  chi2 = {:.4g} ({})\n", summary.levels[l].best.chi2,
                                     summary.levels[l].fit.stop_reason);
  }
  const inverse::BoundingFriction& f = summary.friction;
  if (f.available)
    std::cout << fmt::format("mu_b = {:.4f}; Delta chi2 <= 1: [{:.4f}, {:.4f}]; <= 4: [{:.4f}, {:.4f}]\n", f.mu_best,
                             f.delta1.mu_low, f.delta1.mu_high, f.delta4.mu_low, f.delta4.mu_high);
  for (const std::string& w : summary.covariance.warnings) std::cout << "covariance warning: " << w << "\n";
  std::cout << "wrote " << (std::filesystem::path(out) / "report.md").string() << "\n";
}

// Every hypothesis fitted in OUT/hypotheses/NAME, then ranked in OUT/ranking.md.
int run_hypotheses(const InvertArgs& args, const inverse::Study& study) {
  std::vector<inverse::HypothesisFit> fits;
  for (const inverse::Hypothesis& h : study.hypotheses) {
    inverse::HypothesisFit fit;
    fit.name = h.name;
    fit.study = inverse::hypothesis_study(study, h);
    const std::string out = (std::filesystem::path(args.out) / "hypotheses" / h.name).string();
    if (!args.quiet) std::cerr << "hypothesis " << h.name << " (" << out << ")\n";
    std::error_code ec;
    std::filesystem::create_directories(out, ec);
    if (ec) {
      std::cerr << out << ": --out: cannot create the folder: " << ec.message() << "\n";
      return kExitBadInput;
    }
    const int code = fit_and_report(args, fit.study, out, fit.summary);
    if (code == kExitBadInput) return code;  // a cache or folder problem stops them all
    if (!args.quiet && code == kExitSuccess) print_result(fit.study, fit.summary, out);
    fits.push_back(std::move(fit));
  }
  const inverse::HypothesisRanking ranking = inverse::rank_hypotheses(std::move(fits));
  try {
    for (const std::string& note : inverse::write_ranking(args.out, ranking)) std::cerr << "note: " << note << "\n";
  } catch (const std::exception& e) {
    std::cerr << args.out << ": --out: " << e.what() << "\n";
    return kExitBadInput;
  }
  for (const inverse::HypothesisFit& f : ranking.fits)
    std::cout << (f.failed ? fmt::format("{:>24}  failed\n", f.name)
                           : fmt::format("{:>24}  chi2 {:8.3f}  k {}  AIC {:8.2f}  dAIC {:6.2f}  BIC {:8.2f}\n", f.name,
                                         f.chi2, f.fitted, f.aic, f.delta_aic, f.bic));
  std::cout << "wrote " << (std::filesystem::path(args.out) / "ranking.md").string() << "\n" << ranking.verdict << "\n";
  return ranking.fits.empty() || ranking.fits.front().failed ? kExitRunFailed : kExitSuccess;
}

}  // namespace

int run_invert(const InvertArgs& given) {
  InvertArgs args = given;
  if (args.study.empty()) {
    // What ddafit is for, in one command: the twin experiment's back-analysis, whose true
    // basal degradation is known (30 %), ending on the bounding-friction sentence.
    args.study = std::string(DDAFIT_CASES_DIR) + "/inverse/twin_study.yaml";
    if (!args.quiet) std::cerr << "no study given: running the built-in twin study " << args.study << "\n";
  }
  inverse::Study study;
  if (!load_study(args.study, study)) return kExitBadInput;
  const int budget = args.budget > 0 ? args.budget : study.method.budget;
  if (args.check) {
    if (study.hypotheses.empty()) print_plan(study, budget, args.out);
    for (const inverse::Hypothesis& h : study.hypotheses) {
      std::cout << "hypothesis " << h.name << ":\n";
      print_plan(inverse::hypothesis_study(study, h), budget, args.out + "/hypotheses/" + h.name);
    }
    return kExitSuccess;
  }
  if (const std::string problem = io::prepare_output_folder(args.out); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  batch::exit_on_stop_signals("ddafit invert: interrupted; every finished forward run is kept in " + args.out +
                              "/evaluations.sqlite (hypotheses: in hypotheses/NAME/): run the same command with "
                              "--resume to go on from there\n");
  if (!study.hypotheses.empty()) return run_hypotheses(args, study);
  inverse::InversionSummary summary;
  if (const int code = fit_and_report(args, study, args.out, summary); code != kExitSuccess) return code;
  if (!args.quiet) print_result(study, summary, args.out);
  // The answer the back-analysis is for, last, also with --quiet.
  std::cout << inverse::bounding_friction_sentence(study, summary.friction) << "\n";
  return kExitSuccess;
}

}  // namespace ddafit::app
