#include "forward/low_rank_change.hpp"

#include <cmath>

namespace ddafit {
namespace {

RankOneTerm term_of(const SpringTerm& s) {
  RankOneTerm t;
  const double root = std::sqrt(s.stiffness);
  for (const auto& [unknown, g] : {std::pair{s.i, &s.a}, std::pair{s.j, &s.b}}) {
    if (unknown < 0) continue;
    for (int r = 0; r < 6; ++r) {
      if ((*g)[r] == 0.0) continue;
      t.rows.push_back(6 * unknown + r);
      t.values.push_back(root * (*g)[r]);
    }
  }
  return t;
}

// A spring between two fixed blocks has no unknowns and no term.
void add_term(std::vector<RankOneTerm>& terms, const SpringTerm& s) {
  RankOneTerm t = term_of(s);
  if (!t.rows.empty()) terms.push_back(std::move(t));
}

}  // namespace

LowRankChange low_rank_change(const AssembledTerms& then, const AssembledTerms& now, int max_rank) {
  LowRankChange change;
  if (then.size != now.size || then.pairs != now.pairs || then.block_terms != now.block_terms) return change;
  const std::vector<SpringTerm>& a = then.springs;
  const std::vector<SpringTerm>& b = now.springs;
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i].key < b[j].key)) {
      add_term(change.downdates, a[i++]);
    } else if (i == a.size() || b[j].key < a[i].key) {
      add_term(change.updates, b[j++]);
    } else {
      if (!(a[i] == b[j])) {
        add_term(change.downdates, a[i]);
        add_term(change.updates, b[j]);
      }
      ++i, ++j;
    }
    if (change.rank() > max_rank) return LowRankChange{};
  }
  change.representable = true;
  return change;
}

}  // namespace ddafit
