// cases/verification/*.yaml are the analytic scenes for users to open; verify/cases.cpp
// defines the same scenes for the suite. They must not drift apart.
#include <gtest/gtest.h>

#include "forward/io/scene_reader.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

void expect_same_scene(const Scene& file, const Scene& code) {
  EXPECT_EQ(file.gravity, code.gravity);
  EXPECT_EQ(file.duration, code.duration);
  EXPECT_EQ(file.max_step, code.max_step);
  EXPECT_EQ(file.output_interval, code.output_interval);
  ASSERT_EQ(file.blocks.size(), code.blocks.size());
  for (size_t b = 0; b < code.blocks.size(); ++b) {
    EXPECT_EQ(file.blocks[b].name, code.blocks[b].name);
    EXPECT_EQ(file.blocks[b].fixed, code.blocks[b].fixed);
    EXPECT_EQ(file.blocks[b].velocity, code.blocks[b].velocity);
    EXPECT_EQ(file.blocks[b].polygon, code.blocks[b].polygon);  // the writer round-trips exactly
  }
  ASSERT_EQ(file.interfaces.size(), code.interfaces.size());
  for (size_t k = 0; k < code.interfaces.size(); ++k) {
    EXPECT_EQ(file.interfaces[k].friction_angle, code.interfaces[k].friction_angle);
    EXPECT_EQ(file.interfaces[k].roughness_angle, code.interfaces[k].roughness_angle);
    EXPECT_EQ(file.interfaces[k].critical_distance_ratio, code.interfaces[k].critical_distance_ratio);
  }
  ASSERT_EQ(file.measure.size(), code.measure.size());
  for (size_t k = 0; k < code.measure.size(); ++k) EXPECT_EQ(file.measure[k].at, code.measure[k].at);
}

const std::string kDir = std::string(DDAFIT_CASES_DIR) + "/verification/";

TEST(CasesMatchCode, InclineConstantFriction) {
  EXPECT_NO_FATAL_FAILURE(expect_same_scene(io::read_scene(kDir + "incline_phi25.yaml"), verification::incline_scene({})));
}

TEST(CasesMatchCode, InclineDegradation) {
  verification::InclineSetup setup;
  setup.roughness_angle = 5.0;
  EXPECT_NO_FATAL_FAILURE(expect_same_scene(io::read_scene(kDir + "incline_i5.yaml"), verification::incline_scene(setup)));
}

TEST(CasesMatchCode, Stack) { EXPECT_NO_FATAL_FAILURE(expect_same_scene(io::read_scene(kDir + "stack.yaml"), verification::stack_scene())); }

TEST(CasesMatchCode, RockingBlock) {
  EXPECT_NO_FATAL_FAILURE(expect_same_scene(io::read_scene(kDir + "rocking.yaml"), verification::rocking_block_scene()));
}

TEST(CasesMatchCode, Arch) {
  EXPECT_NO_FATAL_FAILURE(expect_same_scene(io::read_scene(kDir + "arch.yaml"), verification::arch_scene(0.15)));
}

TEST(CasesMatchCode, Collision) {
  EXPECT_NO_FATAL_FAILURE(expect_same_scene(io::read_scene(kDir + "collision.yaml"), verification::collision_scene()));
}

}  // namespace
}  // namespace ddafit
