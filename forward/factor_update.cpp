#include <algorithm>
#include <cmath>

#include "forward/sparse_backend.hpp"

namespace ddafit {

bool solve_with(cholmod_factor* factor, cholmod_common& common, const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
  const int n = static_cast<int>(rhs.size());
  cholmod_dense* b = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common);
  std::copy(rhs.data(), rhs.data() + n, static_cast<double*>(b->x));
  cholmod_dense* sol = cholmod_solve(CHOLMOD_A, factor, b, &common);
  cholmod_free_dense(&b, &common);
  if (sol == nullptr) return false;
  x.resize(n);
  std::copy(static_cast<double*>(sol->x), static_cast<double*>(sol->x) + n, x.data());
  cholmod_free_dense(&sol, &common);
  return true;
}

double relative_residual(cholmod_sparse* a, cholmod_common& common, const Eigen::VectorXd& rhs, const Eigen::VectorXd& x,
                         Eigen::VectorXd& r) {
  const int n = static_cast<int>(rhs.size());
  cholmod_dense* xd = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common);
  cholmod_dense* rd = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common);
  std::copy(x.data(), x.data() + n, static_cast<double*>(xd->x));
  std::copy(rhs.data(), rhs.data() + n, static_cast<double*>(rd->x));
  double minus_one[2] = {-1.0, 0.0}, one[2] = {1.0, 0.0};
  cholmod_sdmult(a, 0, minus_one, one, xd, rd, &common);
  r = Eigen::Map<Eigen::VectorXd>(static_cast<double*>(rd->x), n);
  cholmod_free_dense(&xd, &common);
  cholmod_free_dense(&rd, &common);
  const double scale = rhs.norm();
  return scale > 0.0 ? r.norm() / scale : r.norm();
}

// After a fill-reducing ordering's first factorisation: each unknown's permuted position, and
// for each column of L the entries on its path to the elimination tree's root. A rank-one
// update starting at column j rewrites about path_entries[j] entries of L; a factorisation
// costs about the sum of the squared column counts (Davis & Hager, "Modifying a sparse
// Cholesky factorization", SIAM J. Matrix Anal. Appl. 20, 1999).
void note_ordering(SparseBackend& be) {
  const cholmod_factor* l = be.factor;
  const int n = static_cast<int>(l->n);
  const auto* perm = static_cast<const int*>(l->Perm);
  be.inverse_perm.assign(n, 0);
  for (int k = 0; k < n; ++k) be.inverse_perm[perm[k]] = k;
  std::vector<int> count(n, 1), parent(n, -1);
  if (l->is_super) {
    const auto* super = static_cast<const int*>(l->super);
    const auto* pi = static_cast<const int*>(l->pi);
    const auto* rows = static_cast<const int*>(l->s);
    for (size_t sn = 0; sn < l->nsuper; ++sn) {
      const int k1 = super[sn], k2 = super[sn + 1];
      const int nrows = pi[sn + 1] - pi[sn];
      for (int j = k1; j < k2; ++j) {
        count[j] = nrows - (j - k1);
        parent[j] = j + 1 < k2 ? j + 1 : (nrows > k2 - k1 ? rows[pi[sn] + (k2 - k1)] : -1);
      }
    }
  } else {
    const auto* lp = static_cast<const int*>(l->p);
    const auto* li = static_cast<const int*>(l->i);
    const auto* lnz = static_cast<const int*>(l->nz);
    for (int j = 0; j < n; ++j) {
      count[j] = lnz[j];
      parent[j] = lnz[j] > 1 ? li[lp[j] + 1] : -1;
    }
  }
  be.path_entries.assign(n, 0.0);
  be.factor_entries_squared = 0.0;
  for (int j = n - 1; j >= 0; --j) {
    be.path_entries[j] = count[j] + (parent[j] > j ? be.path_entries[parent[j]] : 0.0);
    be.factor_entries_squared += static_cast<double>(count[j]) * count[j];
  }
}

