#include "forward/contact/slip_history.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <omp.h>

#include "forward/contact/contact_law.hpp"
#include "forward/kinematics.hpp"
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

// A new history for the face of manifold m, with no slip.
SlipHistory fresh_history(const BlockSystem& s, const ContactSet& contacts, const ContactManifold& m) {
  SlipHistory h;
  h.key = m.face_key;
  h.interface = m.interface;
  h.face_length = block_length_along(s, m.overriding_block, m.tangent);
  h.critical_distance = critical_distance(s.interfaces[m.interface], h.face_length);
  if (m.interface < static_cast<int>(contacts.shear_bands.size()) && !contacts.shear_bands[m.interface].empty())
    laws::start_column(contacts.shear_bands[m.interface], h.band_column);
  refresh_friction(s, h);
  h.changed = true;
  return h;
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

// Per face (history), the largest of value(m, q) >= 0 over the points of its manifolds, 0 for a
// face with none; value may return 0 for a point that does not count. A largest value does not
// depend on the order it is gathered in: each thread gathers its contiguous share of the
// manifolds into its own copy of the faces, and the copies are merged face by face, so the
// faces' cache lines are never shared between threads (gathered straight into the histories
// with a compare-and-swap, tried 2026-11-29, the two threads fought over them and the main
// thread's share did not fall). It ran on one thread, reading every 576-byte manifold each
// substep while the other thread waited.
template <class Value>
void largest_per_face(const std::vector<ContactManifold>& manifolds, long faces, Value&& value,
                      std::vector<double>& out) {
  const long n = static_cast<long>(manifolds.size());
  const int most = n >= kParallelMinimum ? omp_get_max_threads() : 1;
  std::vector<double> largest(static_cast<size_t>(most * faces), 0.0);
  out.assign(static_cast<size_t>(faces), 0.0);
#pragma omp parallel num_threads(most) if (most > 1)
  {
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
    double* mine = largest.data() + t * faces;
    const ThreadShare share = thread_share(n, t, threads);
    for (long k = share.first; k < share.last; ++k) {
      const ContactManifold& m = manifolds[k];
      if (m.history >= 0)
        for (int q = 0; q < m.point_count; ++q) mine[m.history] = std::max(mine[m.history], value(m, q));
    }
#pragma omp barrier
#pragma omp for schedule(static)
    for (long f = 0; f < faces; ++f)
      for (int u = 0; u < threads; ++u) out[f] = std::max(out[f], largest[u * faces + f]);
  }
}

}  // namespace

// In four passes, so that the 136-byte histories move once, in parallel, straight to their
// sorted places: (1) each manifold's history of the last step, by key where collide() found
// none (parallel); (2) in manifold order, the slot of each face in use, a carried history's
// at its first manifold and a new face's at the first manifold with its key (integers only);
// (3) the slots' places in key order (one key per face: no ties); (4) each history moved or
// made in its place (parallel). The same histories, in the same order, as appending them in
// manifold order and sorting them after, which took 1.2 s of Vajont section VII's first 10 s
// on one thread, most of it moving the histories twice.
void assign_histories(const BlockSystem& s, ContactSet& contacts, std::vector<SlipHistory>& previous) {
  previous.swap(contacts.histories);
  std::vector<SlipHistory>& histories = contacts.histories;
  std::vector<ContactManifold>& manifolds = contacts.manifolds;
  const long n = static_cast<long>(manifolds.size());
  // Per manifold, what pass 2 reads and writes (its face's key, its interface, its history, then
  // its slot), in 16 bytes rather than a 576-byte manifold: pass 2 runs on one thread.
  struct FaceOf {
    std::uint64_t key;
    int interface;
    int history;
  };
  std::vector<FaceOf> face(static_cast<size_t>(n));
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    const ContactManifold& m = manifolds[k];
    face[k] = {m.face_key, m.interface, m.history};
    // m.history is the last step's history of the same pair and face, if collide() found
    // one; otherwise the face may have touched another block (a joint crossed).
    if (m.interface < 0 || m.history >= 0) continue;
    const auto it = std::lower_bound(previous.begin(), previous.end(), m.face_key,
                                     [](const SlipHistory& h, std::uint64_t key) { return h.key < key; });
    if (it != previous.end() && it->key == m.face_key) face[k].history = static_cast<int>(it - previous.begin());
  }
  std::vector<int> carried(previous.size(), -1);     // previous history -> slot
  std::vector<std::pair<std::uint64_t, int>> fresh;  // faces new in this step -> slot
  std::vector<int> source;                           // per slot: its previous history, or -1 - its manifold
  std::vector<std::pair<std::uint64_t, int>> order;  // per slot: (key, slot)
  bool in_order = true;
  const auto add_slot = [&](std::uint64_t key, int from) {
    if (!order.empty() && order.back().first > key) in_order = false;
    order.emplace_back(key, static_cast<int>(source.size()));
    source.push_back(from);
    return static_cast<int>(source.size()) - 1;
  };
  for (long k = 0; k < n; ++k) {
    FaceOf& f = face[k];  // its history becomes its slot
    if (f.interface < 0) {
      f.history = -1;
    } else if (const int old = f.history; old >= 0) {
      if (carried[old] < 0) carried[old] = add_slot(previous[old].key, old);
      f.history = carried[old];
    } else {
      const auto same = std::find_if(fresh.begin(), fresh.end(), [&](const auto& e) { return e.first == f.key; });
      if (same != fresh.end()) {
        f.history = same->second;
      } else {
        f.history = add_slot(f.key, -1 - static_cast<int>(k));
        fresh.emplace_back(f.key, f.history);
      }
    }
  }
  if (!in_order) std::sort(order.begin(), order.end());
  const long slots = static_cast<long>(source.size());
  std::vector<int> place(slots);
  for (long i = 0; i < slots; ++i) place[order[i].second] = static_cast<int>(i);
  histories.resize(slots);  // every place is assigned below
