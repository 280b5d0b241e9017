#include "inverse/report.hpp"

#include "forward/io/html_report.hpp"
#include "forward/model_revision.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace ddafit::inverse {

namespace {

using nlohmann::json;

const char* kind_name(ObservationKind k) {
  return k == ObservationKind::AtMost ? "at_most" : k == ObservationKind::AtLeast ? "at_least" : "equal";
}

json named_values(const Study& study, const std::vector<double>& values, bool discrete) {
  json j = json::object();
  for (size_t k = 0; k < study.parameters.size() && k < values.size(); ++k)
    if (study.parameters[k].discrete() == discrete) j[study.parameters[k].name] = values[k];
  return j;
}

json observations_json(const Study& study, const Evaluation& e) {
  json out = json::array();
  for (size_t k = 0; k < study.observations.size(); ++k) {
    const Observation& o = study.observations[k];
    out.push_back({{"point", o.point}, {"quantity", o.quantity}, {"kind", kind_name(o.kind)}, {"observed", o.value},
                   {"sigma", o.sigma}, {"model_sigma", o.model_sigma}, {"effective_sigma", o.effective_sigma()},
                   {"simulated", k < e.simulated.size() ? e.simulated[k] : NAN},
                   {"residual", k < e.residuals.size() ? e.residuals[k] : NAN}});
  }
  return out;
}

json range_json(const ProfileRange& r) {
  return {{"delta_chi2", r.threshold}, {"low", r.low}, {"high", r.high}, {"mu_low", r.mu_low},
          {"mu_high", r.mu_high}, {"low_at_bound", r.low_at_bound}, {"high_at_bound", r.high_at_bound}};
}

json fidelity_json(const Study& study, const FidelityCorrection& c) {
  json j = {{"coarse_level", c.coarse_level}, {"fine_level", c.fine_level}, {"rms_sigma", c.rms_sigma},
            {"correction", json::array()}, {"runs", json::array()}};
  for (size_t k = 0; k < study.observations.size() && k < c.offset.size(); ++k)
    j["correction"].push_back({{"point", study.observations[k].point}, {"quantity", study.observations[k].quantity},
                               {"offset", c.offset[k]}, {"slope", c.slope[k]}});
  for (const FidelityRun& r : c.runs)
    j["runs"].push_back({{"value", r.value}, {"fine_chi2", r.fine.chi2}, {"fine_failed", r.fine.failed},
                         {"fine", r.fine.simulated}, {"coarse", r.coarse.simulated}, {"predicted", r.predicted}});
  if (c.checked)
    j["check"] = {{"value", c.runs.back().value}, {"chi2", c.check_chi2}, {"predicted_chi2", c.check_predicted_chi2}};
  return j;
}

std::string fidelity_markdown(const Study& study, const FidelityCorrection& c) {
  const Parameter& p = study.parameters[c.parameter];
  std::string md = fmt::format(
      "\n## Multi-fidelity correction\n\nThe profile is the coarse level's ({:g}) runs corrected towards the fine "
      "level ({:g}): y_fine = y_coarse + a + b {}, a and b by least squares through these fine runs (RMS of the fine "
      "runs' residuals about the corrected model's: {:.3g} sigma).\n\n| {} | quantity | coarse | fine | corrected coarse |\n"
      "|---|---|---|---|---|\n",
      c.coarse_level, c.fine_level, p.name, c.rms_sigma, p.name);
  for (const FidelityRun& r : c.runs)
    for (size_t k = 0; k < study.observations.size(); ++k)
      md += fmt::format("| {:.4g} | {} {} | {:.5g} | {:.5g} | {:.5g} |\n", r.value, study.observations[k].point,
                        study.observations[k].quantity, r.coarse.simulated[k], r.fine.simulated[k],
                        k < r.predicted.size() ? r.predicted[k] : NAN);
  if (c.checked)
    md += fmt::format("\nCheck run at the corrected optimum ({} = {:.4g}): chi2 {:.4g}, predicted {:.4g}.\n", p.name,
                      c.runs.back().value, c.check_chi2, c.check_predicted_chi2);
  return md;
}

json report_json(const Study& study, const InversionSummary& s) {
  json j;
  j["study"] = study.path;
  j["scene"] = study.scene_path;
  j["model_version"] = s.model_version;
  j["scene_hash"] = s.scene_hash;
  j["cache"] = s.cache_path;
  j["method"] = {{"optimizer", study.method.optimizer == Optimizer::Ceres ? "ceres" : "nlopt"},
                 {"algorithm", study.method.optimizer == Optimizer::Ceres ? "levenberg_marquardt" : study.method.algorithm},
                 {"budget", s.budget},
                 {"step_tolerance", study.method.step_tolerance}, {"chi2_tolerance", study.method.chi2_tolerance}};
  j["evaluations_total"] = s.evaluations;
  j["evaluations_cached"] = s.cached;
  j["evaluations_run"] = s.run;
  j["history_reruns"] = s.history_reruns;
  j["wall_seconds"] = s.wall_seconds;
  j["run_seconds"] = s.run_seconds;
  j["parameters"] = json::array();
  for (const Parameter& p : study.parameters)
    j["parameters"].push_back(p.discrete() ? json{{"name", p.name}, {"key", p.key}, {"levels", p.levels}}
                                           : json{{"name", p.name}, {"key", p.key}, {"lower", p.lower},
                                                  {"upper", p.upper}, {"start", p.start},
                                                  {"resolution", p.resolution}});
  j["levels"] = json::array();
  for (const LevelFit& l : s.levels)
    j["levels"].push_back({{"level", named_values(study, l.start, true)},
                           {"best", named_values(study, l.best.values, false)},
                           {"chi2", l.best.chi2},
                           {"failed", l.best.failed},
                           {"evaluations", l.fit.evaluations},
                           {"converged", l.fit.converged},
                           {"stop_reason", l.fit.stop_reason},
                           {"observations", observations_json(study, l.best)}});
  j["best_level"] = s.best_level;
  j["level_strategy"] = study.method.multi_fidelity ? "multi_fidelity"
                        : study.method.coarse_to_fine ? "coarse_to_fine"
                                                      : "independent";
  if (s.fidelity.used) j["multi_fidelity"] = fidelity_json(study, s.fidelity);
  if (s.best_level >= 0) {
    const LevelFit& b = s.levels[s.best_level];
    j["best"] = named_values(study, b.best.values, false);
    j["best"].update(named_values(study, b.best.values, true));
    j["chi2"] = b.best.chi2;
  }
  const BoundingFriction& f = s.friction;
  json bf = {{"available", f.available}};
  if (!f.available) bf["why_not"] = f.why_not;
  if (f.available) {
    bf["parameter"] = study.parameters[f.parameter].name;
    bf["interface"] = f.interface;
    bf["peak_friction_angle"] = f.peak_angle;
    bf["best_value"] = f.best_value;
    bf["mu_best"] = f.mu_best;
    bf["profile_mode"] = f.reoptimized ? "other parameters re-optimised at each point"
                         : f.corrected ? "other parameters fixed at the best fit; coarse runs corrected to the fine level"
                                       : "other parameters fixed at the best fit";
    bf["profile"] = json::array();
    double chi2_min = INFINITY;
    for (const ProfilePoint& p : f.profile) chi2_min = std::min(chi2_min, p.chi2);
    for (const ProfilePoint& p : f.profile)
      bf["profile"].push_back({{"value", p.value}, {"chi2", p.chi2}, {"delta_chi2", p.chi2 - chi2_min}, {"mu", p.mu},
                               {"failed", p.failed}});
    bf["delta_chi2_1"] = range_json(f.delta1);
    bf["delta_chi2_4"] = range_json(f.delta4);
    if (f.with_model_sigma) {
      bf["observations_only"] = {{"delta_chi2_1", range_json(f.delta1_observations)},
                                 {"delta_chi2_4", range_json(f.delta4_observations)}};
    }
  }
  bf["sentence"] = bounding_friction_sentence(study, f);
  j["bounding_friction"] = bf;
  const CovarianceReport& c = s.covariance;
  json cj = {{"computed", c.computed}, {"warnings", c.warnings}, {"condition_number", c.condition_number}};
  cj["parameters"] = json::array();
  for (int k : c.parameters) cj["parameters"].push_back(study.parameters[k].name);
  if (c.computed) {
    cj["matrix"] = c.matrix;
    cj["standard_deviation"] = c.standard_deviation;
    cj["mu_standard_deviation"] = c.mu_standard_deviation;
  }
  j["covariance"] = cj;
  j["notes"] = s.notes;
  return j;
}

std::string markdown(const Study& study, const InversionSummary& s) {
  std::string md = fmt::format("# Back-analysis: {}\n\nScene `{}`, model version {}, scene input hash {}.\n\n",
                               study.path, study.scene_path, s.model_version, s.scene_hash);
  md += fmt::format("{} evaluations: {} forward runs made now, {} from the cache ({}); {:.1f} s wall, {:.1f} s in runs.\n\n",
                    s.evaluations, s.run, s.cached, s.cache_path, s.wall_seconds, s.run_seconds);
  md += study.method.multi_fidelity
            ? "Multi-fidelity: fitted and profiled on the coarse level; a few fine runs correct the coarse model "
              "(section \"Multi-fidelity correction\"); the finest level's best run is reported.\n\n"
        : study.method.coarse_to_fine
            ? "Levels fitted coarse to fine: each starts from the last one's best point; the last (finest) is "
              "reported.\n\n"
            : "Levels fitted independently from the study's start; the lowest chi2 is reported.\n\n";
  md += "## Best parameters per level\n\n| level | ";
  for (const Parameter& p : study.parameters) md += p.name + " | ";
  md += "chi2 | runs | stop |\n|---|";
  for (size_t k = 0; k <= study.parameters.size() + 2; ++k) md += "---|";
  md += "\n";
  for (size_t l = 0; l < s.levels.size(); ++l) {
    const LevelFit& f = s.levels[l];
    md += fmt::format("| {}{} | ", l + 1,
                      static_cast<int>(l) != s.best_level ? ""
                      : study.method.coarse_to_fine || study.method.multi_fidelity ? " (finest, reported)"
                                                          : " (best)");
    for (double v : f.best.values) md += fmt::format("{:.6g} | ", v);
    md += fmt::format("{:.4g} | {} | {} |\n", f.best.chi2, f.fit.evaluations, f.fit.stop_reason);
  }
  if (s.best_level >= 0) {
    md += "\n## Simulated against observed (best level)\n\nResiduals are (simulated - observed) / sigma: in "
          "standard deviations of the observation; a limit that holds counts 0.\n\n| point | quantity | unit | kind | "
          "observed | sigma | simulated | residual (sigmas) |\n|---|---|---|---|---|---|---|---|\n";
    const Evaluation& e = s.levels[s.best_level].best;
    for (size_t k = 0; k < study.observations.size(); ++k) {
      const Observation& o = study.observations[k];
      md += fmt::format("| {} | {} | {} | {} | {:.6g} | {:.3g} | {:.6g} | {:+.2f} |\n", o.point, o.quantity,
                        quantity_unit(o.quantity), kind_name(o.kind), o.value, o.sigma, e.simulated[k], e.residuals[k]);
    }
  }
  const BoundingFriction& f = s.friction;
  md += "\n## Residual basal friction\n\n**" + bounding_friction_sentence(study, s.friction) + "**\n\n";
  if (!f.available) {
    md += "Not computed: " + f.why_not + ".\n";
  } else {
    const Parameter& p = study.parameters[f.parameter];
    md += fmt::format("mu_b = tan(phi_p - i) on interface `{}` (phi_p = {:.4g} deg) with {} = {:.4g}: mu_b = {:.4f} "
                      "(phi_b = {:.2f} deg).\n\n",
                      f.interface, f.peak_angle, p.name, f.best_value, f.mu_best, std::atan(f.mu_best) * 180.0 / M_PI);
    md += fmt::format("Profile of chi2 over {} ({} points, {}{}):\n\n", p.name, f.profile.size(),
                      f.reoptimized ? "other parameters re-optimised at each point" : "other parameters fixed at the best fit",
                      f.corrected ? "; coarse runs corrected to the fine level" : "");
    for (const ProfileRange* r : {&f.delta1, &f.delta4})
      md += fmt::format("- Delta chi2 <= {:g}: {} in [{:.4g}{}, {:.4g}{}] -> mu_b in [{:.4f}, {:.4f}], phi_b in "
                        "[{:.2f}, {:.2f}] deg\n",
                        r->threshold, p.name, r->low, r->low_at_bound ? " (bound)" : "", r->high,
                        r->high_at_bound ? " (bound)" : "", r->mu_low, r->mu_high, std::atan(r->mu_low) * 180.0 / M_PI,
                        std::atan(r->mu_high) * 180.0 / M_PI);
    md += "\nThe lowest mu_b compatible with the observations (Delta chi2 <= 4) is the bounding friction.\n";
  }
  if (s.fidelity.used) md += fidelity_markdown(study, s.fidelity);
  const CovarianceReport& c = s.covariance;
  md += "\n## Linearised covariance (secondary diagnostic)\n\n";
  if (c.computed) {
    for (size_t k = 0; k < c.parameters.size(); ++k)
      md += fmt::format("- {}: standard deviation {:.4g}\n", study.parameters[c.parameters[k]].name,
                        c.standard_deviation[k]);
    if (c.mu_standard_deviation > 0.0) md += fmt::format("- mu_b: standard deviation {:.4f}\n", c.mu_standard_deviation);
    md += fmt::format("- condition number of the weighted Jacobian: {:.3g}\n", c.condition_number);
  }
  for (const std::string& w : c.warnings) md += "- warning: " + w + "\n";
  md += "\n## Charts\n\n![profile](profile.png)\n![fit](fit.png)\n![velocity-distance](velocity_distance.png)\n";
  if (!s.notes.empty()) {
    md += "\n## Notes\n\n";
    for (const std::string& n : s.notes) md += "- " + n + "\n";
  }
  return md;
}

}  // namespace