namespace {

// Applies the rank-one terms to `factor` (an update: LDL' + C C^T; else a downdate), C's rows
// in the factor's permuted order as CHOLMOD requires.
bool apply_terms(SparseBackend& be, const std::vector<RankOneTerm>& terms, bool update) {
  if (terms.empty()) return true;
  const int n = static_cast<int>(be.inverse_perm.size());
  size_t nnz = 0;
  for (const RankOneTerm& t : terms) nnz += t.rows.size();
  cholmod_sparse* c = cholmod_allocate_sparse(n, terms.size(), nnz, 1, 1, 0, CHOLMOD_REAL, &be.common);
  if (c == nullptr) return false;
  auto* cp = static_cast<int*>(c->p);
  auto* ci = static_cast<int*>(c->i);
  auto* cx = static_cast<double*>(c->x);
  // Each term's entries in permuted rows, and the terms in the order of their first row:
  // CHOLMOD applies them eight at a time, and terms that start near each other in the
  // elimination tree share more of their paths to its root.
  std::vector<std::vector<std::pair<int, double>>> columns(terms.size());
  for (size_t k = 0; k < terms.size(); ++k) {
    for (size_t e = 0; e < terms[k].rows.size(); ++e)
      columns[k].emplace_back(be.inverse_perm[terms[k].rows[e]], terms[k].values[e]);
    std::sort(columns[k].begin(), columns[k].end());
  }
  std::sort(columns.begin(), columns.end(), [](const auto& x, const auto& y) { return x.front().first < y.front().first; });
  int pos = 0;
  for (size_t k = 0; k < columns.size(); ++k) {
    cp[k] = pos;
    for (const auto& [row, value] : columns[k]) ci[pos] = row, cx[pos++] = value;
  }
  cp[terms.size()] = pos;
  const int ok = cholmod_updown(update ? 1 : 0, c, be.updated, &be.common);
  cholmod_free_sparse(&c, &be.common);
  return ok != 0 && be.common.status == CHOLMOD_OK && be.updated->minor == be.updated->n;
}

}  // namespace

int solve_updated(SparseBackend& be, const AssembledTerms& now, cholmod_sparse* a, const Eigen::VectorXd& rhs,
                  Eigen::VectorXd& x, double cost_share, double tolerance) {
  if (be.path_entries.empty()) return -1;
  const int n = static_cast<int>(rhs.size());
  const LowRankChange change = low_rank_change(be.factored, now, std::max(8, n / 8));
  if (!change.representable) return -1;
  double cost = 0.0;
  for (const auto* terms : {&change.updates, &change.downdates})
    for (const RankOneTerm& t : *terms) {
      int first = n;
      for (const int row : t.rows) first = std::min(first, be.inverse_perm[row]);
      cost += be.path_entries[first];
    }
  if (cost > cost_share * be.factor_entries_squared) return -1;
  if (change.rank() > 0) {
    if (!be.in_use_updated) {
      if (be.updated) cholmod_free_factor(&be.updated, &be.common);
      be.updated = cholmod_copy_factor(be.factor, &be.common);
      if (be.updated == nullptr || !cholmod_change_factor(CHOLMOD_REAL, 0, 0, 0, 1, be.updated, &be.common)) return -1;
      be.in_use_updated = true;
    }
    // Updates first: the factor stays positive definite in between.
    if (!apply_terms(be, change.updates, true) || !apply_terms(be, change.downdates, false)) {
      be.in_use_updated = false;
      return -1;
    }
  }
  cholmod_factor* factor = be.in_use_updated ? be.updated : be.factor;
  Eigen::VectorXd r, dx;
  bool good = solve_with(factor, be.common, rhs, x) &&
              relative_residual(a, be.common, rhs, x, r) <= tolerance;
  if (!good && x.allFinite() && solve_with(factor, be.common, r, dx)) {  // one step of refinement
    x += dx;
    good = relative_residual(a, be.common, rhs, x, r) <= tolerance;
  }
  if (!good || !x.allFinite()) {
    be.in_use_updated = false;
    return -1;
  }
  std::swap(be.factored, be.current);  // the factor in use now stands for `now`
  return change.rank();
}

}  // namespace ddafit
