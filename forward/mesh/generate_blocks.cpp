#include <cmath>
#include <cstdio>

#include "forward/geometry.hpp"
#include "forward/mesh/region.hpp"

namespace ddafit {

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
