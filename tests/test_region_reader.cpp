// Malformed regions and joint sets: each gets a one-line SceneReadError naming the file
// and the key (the CLI turns it into exit code 2).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "forward/io/scene_reader.hpp"

namespace ddafit::io {
namespace {

const std::string kHead = R"(time: {duration: 1, step: 0.01}
materials: {rock: {density: 2500, young_modulus: 5e9, poisson_ratio: 0.25}}
interfaces: {joint: {friction_angle: 30}}
mesh: {block_size: 5}
)";

// Expects parse_scene to throw with the label, `key` and `word` in one line.
void expect_error(const std::string& regions, const std::string& key, const std::string& word,
                  const std::string& base_dir = "") {
  try {
    parse_scene(kHead + regions, "bad.yaml", base_dir);
    ADD_FAILURE() << "no error for: " << regions;
  } catch (const SceneReadError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("bad.yaml: ", 0), 0u) << m;
    EXPECT_NE(m.find(key), std::string::npos) << m;
    EXPECT_NE(m.find(word), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

const std::string kSquare = "polygon: [[0,0],[20,0],[20,20],[0,20]]";

TEST(RegionReader, AValidRegionIsCut) {
  // 20 m square, joints every 5 m both ways: 16 blocks of 25 m^2, exactly.
  const Scene s = parse_scene(kHead + "regions: [{name: r, material: rock, " + kSquare +
                                  ", joint_sets: [{dip: 90}, {dip: 0}]}]\n",
                              "ok.yaml");
  EXPECT_EQ(s.blocks.size(), 16u);
}

TEST(RegionReader, NoShape) { EXPECT_NO_FATAL_FAILURE(expect_error("regions: [{name: r, material: rock}]\n", "regions[0]", "exactly one")); }

TEST(RegionReader, TwoShapes) {
  EXPECT_NO_FATAL_FAILURE(expect_error("regions: [{name: r, material: rock, " + kSquare + ", below: {surface: s.csv, base: 0}}]\n",
               "regions[0]", "exactly one"));
}

TEST(RegionReader, UnknownMaterial) {
  EXPECT_NO_FATAL_FAILURE(expect_error("regions: [{name: r, material: granite, " + kSquare + "}]\n", "regions[0].material", "granite"));
}

TEST(RegionReader, MisspeltJointKey) {
  EXPECT_NO_FATAL_FAILURE(expect_error("regions: [{name: r, material: rock, " + kSquare + ", joint_sets: [{dipp: 90}]}]\n",
               "regions[0].joint_sets[0].dipp", "unknown key"));
}

TEST(RegionReader, NegativeSpacing) {
  EXPECT_NO_FATAL_FAILURE(expect_error("regions: [{name: r, material: rock, " + kSquare + ", joint_sets: [{dip: 90, spacing: -2}]}]\n",
               "regions[0].joint_sets[0].spacing", "(0, 1e6] m"));
}

TEST(RegionReader, DipAndParallelTogether) {
  EXPECT_NO_FATAL_FAILURE(expect_error("regions: [{name: r, material: rock, " + kSquare +
                   ", joint_sets: [{dip: 90, parallel_to: base.csv}]}]\n",
               "regions[0].joint_sets[0]", "not both"));
}

TEST(RegionReader, SelfIntersectingOutline) {
  EXPECT_NO_FATAL_FAILURE(expect_error("regions: [{name: r, material: rock, polygon: [[0,0],[20,20],[20,0],[0,20]]}]\n", "regions[0]",
               "simple polygon"));
}

TEST(RegionReader, MissingCsv) {
  EXPECT_NO_FATAL_FAILURE(expect_error("regions: [{name: r, material: rock, below: {surface: nowhere.csv, base: 0}}]\n",
               "regions[0].below.surface", "cannot read"));
}

// Writes a CSV file into a scratch folder and returns the folder.
std::string scratch_csv(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "ddafit_region_reader";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir.string();
}

TEST(RegionReader, CsvWithXGoingBack) {
  const std::string dir = scratch_csv("back.csv", "x,y\n0,10\n5,11\n3,12\n");
  EXPECT_NO_FATAL_FAILURE(expect_error("regions: [{name: r, material: rock, below: {surface: back.csv, base: 0}}]\n",
               "regions[0].below.surface", "x must increase", dir));
}

TEST(RegionReader, BaseAboveTheSurface) {
  const std::string dir = scratch_csv("surface.csv", "x,y\n0,10\n5,11\n");
  EXPECT_NO_FATAL_FAILURE(expect_error("regions: [{name: r, material: rock, below: {surface: surface.csv, base: 10.5}}]\n",
               "regions[0].below.base", "below every point", dir));
}

TEST(RegionReader, JointsWithoutBlockSize) {
  try {
    parse_scene("time: {duration: 1, step: 0.01}\nmaterials: {rock: {density: 2500, young_modulus: 5e9, "
                "poisson_ratio: 0.25}}\nregions: [{name: r, material: rock, " + kSquare +
                    ", joint_sets: [{dip: 90}]}]\n",
                "bad.yaml");
    ADD_FAILURE() << "no error";
  } catch (const SceneReadError& e) {
    EXPECT_NE(std::string(e.what()).find("block_size"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ddafit::io
