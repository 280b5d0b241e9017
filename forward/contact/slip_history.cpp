#include "forward/contact/slip_history.hpp"

#include <algorithm>

#include "forward/contact/contact_law.hpp"
#include "forward/parallel.hpp"

namespace ddafit {
namespace {

// tan(phi) of every manifold from its face's history.
void update_friction(const BlockSystem& s, ContactSet& contacts) {
  const long n = static_cast<long>(contacts.manifolds.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    ContactManifold& m = contacts.manifolds[k];
    if (m.history >= 0) m.friction = friction_coefficient(s.interfaces[m.interface], contacts.histories[m.history]);
  }
}

}  // namespace

void assign_histories(const BlockSystem& s, ContactSet& contacts) {
  std::vector<ContactManifold>& manifolds = contacts.manifolds;
  std::vector<std::uint64_t> keys;
  keys.reserve(manifolds.size());
  for (const ContactManifold& m : manifolds)
    if (m.interface >= 0) keys.push_back(m.face_key);
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());

  const std::vector<SlipHistory> previous = std::move(contacts.histories);
  std::vector<SlipHistory>& histories = contacts.histories;
  histories.assign(keys.size(), SlipHistory{});
  for (size_t k = 0; k < keys.size(); ++k) {
    const auto old = std::lower_bound(previous.begin(), previous.end(), keys[k],
                                      [](const SlipHistory& h, std::uint64_t key) { return h.key < key; });
    if (old != previous.end() && old->key == keys[k]) histories[k] = *old;
    histories[k].key = keys[k];
    histories[k].increment = 0.0;
  }
  for (ContactManifold& m : manifolds) {
    if (m.interface < 0) continue;
    m.history = static_cast<int>(std::lower_bound(keys.begin(), keys.end(), m.face_key) - keys.begin());
    SlipHistory& h = histories[m.history];
    if (h.critical_distance == 0.0)
      h.critical_distance = critical_distance(s.interfaces[m.interface], block_length_along(s, m.overriding_block, m.tangent));
  }
  update_friction(s, contacts);
}

void advance_histories(const BlockSystem& s, ContactSet& contacts) {
  for (const ContactManifold& m : contacts.manifolds)
    if (m.history >= 0)
      for (int q = 0; q < m.point_count; ++q) gather_slip(contacts.histories[m.history], m.points[q].slip);
  for (SlipHistory& h : contacts.histories) add_slip(h);
  update_friction(s, contacts);
}

}  // namespace ddafit
