// The extra sweeps in list order split into groups that share no moving block
// (forward/substep/list_groups.hpp): the split itself on random lists, and the promise that
// the groups shared between two threads give the numbers of one thread to the bit on a scene
// whose deep and light-block lists hold many groups (Vajont section I).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "forward/io/scene_reader.hpp"
#include "forward/simulation.hpp"
#include "forward/substep/list_groups.hpp"
#include "tests/threads_agree.hpp"

namespace ddafit {
namespace {

// Moving blocks joined through the list's manifolds (breadth-first, the test's own reading).
std::vector<int> components(const std::vector<int>& list, const std::vector<std::array<int, 2>>& pairs,
                            const std::vector<BlockMass>& masses) {
  const int n = static_cast<int>(masses.size());
  std::vector<int> label(n, -1);
  for (int start = 0; start < n; ++start) {
    if (label[start] >= 0 || !masses[start].moves) continue;
    std::vector<int> todo{start};
    label[start] = start;
    while (!todo.empty()) {
      const int b = todo.back();
      todo.pop_back();
      for (const int k : list) {
        const auto [x, y] = pairs[k];
        if (!masses[x].moves || !masses[y].moves || (x != b && y != b)) continue;
        const int other = x == b ? y : x;
        if (label[other] < 0) label[other] = start, todo.push_back(other);
      }
    }
  }
  return label;
}

// Random lists over random pairs of 40 blocks, a fifth of them fixed: every manifold of the list
// is in exactly one group, each group keeps the list's order, a group is one set of moving blocks
// joined by its manifolds (no fewer groups, no more), groups are numbered by their first
// manifold in the list.
TEST(ListGroups, SplitTheListByTheMovingBlocksItsManifoldsShare) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 300; ++trial) {
    const int blocks = 40;
    std::vector<BlockMass> masses(blocks);
    for (BlockMass& m : masses) m.moves = random() % 5 != 0;
    std::vector<std::array<int, 2>> pairs;
    for (int k = 0; k < 60; ++k) {
      int a = static_cast<int>(random() % blocks), b = static_cast<int>(random() % blocks);
      if (a == b || (!masses[a].moves && !masses[b].moves)) continue;
      pairs.push_back({a, b});
    }
    std::vector<int> list;
    for (int k = 0; k < static_cast<int>(pairs.size()); ++k)
      if (random() % 3 != 0) list.push_back(k);
    std::shuffle(list.begin(), list.end(), random);
    ListGroups groups;
    group_by_blocks(list, pairs, masses, groups);

    ASSERT_EQ(groups.ids.size(), list.size()) << "trial " << trial;
    std::vector<int> position(pairs.size(), -1);
    for (size_t i = 0; i < list.size(); ++i) position[list[i]] = static_cast<int>(i);
    const std::vector<int> label = components(list, pairs, masses);
    const auto label_of = [&](int k) { return masses[pairs[k][0]].moves ? label[pairs[k][0]] : label[pairs[k][1]]; };
    std::vector<int> group_of_label(blocks, -1);
    const int count = static_cast<int>(groups.first.size()) - 1;
    int last_first = -1;
    for (int g = 0; g < count; ++g) {
      ASSERT_LT(groups.first[g], groups.first[g + 1]) << "trial " << trial << ": empty group " << g;
      const int lead = groups.ids[groups.first[g]];
      EXPECT_GT(position[lead], last_first) << "trial " << trial << ": groups out of order";
      last_first = position[lead];
      for (int i = groups.first[g]; i < groups.first[g + 1]; ++i) {
        const int k = groups.ids[i];
        if (i > groups.first[g]) {
          EXPECT_LT(position[groups.ids[i - 1]], position[k]) << "trial " << trial;
        }
        const int l = label_of(k);
        // One group per set of joined blocks, and one set per group.
        if (group_of_label[l] < 0) group_of_label[l] = g;
        EXPECT_EQ(group_of_label[l], g) << "trial " << trial << ": manifold " << k;
        EXPECT_EQ(label_of(lead), l) << "trial " << trial << ": manifold " << k;
      }
    }
  }
}

// Vajont section I degraded, cut at 16 m (the finest block of `ddafit advise` on Vajont): its
// slivers beside blocks 30 times heavier and its deep neighbourhoods lie scattered through the
// slide, so the extra sweeps run in several groups on both threads (about 65 manifolds in 6
// groups for the light blocks' 8 sweeps, from the first step; 28 in 2 for the deep ones' 16,
// once the slide runs: a temporary count). Four seconds of the slide on one and on two threads:
// the same history to the bit (as tests/test_substep_threads.cpp asks of the coloured sweeps).
// At 34.3 m the lists are too short to be shared.
TEST(ListGroups, VajontSectionIOnOneAndTwoThreadsAgreesBitForBit) {
  const io::Overrides overrides = {{"mesh.block_size", "16.0"}, {"time.duration", "4"},
                                   {"time.integrator", "substep"}};
  const Scene scene = io::read_scene(std::string(DDAFIT_CASES_DIR) + "/vajont/degraded.yaml", overrides);
  expect_same_on_one_and_two_threads(scene, "Vajont section I at 16 m");
}

}  // namespace
}  // namespace ddafit
