#include "forward/io/run_files.hpp"

#include "forward/earthquake/ground_motion.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "forward/io/run_json.hpp"
#include "forward/perturb.hpp"

namespace ddafit::io {
namespace {

void write_json(const std::string& path, const nlohmann::ordered_json& j) {
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace

std::string prepare_output_folder(const std::string& out) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) return out + ": --out: cannot create the folder (" + ec.message() + ")";
  if (!fs::is_directory(out, ec)) return out + ": --out: not a folder";
  // Permissions alone do not say it (root ignores them; a read-only mount does not):
  // write a file and remove it.
  const fs::path probe = fs::path(out) / ".ddafit-write-check";
  {
    std::ofstream file(probe);
    file << "ok\n";
    if (!file) return out + ": --out: cannot write in the folder (" + std::strerror(errno) + ")";
  }
  fs::remove(probe, ec);
  return {};
}

void write_history_csv(const std::string& path, const Scene& scene, const SimulationResult& result) {
  auto out = fmt::output_file(path);
  // In an earthquake the run's positions, displacements and velocities are relative to the
  // ground (as a Newmark analysis gives them); the absolute ones follow as extra columns.
  // (The sled ignores the shaking: no absolute columns for it.)
  const GroundTrack ground(scene.options.integrator == Integrator::Sled ? GroundMotion{} : scene.earthquake);
  out.print("time,point,x,y,ux,uy,vx,vy{}\n", ground.present() ? ",ux_abs,uy_abs,vx_abs,vy_abs" : "");
  for (const HistoryRow& h : result.history) {
    out.print("{:.9g},{},{:.12g},{:.12g},{:.9g},{:.9g},{:.9g},{:.9g}", h.time, scene.measure[h.point].name,
              h.position.x(), h.position.y(), h.displacement.x(), h.displacement.y(), h.velocity.x(),
              h.velocity.y());
    if (ground.present()) {
      const GroundState g = ground.at(h.time);
      const Vec2 u = h.displacement + g.displacement, v = h.velocity + g.velocity;
      out.print(",{:.9g},{:.9g},{:.9g},{:.9g}", u.x(), u.y(), v.x(), v.y());
    }
    out.print("\n");
  }
}

std::string summary_json_text(const std::string& scene_path, const SimulationResult& result) {
  const SimulationSummary& s = result.summary;
  nlohmann::ordered_json j;
  j["scene"] = scene_path;
  j["status"] = status_name(s.status);
  if (!s.message.empty()) j["message"] = s.message;
  j["warnings"] = s.warnings;
  j["points"] = nlohmann::ordered_json::object();
  for (const PointSummary& p : s.points) j["points"][p.name] = point_json<nlohmann::ordered_json>(p);
  j["run"] = {{"steps", s.run.steps},
              {"open_close_iterations", s.run.open_close_iterations},
              {"step_cuts", s.run.step_cuts},
              {"penalty_raises", s.run.penalty_raises},
              {"unsettled_contacts", s.run.unsettled_contacts},
              {"symbolic_analyses", s.run.symbolic_analyses},
              {"factorizations", s.run.factorizations},
              {"cg_solves", s.run.cg_solves},
              {"factor_updates", s.run.factor_updates},
              {"update_rank", s.run.update_rank},
              {"wall_seconds", s.profile.total},
              {"simulated_time", s.run.simulated_time},
              {"smallest_step", s.run.smallest_step},
              {"largest_step", s.run.largest_step},
              {"final_penalty", s.run.final_penalty}};
  const SolverReport& solver = s.solver;
  j["solver"] = {{"integrator", to_string(solver.integrator)}, {"reason", solver.reason}};
  // Both solvers measure the deepest overlap of a contact point at the end of every step.
  j["solver"]["worst_penetration"] = solver.worst_penetration;
  j["solver"]["worst_penetration_ratio"] = solver.worst_penetration_ratio;
  j["solver"]["worst_penetration_time"] = solver.worst_penetration_time;
  j["solver"]["worst_penetration_at"] = solver.worst_penetration_at;
  if (solver.integrator == Integrator::Substep) {
    const double steps = std::max<double>(1.0, static_cast<double>(s.run.steps));
    j["solver"]["substeps"] = solver.substeps;
    j["solver"]["deep_overlap_ratio"] = solver.deep_overlap_ratio;
    j["solver"]["stored_contact_energy"] = solver.stored_contact_energy;
    j["solver"]["quiet_start_steps"] = solver.quiet_start_steps;
    j["solver"]["quiet_start_change"] = solver.quiet_start_change;
    j["solver"]["mean_contact_points"] = static_cast<double>(solver.contact_points) / steps;
    j["solver"]["unconverged_points"] = solver.unconverged_points;
    j["solver"]["fast_steps"] = solver.fast_steps;
    j["solver"]["sleeping_block_steps"] = solver.sleeping_block_steps;
    j["solver"]["wakes"] = solver.wakes;
    if (solver.all_asleep_time >= 0.0) j["solver"]["all_asleep_time"] = solver.all_asleep_time;
    j["solver"]["steps_on_one_thread"] = solver.steps_on_one_thread;
    j["solver"]["impact_groups"] = solver.impact_groups;
    j["solver"]["impact_groups_too_large"] = solver.impact_groups_too_large;
    j["solver"]["impact_groups_with_friction"] = solver.impact_groups_with_friction;
    j["solver"]["impact_group_pieces"] = solver.impact_group_pieces;
    j["solver"]["impact_groups_refused"] = solver.impact_groups_refused;
  }
  j["profile_seconds"] = {{"settle", s.profile.settle},
                          {"find_contacts", s.profile.find_contacts},
                          {"assemble", s.profile.assemble},
                          {"solve", s.profile.solve},
                          {"check_contacts", s.profile.check_contacts},
                          {"update", s.profile.update}};
  return j.dump(2) + "\n";
}

void write_summary_json(const std::string& path, const std::string& scene_path, const SimulationResult& result) {
  std::ofstream out(path);
  out << summary_json_text(scene_path, result);
  if (!out) throw std::runtime_error(path + ": cannot write");
}

std::string stable_json_text(const StableSearchInput& in, const StableSearchResult& r) {
  nlohmann::ordered_json j;
  j["scene"] = in.scene_path;
  j["interface"] = in.interface;
  const StableSearchOptions& o = in.options;
  j["criterion"] = {{"rule", "over the last rest_window s of a trial, every measure point is slower than rest_speed "
                             "and the speeds are not rising (their mean over the window's second half <= 1.1 x the "
                             "first half's + 0.05 rest_speed)"},
                    {"rest_speed", in.rest_speed},
                    {"rest_window", o.rest_window},
                    {"trial_duration", o.trial_duration},
                    {"max_movement", o.max_movement}};
  j["tolerance"] = o.tolerance;
  j["bracketed"] = r.bracketed;
  j["low"] = r.low;
  j["high"] = r.high;
  if (!r.message.empty()) j["message"] = r.message;
  for (const StableTrial& t : r.trials) {
    nlohmann::ordered_json trial = {{"friction_angle", t.friction_angle}, {"movement", t.movement},
                                    {"window_speed", t.window_speed},     {"end_speed", t.end_speed},
                                    {"rising", t.rising},                 {"stable", t.stable}};
    if (!t.failure.empty()) trial["failure"] = t.failure;
    j["trials"].push_back(trial);
  }
  return j.dump(2) + "\n";
}

void write_stable_json(const std::string& path, const StableSearchInput& in, const StableSearchResult& r) {
  std::ofstream out(path);
  out << stable_json_text(in, r);
  if (!out) throw std::runtime_error(path + ": cannot write");
}

void write_ensemble_json(const std::string& path, const std::string& scene_path, const EnsembleSummary& e) {
  nlohmann::ordered_json j;
  j["scene"] = scene_path;
  j["members"] = e.members;
  j["completed"] = e.completed;
  j["jitter"] = fmt::format("realisation 0 is the scene as given; realisation k >= 1 shifts every free block rigidly "
                            "by an offset uniform in a disc of radius {} x sqrt(block area), drawn from SplitMix64 "
                            "seeded with k (forward/perturb.hpp)", e.jitter_ratio);
  j["failures"] = e.failures;
  j["points"] = nlohmann::ordered_json::object();
  for (const EnsemblePoint& p : e.points) {
    nlohmann::ordered_json& point = j["points"][p.name];
    for (size_t q = 0; q < p.quantities.size(); ++q) {
      const Spread& s = p.quantities[q];
      point[kPointQuantities[q].name] = {{"mean", s.mean}, {"standard_deviation", s.standard_deviation},
                                         {"low", s.low},   {"high", s.high}};
    }
  }
  write_json(path, j);
}

void write_ensemble_csv(const std::string& path, const std::vector<SimulationResult>& members) {
  std::ofstream out(path);
  out << "realisation,status,point";
  for (const PointQuantity& q : kPointQuantities) out << "," << q.name;
  out << "\n";
  for (size_t k = 0; k < members.size(); ++k)
    for (const PointSummary& p : members[k].summary.points) {
      out << k << "," << status_name(members[k].summary.status) << "," << p.name;
      for (const PointQuantity& q : kPointQuantities) out << fmt::format(",{:.12g}", q.get(p));
      out << "\n";
    }
  if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace ddafit::io
