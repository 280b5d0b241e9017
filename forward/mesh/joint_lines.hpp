// Joint lines cut into blocks, the way the DDA block cutter of Shi's codes does it (the "DC"
// step of the public codes, ntdda's src/blocks.c): every joint line is split where lines
// cross, dangling ends are dropped (edges with the same face on both sides: they close no
// block), and each bounded face left is a block. Used by `ddafit import` for the joint-line
// input of those codes; regions cut by joint sets are in region.hpp.
#pragma once

#include <string>
#include <vector>

#include "forward/geometry.hpp"

namespace ddafit {

struct JointLine {
  Vec2 a, b;
  int type = 1;  // the joint property of the DDA input, 1-based
  int line = 0;  // where it stands in its file (for messages)
};

struct JointCut {
  std::vector<std::vector<Vec2>> blocks;  // counter-clockwise outlines
  // Per pair of blocks sharing an edge: the joint type of that edge (the lowest where
  // joints of several types overlap).
  struct SharedEdge {
    int block_a, block_b, type;
  };
  std::vector<SharedEdge> shared;
  int dropped_dangling = 0;  // edges removed because they closed no block
};

// Cuts the lines. Sets `problem` (naming the file line) when a face has another inside it
// (a block inside a block), which ddafit cannot represent.
JointCut cut_joint_lines(const std::vector<JointLine>& lines, std::string& problem);

}  // namespace ddafit