#pragma omp parallel for schedule(static) if (slots >= kParallelMinimum)
  for (long i = 0; i < slots; ++i) {
    const int slot = order[i].second;
    SlipHistory& h = histories[i];
    if (source[slot] >= 0) {
      h = std::move(previous[source[slot]]);
      h.increment = 0.0;
      h.normal_load = 0.0;
    } else {
      h = fresh_history(s, contacts, manifolds[-1 - source[slot]]);
    }
  }
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    ContactManifold& m = manifolds[k];
    const int slot = face[k].history;
    m.history = slot < 0 ? -1 : place[slot];
    if (slot >= 0) m.friction = histories[m.history].friction;
  }
}

void predict_first_slip(const BlockSystem& s, ContactSet& contacts, double step) {
  if (step <= 0.0) return;
  std::vector<SlipHistory>& histories = contacts.histories;
  // The faces that have not slid (a last increment here is this prediction's own).
  std::vector<char> first(histories.size());
  bool any_first = false;
  for (size_t k = 0; k < histories.size(); ++k)
    any_first |= first[k] = histories[k].slip == 0.0 && !histories[k].settled;
  if (!any_first) return;
  // Per such face, its fastest point's sliding speed.
  std::vector<double> speed;
  largest_per_face(
      contacts.manifolds, static_cast<long>(histories.size()),
      [&](const ContactManifold& m, int q) {
        if (!first[m.history]) return 0.0;
        const ContactPoint& p = m.points[q];
        const Vec3 va = s.blocks[m.block_a].velocity.head<3>(), vb = s.blocks[m.block_b].velocity.head<3>();
        return std::abs(m.tangent.dot(velocity_at(vb, p.rb) - velocity_at(va, p.ra)));
      },
      speed);
  bool any = false;
  for (size_t k = 0; k < histories.size(); ++k) {
    if (speed[k] <= 0.0) continue;
    SlipHistory& h = histories[k];
    h.last_slip = speed[k] * step;
    h.slip_rate = h.previous_slip_rate = speed[k];
    refresh_friction(s, h);
    any = true;
  }
  if (!any) return;
  std::vector<ContactManifold>& manifolds = contacts.manifolds;
  const long n = static_cast<long>(manifolds.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    ContactManifold& m = manifolds[k];
    if (m.history >= 0 && speed[m.history] > 0.0) m.friction = histories[m.history].friction;
  }
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

namespace {

// Each face's largest slip of its points and, under thermal pressurization, their load. A load
// is a sum, whose rounding depends on the order: with shear bands both are gathered into the
// histories here, in manifold order, on one thread, and `largest` is left empty. Otherwise the
// largest slips are gathered on all threads into `largest` (largest_per_face), for the
// histories' own parallel loop to take (gather_slip).
void gather_points(ContactSet& contacts, std::vector<double>& largest) {
  const std::vector<ContactManifold>& manifolds = contacts.manifolds;
  std::vector<SlipHistory>& histories = contacts.histories;
  const bool bands = std::any_of(contacts.shear_bands.begin(), contacts.shear_bands.end(),
                                 [](const laws::DiffusionGrid& g) { return !g.empty(); });
  largest.clear();
  if (bands) {
    for (const ContactManifold& m : manifolds)
      if (m.history >= 0)
        for (int q = 0; q < m.point_count; ++q) {
          SlipHistory& h = histories[m.history];
          gather_slip(h, m.points[q].slip);
          if (!h.band_column.empty()) h.normal_load += m.points[q].normal_load;
        }
    return;
  }
  largest_per_face(manifolds, static_cast<long>(histories.size()),
                   [](const ContactManifold& m, int q) { return m.points[q].slip; }, largest);
}

}  // namespace

void advance_histories(const BlockSystem& s, ContactSet& contacts, double duration) {
  std::vector<double> largest;
  gather_points(contacts, largest);
  // Each face's law on its own: parallel, and the same numbers on any thread count.
  std::vector<SlipHistory>& histories = contacts.histories;
  const long n = static_cast<long>(histories.size());
  bool any = false;
#pragma omp parallel for schedule(static) reduction(|| : any) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    SlipHistory& h = histories[k];
    if (!largest.empty()) gather_slip(h, largest[k]);
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
