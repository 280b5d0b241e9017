#include "forward/step/find_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <unordered_map>

#include "forward/geometry.hpp"

namespace ddafit {
namespace {

// Vertices whose wedge dips more than about 9 degrees into the edge's block cannot
// enter through that edge (Shi's angle test; it removes false contacts at corners).
constexpr double kWedgeTolerance = 0.15;

// Deepest penetration, as a fraction of the search distance, of a vertex that lies beyond
// the end of an edge and still counts as touching it.
constexpr double kExtensionDepth = 0.1;

// Penetrations deeper than this fraction of the search distance are checked against
// block j's polygon (shallower ones include the exact touching of a tiled mass at t = 0).
constexpr double kInsideCheckDepth = 1e-3;

struct EdgeGrid {
  double cell = 1.0;
  std::vector<std::pair<std::uint64_t, int>> entries;  // (cell key, edge start vertex), sorted

  static std::uint64_t key(long ix, long iy) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ix)) << 32) |
           static_cast<std::uint32_t>(iy);
  }
  long index(double x) const { return static_cast<long>(std::floor(x / cell)); }
};

EdgeGrid build_edge_grid(const BlockSystem& s, double rho) {
  EdgeGrid grid;
  // Cell size: the mean edge length of free blocks, at least 2 rho, so that a typical
  // edge covers a few cells and a vertex looks in exactly one.
  double total = 0.0;
  int count = 0;
  for (const Block& b : s.blocks) {
    if (b.fixed) continue;
    for (int v = b.first_vertex; v < b.first_vertex + b.vertex_count; ++v) {
      total += (s.vertices[s.next_vertex(v)] - s.vertices[v]).norm();
      ++count;
    }
  }
  grid.cell = std::max(count ? total / count : 1.0, 2.0 * rho);
  for (int v = 0; v < static_cast<int>(s.vertices.size()); ++v) {
    const Vec2& a = s.vertices[v];
    const Vec2& b = s.vertices[s.next_vertex(v)];
    const long x0 = grid.index(std::min(a.x(), b.x()) - rho), x1 = grid.index(std::max(a.x(), b.x()) + rho);
    const long y0 = grid.index(std::min(a.y(), b.y()) - rho), y1 = grid.index(std::max(a.y(), b.y()) + rho);
    // Long edges only register in the cells their inflated segment passes through.
    const Vec2 d = b - a;
    const double len = d.norm();
    const Vec2 n = len > 0 ? Vec2(-d.y(), d.x()) / len : Vec2(0, 0);
    const double reach = rho + grid.cell * M_SQRT1_2;
    for (long ix = x0; ix <= x1; ++ix)
      for (long iy = y0; iy <= y1; ++iy) {
        const Vec2 centre((ix + 0.5) * grid.cell, (iy + 0.5) * grid.cell);
        if (std::abs((centre - a).dot(n)) > reach) continue;
        grid.entries.emplace_back(EdgeGrid::key(ix, iy), v);
      }
  }
  std::sort(grid.entries.begin(), grid.entries.end());
  return grid;
}

// d_c of seed Eq. 2: a fraction of the overriding block's length along the edge.
double critical_distance(const BlockSystem& s, int interface, int block_i, const Vec2& t) {
  const double ratio = interface >= 0 ? s.interfaces[interface].critical_distance_ratio : 0.01;
  return ratio * block_length_along(s, block_i, t);
}

// l_c: cohesion and tension act on the halves of the vertex's two edges that lie along
// the contact (two corners of a block resting on a face share its whole length).
double bond_length(const BlockSystem& s, int v, const Vec2& t) {
  const Vec2& p = s.vertices[v];
  return 0.5 * (std::abs((s.vertices[s.next_vertex(v)] - p).dot(t)) +
                std::abs((s.vertices[s.previous_vertex(v)] - p).dot(t)));
}

struct Candidate {
  int edge = -1;
  int block_j = -1;
  double gap = 0.0;
  double ratio = 0.0;
  bool kept = false;  // the edge this vertex touched in the previous step, still under it
};