const char* quantity_unit(const std::string& quantity) {
  if (quantity.find("velocity") != std::string::npos) return "m/s";
  if (quantity.find("displacement") != std::string::npos) return "m";
  if (quantity == "duration") return "s";
  return "-";
}

std::string bounding_friction_sentence(const Study& study, const BoundingFriction& f) {
  if (!f.available) return "No bounding friction: " + f.why_not + ".";
  const auto degrees = [](double mu) { return std::atan(mu) * 180.0 / M_PI; };
  const std::string best = fmt::format("the best fit is mu_b = {:.3f} (phi_b = {:.1f} deg)", f.mu_best, degrees(f.mu_best));
  // With a model spread: the bound with it, then the observations' sigma alone.
  const std::string spread = f.with_model_sigma ? " with the model's spread" : "";
  const std::string alone =
      !f.with_model_sigma ? std::string()
      : f.delta4_observations.high_at_bound
          ? " (observations only: no lower bound within the search bounds)"
          : fmt::format(" (observations only: >= {:.3f}, phi_b = {:.1f} deg)", f.delta4_observations.mu_low,
                        degrees(f.delta4_observations.mu_low));
  // mu_b = tan(phi_p - i) falls as the profiled degradation or roughness rises, so the
  // lowest friction sits at the range's upper end of the parameter.
  if (f.delta4.high_at_bound)
    return fmt::format("Basal friction as low as mu_b = {:.3f} (phi_b = {:.1f} deg, {} at its upper search bound) is "
                       "still compatible at Delta chi2 <= 4{}{} (interface `{}`): no lower bound was found; widen "
                       "the bound to find one. {}{}.",
                       f.delta4.mu_low, degrees(f.delta4.mu_low), study.parameters[f.parameter].name, spread,
                       alone, f.interface,
                       static_cast<char>(std::toupper(best[0])), best.substr(1));
  return fmt::format("Basal friction cannot have dropped below mu_b = {:.3f} (phi_b = {:.1f} deg) at Delta chi2 <= 4{}{} "
                     "(interface `{}`); {}.",
                     f.delta4.mu_low, degrees(f.delta4.mu_low), spread, alone, f.interface, best);
}

std::vector<std::string> write_report(const std::string& dir, const Study& given, const InversionSummary& summary) {
  // The observations as fitted (a measured model_sigma filled in).
  Study study = given;
  if (!summary.observations.empty()) study.observations = summary.observations;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir + ": cannot create the folder (" + ec.message() + ")");
  const std::filesystem::path d(dir);
  {
    std::ofstream out(d / "report.json");
    out << report_json(study, summary).dump(2) << "\n";
    if (!out) throw std::runtime_error(dir + ": cannot write report.json");
  }
  const std::string text = markdown(study, summary);
  {
    std::ofstream out(d / "report.md");
    out << text;
    if (!out) throw std::runtime_error(dir + ": cannot write report.md");
  }
  std::vector<std::string> notes;
  std::string reason;
  if (!plot_report(dir, study, summary, reason)) notes.push_back("charts not drawn: " + reason);
  // report.html after the charts, which it embeds.
  io::HtmlReport page;
  page.title = "Back-analysis: " + study.path;
  page.headline = bounding_friction_sentence(study, summary.friction);
  page.markdown = text;
  page.settings = {{"study", study.path}, {"model revision", kModelRevision}};
  io::write_html_report(dir, page);
  return notes;
}

}  // namespace ddafit::inverse
