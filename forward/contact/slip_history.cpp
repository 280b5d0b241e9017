#include "forward/contact/slip_history.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "forward/contact/contact_law.hpp"
#include "forward/parallel.hpp"

namespace ddafit {
namespace {

// tan(phi) of a history from the law, unless no further slip can change it.
void refresh_friction(const BlockSystem& s, SlipHistory& h) {
  h.changed = !h.settled;
  if (h.settled) return;
  const Interface& face = s.interfaces[h.interface];
  h.friction = friction_coefficient(face, h);
  h.settled = friction_law_settled(face, {h.slip, h.slip_rate, h.critical_distance});
}

// Sorts the histories by key (the next step finds a face's history by binary search) and
// points the manifolds at their new places.
// The keys are sorted beside their places (one key per face: no ties, so the order is the
// same), not read through the 136-byte histories at every comparison, and the histories are
// moved into a reserved list rather than one first filled with empty histories. The sort follows
// nearly every step's assignment (histories are appended in manifold order); on Vajont section
// VII's first 10 s the assignment took 1.30 s before and 1.22 s after, on one thread, most of it
// in reading and moving the histories themselves.
void sort_histories(ContactSet& contacts) {
  std::vector<SlipHistory>& h = contacts.histories;
  std::vector<std::pair<std::uint64_t, int>> order(h.size());
  for (size_t k = 0; k < h.size(); ++k) order[k] = {h[k].key, static_cast<int>(k)};
  std::sort(order.begin(), order.end());
  std::vector<int> place(h.size());
  std::vector<SlipHistory> sorted;
  sorted.reserve(h.size());
  for (size_t k = 0; k < order.size(); ++k) {
    place[order[k].second] = static_cast<int>(k);
    sorted.push_back(std::move(h[order[k].second]));
  }
  h.swap(sorted);
  for (ContactManifold& m : contacts.manifolds)
    if (m.history >= 0) m.history = place[m.history];
}

// Thermal pressurization (laws/thermal_pressurization.hpp): the face's effective normal
// stress over the (sub)step, the heat of its slip at the friction it slid with, and the
// band's excess pore pressure after it.
void heat_shear_band(const BlockSystem& s, const ContactSet& contacts, SlipHistory& h, double duration) {
  const Interface& face = s.interfaces[h.interface];
  h.normal_stress = h.face_length > 0.0 ? h.normal_load / h.face_length : 0.0;
  const double heat = h.friction * std::max(h.normal_stress, 0.0) * h.increment;
  h.excess_pressure = laws::advance_column(face, contacts.shear_bands[h.interface], heat, duration, h.band_column);
  h.normal_load = 0.0;
}

}  // namespace

void assign_histories(const BlockSystem& s, ContactSet& contacts, std::vector<SlipHistory>& previous) {
  previous.swap(contacts.histories);
  std::vector<SlipHistory>& histories = contacts.histories;
  histories.clear();
  std::vector<int> carried(previous.size(), -1);     // previous history -> this step's
  std::vector<std::pair<std::uint64_t, int>> fresh;  // faces new in this step -> this step's
  bool in_order = true;
  for (ContactManifold& m : contacts.manifolds) {
    if (m.interface < 0) {
      m.history = -1;
      continue;
    }
    // m.history is the last step's history of the same pair and face, if collide() found
    // one; otherwise the face may have touched another block (a joint crossed).
    int old = m.history;
    if (old < 0) {
      const auto it = std::lower_bound(previous.begin(), previous.end(), m.face_key,
                                       [](const SlipHistory& h, std::uint64_t key) { return h.key < key; });
      if (it != previous.end() && it->key == m.face_key) old = static_cast<int>(it - previous.begin());
    }
    if (old >= 0) {
      if (carried[old] < 0) {
        carried[old] = static_cast<int>(histories.size());
        histories.push_back(std::move(previous[old]));  // its key stays for the searches below
        histories.back().increment = 0.0;
        histories.back().normal_load = 0.0;
      }
      m.history = carried[old];
    } else {
      const auto same = std::find_if(fresh.begin(), fresh.end(), [&](const auto& f) { return f.first == m.face_key; });
      if (same != fresh.end()) {
        m.history = same->second;
      } else {
        SlipHistory h;
        h.key = m.face_key;
        h.interface = m.interface;
        h.face_length = block_length_along(s, m.overriding_block, m.tangent);
        h.critical_distance = critical_distance(s.interfaces[m.interface], h.face_length);
        if (m.interface < static_cast<int>(contacts.shear_bands.size()) && !contacts.shear_bands[m.interface].empty())
          laws::start_column(contacts.shear_bands[m.interface], h.band_column);
        refresh_friction(s, h);
        h.changed = true;
        m.history = static_cast<int>(histories.size());
        fresh.emplace_back(m.face_key, m.history);
        histories.push_back(h);
      }
    }
    if (histories.size() > 1 && m.history == static_cast<int>(histories.size()) - 1 &&
        histories[m.history - 1].key > histories[m.history].key)
      in_order = false;
  }
  if (!in_order) sort_histories(contacts);
  for (ContactManifold& m : contacts.manifolds)
    if (m.history >= 0) m.friction = histories[m.history].friction;
}

void prepare_shear_bands(const BlockSystem& s, double duration, ContactSet& contacts) {
  contacts.shear_bands.clear();
  for (const Interface& f : s.interfaces)
    contacts.shear_bands.push_back(f.law == FrictionLaw::ThermalPressurization ? laws::make_diffusion_grid(f, duration)
                                                                                : laws::DiffusionGrid{});
}

void reset_histories(const BlockSystem& s, ContactSet& contacts) {
  for (SlipHistory& h : contacts.histories) {
    h.slip = h.last_slip = h.increment = h.slip_rate = h.previous_slip_rate = 0.0;
    h.normal_load = h.normal_stress = h.excess_pressure = 0.0;
    if (!h.band_column.empty()) laws::start_column(contacts.shear_bands[h.interface], h.band_column);
    h.settled = false;
    refresh_friction(s, h);
  }
  for (ContactManifold& m : contacts.manifolds)
    if (m.history >= 0) m.friction = contacts.histories[m.history].friction;
}

void advance_histories(const BlockSystem& s, ContactSet& contacts, double duration) {
  for (const ContactManifold& m : contacts.manifolds)
    if (m.history >= 0)
      for (int q = 0; q < m.point_count; ++q) {
        SlipHistory& h = contacts.histories[m.history];
        gather_slip(h, m.points[q].slip);
        if (!h.band_column.empty()) h.normal_load += m.points[q].normal_load;
      }
  // Each face's law on its own: parallel, and the same numbers on any thread count.
  std::vector<SlipHistory>& histories = contacts.histories;
  const long n = static_cast<long>(histories.size());
  bool any = false;
#pragma omp parallel for schedule(static) reduction(|| : any) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    SlipHistory& h = histories[k];
    if (!h.band_column.empty()) heat_shear_band(s, contacts, h, duration);
    add_slip(h, duration);
    refresh_friction(s, h);
    any = any || h.changed;
  }
  if (!any) return;
  std::vector<ContactManifold>& manifolds = contacts.manifolds;
  const long count = static_cast<long>(manifolds.size());
#pragma omp parallel for schedule(static) if (count >= kParallelMinimum)
  for (long k = 0; k < count; ++k) {
    ContactManifold& m = manifolds[k];
    if (m.history >= 0 && histories[m.history].changed) m.friction = histories[m.history].friction;
  }
}

}  // namespace ddafit
