#include <cmath>
#include <cstdio>

#include "forward/geometry.hpp"
#include "forward/mesh/region.hpp"

namespace ddafit {

std::vector<SceneError> validate_mesh_settings(const MeshSettings& m) {
  std::vector<SceneError> errors;
  const auto expect = [&](bool ok, const char* key, double value, const char* rule) {
    if (ok) return;
    char text[64];
    std::snprintf(text, sizeof text, "is %g; ", value);
    errors.push_back({key, text + std::string(rule)});
  };
  expect(m.block_size == 0.0 || (m.block_size > 0.0 && m.block_size <= 1e6), "mesh.block_size", m.block_size,
         "must be in (0, 1e6] m");
  expect(m.min_area_ratio >= 0.0 && m.min_area_ratio < 1.0, "mesh.min_area_ratio", m.min_area_ratio,
         "must be in [0, 1)");
  expect(m.min_angle >= 0.0 && m.min_angle < 60.0, "mesh.min_angle", m.min_angle, "must be in [0, 60) degrees");
  expect(m.min_edge_ratio >= 0.0 && m.min_edge_ratio < 0.5, "mesh.min_edge_ratio", m.min_edge_ratio,
         "must be in [0, 0.5)");
  expect(m.max_arrangement_edges >= 1e3 && m.max_arrangement_edges <= 1e8, "mesh.max_arrangement_edges",
         m.max_arrangement_edges, "must be in [1e3, 1e8] (1e8 edges is about ten minutes of cutting)");
  return errors;
}

std::vector<RegionMesh> generate_blocks(Scene& scene, std::string& problem) {
  if (scene.explicit_block_count < 0) scene.explicit_block_count = static_cast<int>(scene.blocks.size());
  std::vector<BlockInput> blocks(scene.blocks.begin(), scene.blocks.begin() + scene.explicit_block_count);
  std::vector<RegionMesh> meshes;
  for (size_t r = 0; r < scene.regions.size(); ++r) {
    const RegionInput& region = scene.regions[r];
    RegionMesh mesh;
    mesh.region = region.name;
    std::vector<std::vector<Vec2>> polygons;
    if (region.joint_sets.empty()) {
      polygons.push_back(region.polygon);  // an uncut region is one block (bedrock)
      mesh.stats.block_count = 1;
      mesh.stats.smallest_area = std::abs(signed_area(region.polygon));
    } else {
      const double size = region.block_size > 0.0 ? region.block_size : scene.mesh.block_size;
      if (!(size > 0.0)) {
        problem = "regions[" + std::to_string(r) + "]: joint sets need a block size: set mesh.block_size or the "
                  "region's block_size";
        return {};
      }
      polygons = cut_region(region, scene.mesh, mesh.stats, problem);
      if (!problem.empty()) {
        problem = "regions[" + std::to_string(r) + "]: " + problem;
        return {};
      }
    }
    double total = 0.0;
    for (const auto& p : polygons) total += std::abs(signed_area(p));
    mesh.stats.mean_block_size = std::sqrt(total / static_cast<double>(polygons.size()));
    for (size_t k = 0; k < polygons.size(); ++k) {
      BlockInput b;
      char suffix[32];
      std::snprintf(suffix, sizeof suffix, "_%05zu", k + 1);
      b.name = polygons.size() == 1 ? region.name : region.name + suffix;
      b.group = region.group.empty() ? region.name : region.group;
      b.material = region.material;
      b.fixed = region.fixed;
      b.polygon = polygons[k];
      blocks.push_back(std::move(b));
    }
    meshes.push_back(mesh);
  }
  scene.blocks = std::move(blocks);
  return meshes;
}

}  // namespace ddafit