// Which of two edges of one block a vertex touches. Shi's entrance rule asks for the
// edge it entered through; the edge it touched in the previous step, while the approach
// was still unambiguous, is that edge for as long as the vertex projects onto it. Only
// new contacts fall back on the least penetration, which misreads a corner that has gone
// deep near a corner of the other block.
bool better(const Candidate& a, const Candidate& b) {
  if (a.kept != b.kept) return a.kept;
  return a.gap > b.gap;
}

}  // namespace

const char* to_string(ContactState state) {
  switch (state) {
    case ContactState::Open: return "open";
    case ContactState::Sliding: return "sliding";
    case ContactState::Locked: return "locked";
  }
  return "?";
}

std::string find_contacts(const BlockSystem& s, const ContactSearch& search,
                          std::vector<Contact>& contacts) {
  const double rho = search.search_distance;
  std::unordered_map<std::uint64_t, int> previous;
  previous.reserve(contacts.size());
  for (int k = 0; k < static_cast<int>(contacts.size()); ++k)
    previous.emplace(contact_key(contacts[k].vertex, contacts[k].block_j), k);

  const EdgeGrid grid = build_edge_grid(s, rho);
  std::vector<Contact> found;
  found.reserve(contacts.size() + 16);
  std::vector<Candidate> best;  // best edge per touched block for the current vertex
  std::string problem;

  for (int v = 0; v < static_cast<int>(s.vertices.size()); ++v) {
    const int bi = s.vertex_block[v];
    const Vec2& p1 = s.vertices[v];
    const Vec2 wedge_a = (s.vertices[s.next_vertex(v)] - p1).normalized();
    const Vec2 wedge_b = (s.vertices[s.previous_vertex(v)] - p1).normalized();
    const auto key = EdgeGrid::key(grid.index(p1.x()), grid.index(p1.y()));
    auto it = std::lower_bound(grid.entries.begin(), grid.entries.end(), std::make_pair(key, -1));
    best.clear();
    for (; it != grid.entries.end() && it->first == key; ++it) {
      const int e = it->second;
      const int bj = s.vertex_block[e];
      if (bj == bi || (s.blocks[bi].fixed && s.blocks[bj].fixed)) continue;
      const Vec2& p2 = s.vertices[e];
      const Vec2& p3 = s.vertices[s.next_vertex(e)];
      const Vec2 d = p3 - p2;
      const double l = d.norm();
      const Vec2 t = d / l;
      const Vec2 outward(t.y(), -t.x());  // block j lies to the left of P2->P3
      const double gap = (p1 - p2).dot(outward);
      if (gap >= rho || gap <= -rho) continue;
      const double ratio = (p1 - p2).dot(t) / l;
      const double extension = std::min(rho, 0.25 * l) / l;  // catches vertex-vertex approach
      if (ratio < -extension || ratio > 1.0 + extension) continue;
      // Beyond an end of the edge (the vertex-vertex zone) the vertex only touches this
      // edge if it is also inside the neighbouring edge at that end; otherwise it lies
      // beside the block, and the extended line would report a false penetration (a
      // corner sliding past a corner read 0.4 m "deep" and wrecked the Vajont run).
      if (ratio < 0.0 || ratio > 1.0) {
        // Beyond the end, the zone only catches corners approaching corners; a vertex
        // already deep there is inside the corner of block j and belongs to the
        // neighbouring edge. Measured from this edge's line its depth is unbounded (a
        // spring at 0.6 m threw Vajont blocks at 150 m/s).
        if (gap < -kExtensionDepth * rho) continue;
        const int corner = ratio > 1.0 ? s.next_vertex(e) : e;
        const int a = ratio > 1.0 ? corner : s.previous_vertex(corner);
        const Vec2 da = s.vertices[s.next_vertex(a)] - s.vertices[a];
        const Vec2 neighbour_out = Vec2(da.y(), -da.x()).normalized();
        if ((p1 - s.vertices[corner]).dot(neighbour_out) > 0.0) continue;
        // Beyond a reflex corner of block j (a valley floor meeting the opposite wall) the
        // extended line runs inside the block: a corner sliding along the floor into the
        // wall read 2 cm "deep" on the floor's extension while 0.47 m inside the wall.
        // Where the vertex projects onto the neighbouring edge, that edge measures it.
        const Vec2 db = s.vertices[s.next_vertex(s.next_vertex(a))] - s.vertices[s.next_vertex(a)];
        if (da.x() * db.y() - da.y() * db.x() < 0.0) {
          const double along = (p1 - s.vertices[a]).dot(da) / da.squaredNorm();
          if (along >= 0.0 && along <= 1.0) continue;
        }
      }
      // A vertex deeper than a hair behind the edge's line must be inside block j: near
      // a corner of j the line of one edge passes under a vertex that is beside the
      // block, outside its other edge (a Vajont corner read 0.6 m deep that way).
      if (gap < -kInsideCheckDepth * rho) {
        const Block& block_j = s.blocks[bj];
        if (!point_in_polygon(p1, std::span<const Vec2>(s.vertices).subspan(block_j.first_vertex,
                                                                             block_j.vertex_count)))
          continue;
      }
      if (wedge_a.dot(outward) < -kWedgeTolerance || wedge_b.dot(outward) < -kWedgeTolerance) continue;
      // One contact per (vertex, block): keep the edge with the least penetration,
      // which is the edge the vertex entered through (Shi's entrance rule, simplified).
      Candidate candidate{e, bj, gap, ratio, false};
      if (ratio >= 0.0 && ratio <= 1.0) {
        const auto old = previous.find(contact_key(v, bj));
        candidate.kept = old != previous.end() && contacts[old->second].edge == e &&
                         contacts[old->second].state != ContactState::Open;
      }
      auto slot = std::find_if(best.begin(), best.end(), [&](const Candidate& c) { return c.block_j == bj; });
      if (slot == best.end()) {
        best.push_back(candidate);
      } else if (better(candidate, *slot)) {
        *slot = candidate;
      }
    }
    for (const Candidate& c : best) {
      Contact contact;
      const auto old = previous.find(contact_key(v, c.block_j));
      const Vec2 t = (s.vertices[s.next_vertex(c.edge)] - s.vertices[c.edge]).normalized();
      if (old != previous.end()) {
        contact = contacts[old->second];
        if (contact.edge != c.edge) {
          // The vertex moved onto a neighbouring edge of the same block: it keeps its
          // accumulated slip (seed 2.2), while the reference point and the lengths that
          // depend on the edge's direction are taken anew.
          contact.reference_ratio = c.ratio;
          contact.critical_distance = critical_distance(s, contact.interface, bi, t);
          contact.bond_length = bond_length(s, v, t);
        }
      } else {
        contact.vertex = v;
        contact.block_i = bi;
        contact.block_j = c.block_j;
        contact.interface = s.interface_between(bi, c.block_j);
        if (contact.interface < 0 && problem.empty()) {
          problem = "blocks '" + s.block_names[bi] + "' and '" + s.block_names[c.block_j] + "' (groups '" +
                    s.group_names[s.blocks[bi].group] + "', '" + s.group_names[s.blocks[c.block_j].group] +
                    "') touch but no interface is defined for that pair: add a contacts entry or default_interface";
        }
        contact.state = c.gap <= 0.0 ? ContactState::Locked : ContactState::Open;
        contact.reference_ratio = c.ratio;
        contact.critical_distance = critical_distance(s, contact.interface, bi, t);
        contact.bond_length = bond_length(s, v, t);
        // A bond only exists where the interface has strength to hold.
        const bool strong = contact.interface >= 0 && (s.interfaces[contact.interface].cohesion > 0.0 ||
                                                        s.interfaces[contact.interface].tensile_strength > 0.0);
        contact.bonded = search.first_step && c.gap <= 0.0 && strong;
      }
      contact.edge = c.edge;
      contact.start_gap = c.gap;
      contact.step_state = contact.state;
      contact.state_changes = 0;
      found.push_back(contact);
    }
  }
  contacts.swap(found);
  return problem;
}

}  // namespace ddafit
