// The scene reader, the region/CSV reader with the mesher behind it, and --set.
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "forward/io/ddaml_import.hpp"
#include "forward/io/scene_reader.hpp"
#include "fuzz/targets.hpp"
#include "verify/cases.hpp"

namespace ddafit::fuzz {
namespace {

// Reads `text` as a scene; a refusal must be one printable line.
void read(const std::string& text, const std::string& base_dir,
          const std::vector<std::pair<std::string, std::string>>& overrides) {
  try {
    io::parse_scene(text, "fuzz.yaml", base_dir, overrides);
  } catch (const io::SceneReadError& e) {
    check_message(e.what());
  }
}

}  // namespace

int scene_reader(const std::uint8_t* data, std::size_t size) {
  read(std::string(reinterpret_cast<const char*>(data), size), "", {});
  return 0;
}

int region_mesh(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const size_t split = input.find("\n%%\n");
  const std::string scene = input.substr(0, split);
  const std::string csv = split == std::string::npos ? "" : input.substr(split + 4);
  const std::filesystem::path dir = scratch_folder();
  {
    std::ofstream out(dir / "surface.csv", std::ios::binary | std::ios::trunc);
    out << csv;
  }
  // A tenth of the default work bound (mesh.max_arrangement_edges): 2e5 edges take ~17 s
  // under the sanitizers, so every input the mesher accepts ends well inside the fuzzer's
  // 60 s timeout. The refusal above the bound is the same code at any value.
  read(scene, dir.string(), {{"mesh.max_arrangement_edges", "2e5"}});
  return 0;
}

int set_parser(const std::uint8_t* data, std::size_t size) {
  static const std::string incline = io::scene_to_yaml(verification::incline_scene({}));
  std::vector<std::pair<std::string, std::string>> overrides;
  std::string line;
  const std::string input(reinterpret_cast<const char*>(data), size);
  for (size_t start = 0; start <= input.size();) {
    size_t end = input.find('\n', start);
    if (end == std::string::npos) end = input.size();
    line = input.substr(start, end - start);
    const size_t eq = line.find('=');
    // The command line refuses a --set without '=' or with an empty key before this point.
    if (eq != std::string::npos && eq > 0) overrides.emplace_back(line.substr(0, eq), line.substr(eq + 1));
    start = end + 1;
  }
  read(incline, "", overrides);
  return 0;
}

int ddaml(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const size_t split = input.find("\n%%\n");
  const std::filesystem::path dir = scratch_folder();
  {
    std::ofstream geo(dir / "in.geo", std::ios::binary | std::ios::trunc);
    geo << input.substr(0, split);
    std::ofstream ana(dir / "in.ana", std::ios::binary | std::ios::trunc);
    ana << (split == std::string::npos ? "" : input.substr(split + 4));
  }
  try {
    io::import_ddaml((dir / "in.geo").string(), split == std::string::npos ? "" : (dir / "in.ana").string(),
                     io::DdamlUnits::SI);
  } catch (const io::SceneReadError& e) {
    check_message(e.what());
  }
  return 0;
}

}  // namespace ddafit::fuzz
