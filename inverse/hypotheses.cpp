#include "inverse/hypotheses.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "forward/io/gnuplot.hpp"
#include "inverse/report.hpp"

namespace ddafit::inverse {
namespace {

// Burnham & Anderson's threshold: Delta AIC below it is substantial support for both.
constexpr double kIndistinguishableAic = 2.0;

std::string verdict_of(const HypothesisRanking& r) {
  if (r.fits.empty() || r.fits.front().failed) return "No hypothesis could be fitted: every run failed.";
  if (r.tied.size() > 1) {
    std::string names;
    for (size_t k = 0; k < r.tied.size(); ++k) names += (k ? (k + 1 == r.tied.size() ? " and " : ", ") : "") + r.tied[k];
    return fmt::format("{} are not distinguishable on these observations (Delta AIC < {:g}).", names,
                       kIndistinguishableAic);
  }
  const HypothesisFit& best = r.fits.front();
  const double gap = r.fits.size() > 1 && !r.fits[1].failed ? r.fits[1].delta_aic : INFINITY;
  return fmt::format("{} explains these observations best (AIC {:.2f}; the next is {:.2f} worse).", best.name, best.aic,
                     gap);
}

}  // namespace

Study read_checked_study(const std::string& path) {
  Study study = read_study(path);
  if (study.hypotheses.empty()) check_study_against_scene(study);
  for (const Hypothesis& h : study.hypotheses) check_study_against_scene(hypothesis_study(study, h));
  return study;
}

Study hypothesis_study(const Study& study, const Hypothesis& h) {
  Study s = study;
  s.hypotheses.clear();
  for (const auto& kv : h.settings) s.settings.push_back(kv);
  if (!h.parameters.empty()) s.parameters = h.parameters;
  return s;
}

HypothesisRanking rank_hypotheses(std::vector<HypothesisFit> fits) {
  HypothesisRanking r;
  for (HypothesisFit& f : fits) {
    const InversionSummary& s = f.summary;
    f.failed = s.best_level < 0 || s.levels[s.best_level].best.failed;
    f.observations = static_cast<int>(f.study.observations.size());
    f.fitted = static_cast<int>(std::count_if(f.study.parameters.begin(), f.study.parameters.end(),
                                              [](const Parameter& p) { return !p.discrete(); }));
    if (f.failed) continue;
    f.chi2 = s.levels[s.best_level].best.chi2;
    f.aic = f.chi2 + 2.0 * f.fitted;
    f.bic = f.chi2 + f.fitted * std::log(static_cast<double>(std::max(f.observations, 1)));
  }
  std::stable_sort(fits.begin(), fits.end(), [](const HypothesisFit& a, const HypothesisFit& b) {
    if (a.failed != b.failed) return !a.failed;
    return !a.failed && a.aic < b.aic;
  });
  double best_bic = INFINITY;
  for (const HypothesisFit& f : fits)
    if (!f.failed) best_bic = std::min(best_bic, f.bic);
  for (HypothesisFit& f : fits) {
    if (f.failed) continue;
    f.delta_aic = f.aic - fits.front().aic;
    f.delta_bic = f.bic - best_bic;
    if (f.delta_aic < kIndistinguishableAic) r.tied.push_back(f.name);
  }
  r.fits = std::move(fits);
  r.verdict = verdict_of(r);
  return r;
}

std::vector<std::string> write_ranking(const std::string& dir, const HypothesisRanking& r) {
  namespace fs = std::filesystem;
  using nlohmann::json;
  std::vector<std::string> notes;
  const fs::path d(dir);
  json j;
  j["verdict"] = r.verdict;
  j["tied"] = r.tied;
  j["criterion"] = "AIC = chi2 + 2k, BIC = chi2 + k ln n; Delta AIC < 2: not distinguishable";
  j["hypotheses"] = json::array();
  std::string md = "# Hypotheses ranked\n\n**" + r.verdict + "**\n\n";
  md += "| rank | hypothesis | chi² | k | n | AIC | ΔAIC | BIC | ΔBIC | bounding friction |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|\n";
  int rank = 0;
  for (const HypothesisFit& f : r.fits) {
    const std::string sentence = bounding_friction_sentence(f.study, f.summary.friction);
    json h = {{"name", f.name}, {"failed", f.failed}, {"fitted_parameters", f.fitted}, {"observations", f.observations},
              {"bounding_friction", sentence}, {"report", (fs::path("hypotheses") / f.name / "report.md").string()}};
    if (!f.failed) {
      h["chi2"] = f.chi2;
      h["aic"] = f.aic;
      h["bic"] = f.bic;
      h["delta_aic"] = f.delta_aic;
      h["delta_bic"] = f.delta_bic;
      const BoundingFriction& b = f.summary.friction;
      if (b.available) h["mu_best"] = b.mu_best, h["mu_delta4"] = {b.delta4.mu_low, b.delta4.mu_high};
      md += fmt::format("| {} | [{}](hypotheses/{}/report.md) | {:.3f} | {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {} |\n",
                        ++rank, f.name, f.name, f.chi2, f.fitted, f.observations, f.aic, f.delta_aic, f.bic,
                        f.delta_bic, sentence);
    } else {
      md += fmt::format("| − | {} | failed | {} | {} | − | − | − | − | {} |\n", f.name, f.fitted, f.observations, sentence);
    }
    j["hypotheses"].push_back(h);
  }
  md += "\nk: fitted continuous parameters; n: observations. Each hypothesis's fit, profile and report are in "
        "`hypotheses/NAME/`. ΔAIC < 2 means the observations support both (Burnham & Anderson 2002); a lower χ² "
        "with more parameters is not by itself a better explanation.\n\n![the best run of each](ranking.png)\n";
  {
    std::ofstream out(d / "ranking.md");
    out << md;
    std::ofstream js(d / "ranking.json");
    js << j.dump(2) << "\n";
    if (!out || !js) throw std::runtime_error("cannot write ranking.md / ranking.json");
  }

  // The chart: point of the first displacement or velocity observation, each best run.
  const Study* first = r.fits.empty() ? nullptr : &r.fits.front().study;
  std::string point;
  bool lateral_u = false, lateral_v = false;  // axes as observed: lateral or total
  if (first)
    for (const Observation& o : first->observations) {
      if (point.empty() && (is_displacement(o.quantity) || is_velocity(o.quantity))) point = o.point;
      lateral_u = lateral_u || o.quantity == "max_lateral_displacement";
      lateral_v = lateral_v || o.quantity == "peak_lateral_velocity";
    }
  const std::string script = (d / "ranking.gp").string();
  auto gp = fmt::output_file(script);
  gp.print("set terminal pngcairo size 1200,800 font ',12'\nset grid\nset output '{}'\n", (d / "ranking.png").string());
  gp.print("set key outside right noenhanced\nset title 'best fit of each hypothesis, point {}' noenhanced\n", point);
  gp.print("set xlabel '{} (m)' noenhanced\nset ylabel '{} (m/s)' noenhanced\n",
           lateral_u ? "lateral displacement |u_x|" : "displacement |u|", lateral_v ? "lateral speed |v_x|" : "speed |v|");
  int arrows = 0;
  if (first)
    for (const Observation& o : first->observations) {
      if (o.point != point || !(is_displacement(o.quantity) || is_velocity(o.quantity))) continue;
      for (double v : {o.value - o.sigma, o.value + o.sigma}) {
        if (is_displacement(o.quantity))
          gp.print("set arrow {} from first {:.9g}, graph 0 to first {:.9g}, graph 1 nohead dt 3\n", ++arrows, v, v);
        else
          gp.print("set arrow {} from graph 0, first {:.9g} to graph 1, first {:.9g} nohead dt 3\n", ++arrows, v, v);
      }
    }
  std::string plot;
  for (const HypothesisFit& f : r.fits) {
    if (f.failed) continue;
    const LevelFit& level = f.summary.levels[f.summary.best_level];
    const auto& names = level.best.point_names;
    const auto at = std::find(names.begin(), names.end(), point);
    if (at == names.end() || level.history.empty()) continue;
    const int index = static_cast<int>(at - names.begin());
    const std::string data = (d / ("ranking_" + f.name + ".dat")).string();
    auto dat = fmt::output_file(data);
    dat.print("# displacement (m), speed (m/s), {} and {}: best run of {}\n", lateral_u ? "lateral" : "total",
              lateral_v ? "lateral" : "total", f.name);
    for (const HistoryRow& row : level.history)
      if (row.point == index)
        dat.print("{:.9g} {:.9g}\n", lateral_u ? std::abs(row.displacement.x()) : row.displacement.norm(),
                  lateral_v ? std::abs(row.velocity.x()) : row.velocity.norm());
    dat.close();
    plot += fmt::format("{}'{}' using 1:2 with lines lw 2 title '{} (chi2 {:.2f})'", plot.empty() ? "plot " : ", ", data,
                        f.name, f.chi2);
  }
  if (plot.empty()) plot = "plot 0 notitle";
  gp.print("{}\n", plot);
  gp.close();
  std::string reason;
  if (!io::run_gnuplot(script, "ranking.md and ranking.json", reason)) notes.push_back(reason);
  return notes;
}

}  // namespace ddafit::inverse
