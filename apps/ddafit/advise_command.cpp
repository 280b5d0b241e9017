// `ddafit advise SCENE --quantity Q --point P`: block-size advice (forward/analysis/
// block_size_advice.hpp). The mesher cuts the scene's regions again at each size of a ladder,
// coarse to fine; each size runs as a small ensemble for its spread; the advice names the
// coarsest size within the tolerance of the next finer, or says the answer keeps moving.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "batch/ensemble_runs.hpp"
#include "forward/analysis/block_size_advice.hpp"
#include "forward/io/run_files.hpp"

namespace ddafit::app {
namespace {

void write_advice(const std::string& dir, const AdviseArgs& args, const BlockSizeAdvice& a) {
  nlohmann::ordered_json j;
  j["scene"] = args.scene;
  j["point"] = args.point;
  j["quantity"] = args.quantity;
  j["tolerance"] = a.tolerance;
  j["members_per_size"] = args.members;
  j["rule"] = "a size is converged when |m_k - m_k+1| / |m_k+1| <= max(tolerance, 2 sqrt(s_k^2 + s_k+1^2) / |m_k+1|)";
  j["rungs"] = nlohmann::ordered_json::array();
  for (size_t k = 0; k < a.rungs.size(); ++k) {
    const LadderRung& r = a.rungs[k];
    nlohmann::ordered_json row = {{"block_size", r.block_size},     {"free_blocks", r.free_blocks},
                                  {"completed", r.completed},        {"mean", r.value.mean},
                                  {"standard_deviation", r.value.standard_deviation},
                                  {"low", r.value.low},              {"high", r.value.high},
                                  {"wall_seconds", r.wall_seconds}};
    if (k < a.change.size()) {
      row["change_to_next_finer"] = std::isfinite(a.change[k]) ? nlohmann::ordered_json(a.change[k]) : nullptr;
      row["allowed"] = a.allowed[k];
    }
    j["rungs"].push_back(row);
  }
  j["recommended_block_size"] = a.recommended >= 0 ? nlohmann::ordered_json(a.rungs[a.recommended].block_size) : nullptr;
  j["verdict"] = a.verdict;
  std::ofstream(std::filesystem::path(dir) / "advise.json") << j.dump(2) << "\n";
}

}  // namespace

int run_advise(const AdviseArgs& args) {
  Scene base;
  if (!load_scene(args.scene, args.sets, base)) return kExitBadInput;
  if (base.regions.empty()) {
    std::cerr << args.scene << ": regions: advise needs a scene with regions (the mesher cuts them again at each block "
                               "size); this one gives its blocks one by one\n";
    return kExitBadInput;
  }
  std::vector<double> sizes = args.sizes;
  if (sizes.empty()) {
    const double b = base.mesh.block_size;
    sizes = {4.0 * b, 2.0 * b, b};
  }
  std::sort(sizes.begin(), sizes.end(), std::greater<double>());
  if (sizes.size() < 2 || !(sizes.back() > 0.0) || std::adjacent_find(sizes.begin(), sizes.end()) != sizes.end()) {
    std::cerr << "ddafit advise: --sizes: give at least two different block sizes > 0 m\n";
    return kExitBadInput;
  }
  bool known = false;
  for (const PointQuantity& q : kPointQuantities) known = known || args.quantity == q.name;
  if (!known) {
    std::cerr << "ddafit advise: --quantity: unknown quantity '" << args.quantity
              << "'; use max_lateral_displacement, max_total_displacement, peak_lateral_velocity, "
                 "peak_total_velocity or duration\n";
    return kExitBadInput;
  }
  if (const std::string problem = io::prepare_output_folder(args.out); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  std::vector<LadderRung> rungs;
  std::cout << fmt::format("{:>10} {:>8} {:>10} {:>12} {:>10}  ({} of point {}, {} realisations per size)\n",
                           "size (m)", "blocks", "completed", "mean", "std", args.quantity, args.point, args.members);
  for (const double size : sizes) {
    std::vector<std::string> sets = args.sets;
    sets.push_back(fmt::format("mesh.block_size={}", size));
    Scene scene;
    if (!load_scene(args.scene, sets, scene)) return kExitBadInput;
    const std::vector<SimulationResult> members =
        batch::run_ensemble(scene, batch::ensemble_runs(args.members, args.jobs, args.threads));
    if (members.front().summary.status == RunStatus::InvalidScene) {
      std::cerr << args.scene << " (block_size " << size << "): " << members.front().summary.message << "\n";
      return kExitBadInput;
    }
    std::vector<SimulationSummary> summaries;
    LadderRung rung;
    rung.block_size = size;
    for (const BlockInput& b : scene.blocks) rung.free_blocks += b.fixed ? 0 : 1;
    for (const SimulationResult& m : members) {
      summaries.push_back(m.summary);
      rung.wall_seconds += m.summary.profile.total;
    }
    const EnsembleSummary e = summarise_ensemble(summaries);
    rung.completed = e.completed;
    const Spread* spread = find_spread(e, args.point, args.quantity);
    if (e.completed > 0 && spread == nullptr) {
      std::cerr << args.scene << ": --point: no measure point '" << args.point << "' in the scene\n";
      return kExitBadInput;
    }
    if (spread) rung.value = *spread;
    std::cout << fmt::format("{:>10g} {:>8} {:>10} {:>12.4g} {:>10.3g}\n", size, rung.free_blocks,
                             fmt::format("{}/{}", e.completed, args.members), rung.value.mean,
                             rung.value.standard_deviation)
              << std::flush;
    rungs.push_back(rung);
  }
  const BlockSizeAdvice advice = advise_block_size(rungs, args.tolerance);
  write_advice(args.out, args, advice);
  std::cout << advice.verdict << "\nwrote " << args.out << "/advise.json\n";
  return kExitSuccess;
}

}  // namespace ddafit::app
