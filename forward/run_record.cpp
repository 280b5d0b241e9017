#include "forward/run_record.hpp"

#include "forward/top_surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace ddafit {

void report_overlap(const BlockSystem& s, const WorstOverlap& worst, SolverReport& report) {
  report.worst_penetration = worst.depth;
  report.worst_penetration_ratio = worst.ratio;
  report.worst_penetration_time = worst.time;
  if (worst.block_a >= 0)
    report.worst_penetration_at = "blocks '" + s.block_names[worst.block_a] + "' and '" + s.block_names[worst.block_b] + "'";
}

std::string overlap_warning(const Scene& scene, const SolverReport& report) {
  if (!(report.worst_penetration_ratio > kOverlapBoundRatio)) return {};
  const SimulationOptions& o = scene.options;
  std::ostringstream out;
  out.precision(3);
  out << "the worst overlap, " << report.worst_penetration << " m at t = " << report.worst_penetration_time
      << " s between " << report.worst_penetration_at << ", is " << 100.0 * report.worst_penetration_ratio
      << " % of the smaller block, over the " << 100.0 * kOverlapBoundRatio
      << " % ddafit's runs are checked to (docs/theory.md, \"Failure diagnosis\"): the blocks sank into each other "
         "there; ";
  if (report.integrator == Integrator::Substep) {
    out << "shorten time.step (now " << scene.max_step << " s) or raise time.substeps (now " << o.substeps << ")";
    // A deep-overlap ratio the scene set (0 = automatic) is where the position correction starts.
    if (o.deep_overlap_ratio > 0.0) out << ", or lower control.deep_overlap_ratio (now " << o.deep_overlap_ratio << ")";
  } else {
    out << "lower control.max_penetration_ratio (now " << o.max_penetration_ratio << ") or time.step (now "
        << scene.max_step << " s)";
  }
  return out.str();
}

Vec2 point_velocity(const BlockSystem& s, const MaterialPoint& p) {
  const Block& b = s.blocks[p.block];
  if (b.unknown < 0) return Vec2::Zero();
  return displacement_matrix(p.position, b.centroid) * b.velocity;
}

RunRecorder::RunRecorder(const Scene& scene, const SimulationHooks& hooks, SimulationResult& result)
    : scene_(scene),
      hooks_(hooks),
      result_(result),
      next_output_(scene.output_interval),
      end_slack_(1e-9 * scene.duration),
      last_progress_(std::chrono::steady_clock::now()) {
  for (const MeasurePoint& m : scene.measure) result_.summary.points.push_back({m.name});
}

void RunRecorder::record_row(double time, const BlockSystem& s) {
  for (size_t k = 0; k < s.points.size(); ++k) {
    const MaterialPoint& p = s.points[k];
    result_.history.push_back({time, static_cast<int>(k), p.position, p.position - p.initial_position,
                               point_velocity(s, p)});
  }
}

void RunRecorder::start(const BlockSystem& s) {
  record(0.0, s);
}

double RunRecorder::next_row_time() const {
  return scene_.output_interval > 0.0 ? std::min(next_output_, scene_.duration) : scene_.duration;
}

double RunRecorder::fit_step(double time, double step, double* landing) const {
  *landing = -1.0;
  const double target = next_row_time();
  if (target - time <= step * (1.0 + 1e-6)) {
    *landing = target;
    return target - time;
  }
  return step;
}

double RunRecorder::even_step(double time, double step, double* landing) const {
  const double dt = fit_step(time, step, landing);
  if (*landing >= 0.0) return dt;
  const double to_go = next_row_time() - time;
  return to_go / std::ceil(to_go / step * (1.0 - 1e-6));
}

void RunRecorder::record(double time, const BlockSystem& s) {
  for (size_t k = 0; k < s.points.size(); ++k) {
    const MaterialPoint& p = s.points[k];
    const Vec2 u = p.position - p.initial_position;
    const Vec2 v = point_velocity(s, p);
    PointSummary& sum = result_.summary.points[k];
    sum.max_lateral_displacement = std::max(sum.max_lateral_displacement, std::abs(u.x()));
    sum.max_total_displacement = std::max(sum.max_total_displacement, u.norm());
    sum.peak_lateral_velocity = std::max(sum.peak_lateral_velocity, std::abs(v.x()));
    sum.peak_total_velocity = std::max(sum.peak_total_velocity, v.norm());
    if (v.norm() >= scene_.rest_speed) sum.duration = time;
    sum.stopped = v.norm() < scene_.rest_speed;
  }
  const bool at_start = time == 0.0;
  const bool at_output = scene_.output_interval <= 0.0 || time >= next_output_ - end_slack_;
  // The ground the run leaves, once, at its end (not at every output).
  if (finished(time)) result_.summary.final_surface = top_surface(s);
  if (at_start || at_output || finished(time)) {
    record_row(time, s);
    if (hooks_.on_output) hooks_.on_output(time, s);
    while (scene_.output_interval > 0.0 && next_output_ <= time + end_slack_)
      next_output_ = static_cast<double>(++output_count_) * scene_.output_interval;
  }
  const auto now = std::chrono::steady_clock::now();
  if (hooks_.on_progress && now - last_progress_ > std::chrono::seconds(1)) {
    hooks_.on_progress(time, scene_.duration);
    last_progress_ = now;
  }
}

bool RunRecorder::interrupted(double time, const BlockSystem& s) {
  if (!hooks_.should_stop || !hooks_.should_stop()) return false;
  SimulationSummary& summary = result_.summary;
  summary.status = RunStatus::Interrupted;
  char text[96];
  std::snprintf(text, sizeof text, "interrupted at t = %.4g s of %.4g s", time, scene_.duration);
  summary.message = text;
  summary.run.simulated_time = time;
  if (result_.history.empty() || result_.history.back().time < time) record_row(time, s);
  return true;
}

}  // namespace ddafit
