// `ddafit scan`: a profile along one parameter (scan.csv, as before) or a design over all
// of them (runs.csv and report.md), through the evaluation cache, --jobs runs at a time.
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <iostream>
#include <thread>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "batch/stop_signals.hpp"
#include "batch/mpi_pool.hpp"
#include "inverse/model_spread.hpp"
#include "apps/ddafit/clock_text.hpp"
#include "forward/io/html_report.hpp"
#include "forward/io/run_files.hpp"
#include "apps/ddafit/scan_plots.hpp"
#include "apps/ddafit/slurm_scan.hpp"
#include "batch/thread_budget.hpp"
#include "forward/model_revision.hpp"
#include "inverse/evaluation_cache.hpp"
#include "inverse/inversion.hpp"
#include "inverse/scan_design.hpp"
#include "inverse/study.hpp"

namespace ddafit::app {
namespace {

namespace fs = std::filesystem;

inverse::DesignOptions design_options(const ScanArgs& a) {
  inverse::DesignOptions d;
  d.kind = a.design == "grid"     ? inverse::DesignKind::Grid
           : a.design == "morris" ? inverse::DesignKind::Morris
                                  : inverse::DesignKind::LatinHypercube;
  d.points = a.points;
  d.samples = a.samples;
  d.trajectories = a.trajectories;
  d.levels = a.levels;
  d.seed = static_cast<std::uint64_t>(a.seed);
  return d;
}

std::string status_of(const inverse::Evaluation& e) { return e.failed ? "failed" : "completed"; }

// runs.csv: one row per design point: its parameters, chi2, status, wall time, and the
// simulated value of every observation (the quantities the study compares).
void write_runs_csv(const fs::path& path, const inverse::Study& study, const inverse::DesignResult& r) {
  std::ofstream csv(path);
  csv << "run";
  for (const inverse::Parameter& p : study.parameters) csv << "," << p.name;
  csv << ",chi2,status,wall_seconds,cached";
  for (const inverse::Observation& o : study.observations) csv << "," << o.point << ":" << o.quantity;
  csv << "\n";
  for (size_t k = 0; k < r.runs.size(); ++k) {
    const inverse::Evaluation& e = r.runs[k];
    csv << k;
    for (double v : e.values) csv << fmt::format(",{:.10g}", v);
    csv << fmt::format(",{:.6g},{},{:.3f},{}", e.chi2, status_of(e), e.wall_seconds, e.cached ? 1 : 0);
    for (double v : e.simulated) csv << fmt::format(",{:.6g}", v);
    csv << "\n";
  }
  if (!csv) throw std::runtime_error(path.string() + ": cannot write");
}

std::string spread_sentence(const inverse::FrictionSpread& f, double threshold) {
  if (!f.available) return fmt::format("Delta chi2 <= {:g}: no friction range ({}).", threshold, f.why_not);
  const auto deg = [](double mu) { return std::atan(mu) * 180.0 / M_PI; };
  return fmt::format("Delta chi2 <= {:g}: {} runs; residual friction of interface `{}` between mu_b = {:.3f} "
                     "(phi_b = {:.1f} deg) and {:.3f} ({:.1f} deg).",
                     threshold, f.runs, f.interface, f.mu_low, deg(f.mu_low), f.mu_high, deg(f.mu_high));
}

// Writes report.md and returns its text (report.html shows the same).
std::string write_report_md(const fs::path& path, const ScanArgs& a, const inverse::Study& study,
                            const inverse::DesignResult& r) {
  std::ostringstream md;
  md << "# Scan: " << study.path << " (" << a.design << " design)\n\n";
  md << fmt::format("{} points: {} forward runs made now, {} from the cache ({}).\n\n", r.runs.size(), r.run, r.cached,
                    r.cache_path);
  if (r.best >= 0) {
    md << "## Best point\n\n| parameter | value |\n|---|---|\n";
    for (size_t k = 0; k < study.parameters.size(); ++k)
      md << fmt::format("| {} | {:.6g} |\n", study.parameters[k].name, r.runs[r.best].values[k]);
    md << fmt::format("| chi2 | {:.4g} |\n\n", r.runs[r.best].chi2);
  } else {
    md << "Every run failed: see runs.csv and the messages printed during the scan.\n\n";
  }
  md << "## Residual basal friction over the runs that fit\n\n";
  md << "- " << spread_sentence(r.within1, 1.0) << "\n- " << spread_sentence(r.within4, 4.0) << "\n";
  if (r.with_model_sigma)
    md << "- observations only (model_sigma left out): " << spread_sentence(r.within4_observations, 4.0) << "\n";
  md << "\n";
  md << "Charts: `chi2_along_*.png` (chi2 along each parameter), `chi2_map_*_*.png` (over each pair)"
     << (r.effects.empty() ? "" : ", `morris.png`") << ".\n\n";
  md << "A scan samples; the bounds of the friction range are as fine as its points. Where the range "
        "reaches a parameter's search bound, widen the bound before quoting it.\n";
  if (!r.effects.empty()) {
    md << "\n## Morris elementary effects on chi2 (parameters ranked by mu*)\n\n";
    md << "mu* says how much chi2 changes when the parameter moves over its range; a sigma as large as mu* "
          "says that change depends on the other parameters (interaction or non-linearity).\n\n";
    std::vector<int> continuous;
    for (size_t k = 0; k < study.parameters.size(); ++k)
      if (!study.parameters[k].discrete()) continuous.push_back(static_cast<int>(k));
    for (size_t level = 0; level < r.effects.size(); ++level) {
      const inverse::MorrisEffects& e = r.effects[level];
      std::vector<size_t> order(e.mu_star.size());
      for (size_t d = 0; d < order.size(); ++d) order[d] = d;
      std::sort(order.begin(), order.end(), [&](size_t x, size_t y) { return e.mu_star[x] > e.mu_star[y]; });
      md << fmt::format("Level combination {}:\n\n| rank | parameter | mu* | sigma | effects |\n|---|---|---|---|---|\n",
                        level + 1);
      for (size_t rank = 0; rank < order.size(); ++rank) {
        const size_t d = order[rank];
        md << fmt::format("| {} | {} | {:.4g} | {:.4g} | {} |\n", rank + 1, study.parameters[continuous[d]].name,
                          e.mu_star[d], e.sigma[d], e.counted[d]);
      }
      md << "\n";
    }
  }
  std::ofstream out(path);
  out << md.str();
  if (!out) throw std::runtime_error(path.string() + ": cannot write the report");
  return md.str();
}

int run_profile(const ScanArgs& args, const inverse::Study& study, const inverse::InversionOptions& options);

// Runs `scan`; 0, or the exit code of the set-up error it threw (printed): a study or cache
// the scan refuses (2), a cache it cannot write (3).
template <class Scan>
int guarded(Scan&& scan) {
  try {
    scan();
    return 0;
  } catch (const inverse::InversionError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  } catch (const inverse::CacheError& e) {
    std::cerr << e.what() << "\n";
    return kExitRunFailed;
  }
}

}  // namespace

int run_scan(const ScanArgs& args) {
  inverse::Study study;
  if (!load_study(args.study, study)) return kExitBadInput;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (args.threads > 0 && args.jobs * args.threads > cores) {
    std::cerr << fmt::format("ddafit scan: --jobs {} x --threads {} = {} threads on {} cores; lower one of them\n",
                             args.jobs, args.threads, args.jobs * args.threads, cores);
    return kExitBadInput;
  }
  const int per_run = args.threads > 0 ? args.threads : std::max(1, cores / std::max(args.jobs, args.mpi_size));
  if (!args.task_dir.empty()) return run_slurm_task(args, study);
  if (args.mpi_rank > 0) {
    // A worker: forward runs for rank 0 until it says stop; it writes and prints nothing.
    batch::mpi_worker(study, per_run, args.run_timeout);
    return kExitSuccess;
  }
  // Rank 0 under mpirun: whatever way this returns, the workers are told to stop.
  const batch::MpiWorld world{args.mpi_rank, args.mpi_size};
  struct Release {
    batch::MpiWorld world;
    ~Release() {
      if (world.size > 1) batch::mpi_release_workers(world);
    }
  } release{world};
  inverse::InversionOptions options;
  options.out_dir = args.out;
  options.resume = args.resume;
  options.model_version = std::string(DDAFIT_VERSION) + "+" + kModelRevision;
  options.on_log = [](const std::string& line) { std::cerr << "note: " << line << "\n"; };
  options.jobs = args.jobs;
  options.on_worker_start = [per_run] { batch::set_worker_threads(per_run); };
  if (world.size > 1) {
    options.batch_runner = batch::mpi_batch_runner(world);
    options.jobs = world.size - 1;  // runs at a time, for the ETA
  }
  if (args.jobs > 1) batch::set_worker_threads(per_run);

  int profiled = -1;
  std::vector<std::vector<double>> points;
  if (args.design == "profile") {
    for (size_t k = 0; k < study.parameters.size(); ++k)
      if (study.parameters[k].name == args.parameter && !study.parameters[k].discrete()) profiled = static_cast<int>(k);
    if (profiled < 0) {
      std::cerr << args.study << ": --parameter: '" << args.parameter
                << "' is not a continuous parameter of the study (the profile design needs one)\n";
      return kExitBadInput;
    }
    points = inverse::profile_points(study, profiled, args.points);
  } else {
    points = inverse::design_values(study, design_options(args));
  }
  if (points.size() > 100000) {
    std::cerr << fmt::format("ddafit scan: the {} design asks for {} runs, more than 100000; lower --points, "
                             "--samples or --trajectories\n", args.design, points.size());
    return kExitBadInput;
  }
  const inverse::DesignPlan plan = inverse::plan_points(study, options, points);
  const long left = plan.distinct - plan.cached;
  const int at_a_time = world.size > 1 ? world.size - 1 : args.jobs;
  std::cout << fmt::format("plan: {} design, {} runs ({} distinct, {} in the cache, {} to run, {} at a time{})", args.design,
                           plan.points, plan.distinct, plan.cached, left, at_a_time,
                           world.size > 1 ? " on MPI worker ranks" : "");
  if (plan.mean_cached_seconds > 0.0)
    std::cout << fmt::format("; about {} of wall from the cached runs' {:.1f} s each",
                             clock_text(plan.mean_cached_seconds * static_cast<double>(left) / at_a_time),
                             plan.mean_cached_seconds);
  std::cout << std::endl;
  if (args.dry_run) return kExitSuccess;
  if (!args.slurm_dir.empty()) {
    std::vector<std::vector<double>> todo;
    {
      const fs::path cache_path = fs::path(args.out) / "evaluations.sqlite";
      std::set<std::string> keys;
      std::unique_ptr<inverse::EvaluationCache> cache;
      if (fs::exists(cache_path))
        cache = std::make_unique<inverse::EvaluationCache>(cache_path.string(), options.model_version,
                                                           inverse::scene_input_hash(study));
      // The model spread's realisations (model_sigma: ensemble) first: the collecting run
      // measures it before the design, from the cache.
      std::vector<std::vector<double>> all = inverse::model_spread_points(study);
      all.insert(all.end(), points.begin(), points.end());
      for (const auto& x : all) {
        const std::string key = inverse::model_spread_key(study, x);
        if (keys.insert(key).second && !(cache && cache->find(key))) todo.push_back(x);
      }
    }
    return write_slurm_job(args, study, todo);
  }
  if (!args.collect_dir.empty()) {
    const long missing = collect_slurm_results(args, study, options.model_version);
    if (missing < 0) return kExitBadInput;
    if (missing > 0) return kExitRunFailed;
    options.resume = true;  // every point is now in the cache: the report comes from it
  }
  if (const std::string problem = io::prepare_output_folder(args.out); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  batch::exit_on_stop_signals("ddafit scan: interrupted; every finished forward run is kept in " + args.out +
                       "/evaluations.sqlite: run the same command with --resume to go on from there\n");
  options.on_progress = [](const inverse::Progress& p) {
    std::cerr << fmt::format("\r  done {} of {} ({} cached, {} failed), {} running  best chi2 {:.4g}  ETA {}   ",
                             p.evaluations, p.planned, p.cached, p.failed, p.running, p.best_chi2,
                             clock_text(p.eta_seconds))
              << std::flush;
  };
  if (args.design == "profile") return run_profile(args, study, options);

  inverse::DesignResult result;
  std::string report;
  if (const int failed = guarded([&] { result = inverse::run_design(study, options, design_options(args)); }))
    return failed;
  std::cerr << "\n";
  try {
    write_runs_csv(fs::path(args.out) / "runs.csv", study, result);
    report = write_report_md(fs::path(args.out) / "report.md", args, study, result);
  } catch (const std::exception& e) {
    std::cerr << args.out << ": --out: " << e.what() << "\n";
    return kExitBadInput;
  }
  std::string reason;
  if (!plot_scan(args.out, study, result, reason)) std::cerr << "note: charts not drawn: " << reason << "\n";
  try {  // after the charts, which it embeds
    io::HtmlReport page;
    page.title = "Scan: " + study.path + " (" + args.design + " design)";
    page.headline = spread_sentence(result.within4, 4.0);
    page.markdown = report;
    page.settings = {{"study", study.path}, {"design", args.design}, {"model revision", kModelRevision}};
    io::write_html_report(args.out, page);
  } catch (const std::exception& e) {
    std::cerr << args.out << ": --out: " << e.what() << "\n";
    return kExitBadInput;
  }
  std::cout << fmt::format("{} runs ({} made, {} cached); wrote {}/runs.csv and report.md\n", result.runs.size(),
                           result.run, result.cached, args.out);
  std::cout << spread_sentence(result.within1, 1.0) << "\n" << spread_sentence(result.within4, 4.0) << "\n";
  if (result.with_model_sigma)
    std::cout << "observations only (model_sigma left out): " << spread_sentence(result.within4_observations, 4.0)
              << "\n";
  return kExitSuccess;
}

namespace {

// The one-parameter profile: scan.csv and the table on stdout, as before the designs.
int run_profile(const ScanArgs& args, const inverse::Study& study, const inverse::InversionOptions& options) {
  inverse::ScanResult scan;
  if (const int failed = guarded([&] { scan = inverse::run_scan(study, options, args.parameter, args.points); }))
    return failed;
  // Table to stdout and DIR/scan.csv: the value, chi2, then each observation's simulated value.
  std::string header = args.parameter + ",chi2";
  for (const inverse::Observation& o : study.observations) header += "," + o.point + ":" + o.quantity;
  std::ofstream csv(std::filesystem::path(args.out) / "scan.csv");
  csv << header << "\n";
  std::cout << header << "\n";
  for (const inverse::Evaluation& e : scan.points) {
    std::string row = fmt::format("{:.10g},{:.6g}", e.values[scan.parameter], e.chi2);
    for (double v : e.simulated) row += fmt::format(",{:.6g}", v);
    csv << row << "\n";
    std::cout << row << "\n";
  }
  std::cerr << fmt::format("{} points: {} run, {} cached; wrote {}/scan.csv\n", scan.points.size(), scan.run,
                           scan.cached, args.out);
  return kExitSuccess;
}

}  // namespace

}  // namespace ddafit::app
