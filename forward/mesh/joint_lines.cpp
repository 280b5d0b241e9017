#include "forward/mesh/joint_lines.hpp"

#include <algorithm>
#include <map>

#include "forward/mesh/arrangement.hpp"

namespace ddafit {

using cut::Arrangement;

JointCut cut_joint_lines(const std::vector<JointLine>& lines, std::string& problem) {
  JointCut out;
  std::vector<cut::Segment> segments;
  for (const JointLine& j : lines)
    if ((j.b - j.a).norm() > 0.0)
      segments.emplace_back(cut::Point(j.a.x(), j.a.y()), cut::Point(j.b.x(), j.b.y()));
  Arrangement arr;
  CGAL::insert(arr, segments.begin(), segments.end());
  // Dangling ends: an edge with one face on both sides bounds nothing. Removing one can
  // leave another dangling, so repeat until none is left.
  for (;;) {
    std::vector<Arrangement::Halfedge_handle> dangling;
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e)
      if (e->face() == e->twin()->face()) dangling.push_back(e);
    if (dangling.empty()) break;
    for (const auto& e : dangling) arr.remove_edge(e);
    out.dropped_dangling += static_cast<int>(dangling.size());
  }
  std::map<const void*, int> block_of;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->is_unbounded()) continue;
    if (f->number_of_inner_ccbs() > 0) {
      const std::vector<Vec2> outline = cut::face_polygon(f);
      problem = "a block (around x = " + std::to_string(outline.front().x()) + ", y = " +
                std::to_string(outline.front().y()) + ") has another block inside it; ddafit's blocks have no holes";
      return out;
    }
    block_of[&*f] = static_cast<int>(out.blocks.size());
    out.blocks.push_back(cut::face_polygon(f));
  }
  // The joint type of each shared edge: the input line its midpoint lies on.
  const auto type_at = [&](const Vec2& p) {
    int type = -1;
    for (const JointLine& j : lines) {
      const Vec2 d = j.b - j.a;
      const double len2 = d.squaredNorm();
      if (len2 == 0.0) continue;
      const double s = std::clamp((p - j.a).dot(d) / len2, 0.0, 1.0);
      if ((j.a + s * d - p).norm() <= 1e-9 * (1.0 + std::sqrt(len2)) && (type < 0 || j.type < type)) type = j.type;
    }
    return type < 0 ? 1 : type;
  };
  std::map<std::pair<int, int>, int> pair_type;
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const auto fa = block_of.find(&*e->face()), fb = block_of.find(&*e->twin()->face());
    if (fa == block_of.end() || fb == block_of.end()) continue;
    const Vec2 mid = 0.5 * (cut::to_vec(e->source()->point()) + cut::to_vec(e->target()->point()));
    const std::pair<int, int> key = std::minmax(fa->second, fb->second);
    const int type = type_at(mid);
    const auto [it, fresh] = pair_type.emplace(key, type);
    if (!fresh) it->second = std::min(it->second, type);
  }
  for (const auto& [key, type] : pair_type) out.shared.push_back({key.first, key.second, type});
  return out;
}

}  // namespace ddafit
