#include "forward/sparse_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

namespace ddafit {

void BlockSparseMatrix::reset(int free_blocks) {
  size = free_blocks;
  diagonal.assign(free_blocks, Mat6::Zero());
  pairs.clear();
  off_diagonal.clear();
  pair_index.clear();
}

void BlockSparseMatrix::add(int a, int b, const Mat6& m) {
  if (a == b) {
    diagonal[a] += m;
    return;
  }
  const bool swap = a > b;
  const int lo = swap ? b : a, hi = swap ? a : b;
  const std::uint64_t key = (static_cast<std::uint64_t>(lo) << 32) | static_cast<std::uint32_t>(hi);
  auto [it, inserted] = pair_index.emplace(key, static_cast<int>(pairs.size()));
  if (inserted) {
    pairs.emplace_back(lo, hi);
    off_diagonal.push_back(Mat6::Zero());
  }
  if (swap)
    off_diagonal[it->second] += m.transpose();
  else
    off_diagonal[it->second] += m;
}

SparseSolver::SparseSolver(const SolverOptions& options) : options_(options) {
  cholmod_start(&common_);
  common_.print = 0;
  common_.error_handler = nullptr;
}

SparseSolver::~SparseSolver() {
  if (factor_) cholmod_free_factor(&factor_, &common_);
  cholmod_finish(&common_);
}

bool SparseSolver::solve(const BlockSparseMatrix& k, const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
                         std::string& reason) {
  const int nb = k.size;
  const int n = 6 * nb;
  if (n == 0) {
    x.resize(0);
    return true;
  }
  // Upper triangle in compressed columns: block column b holds the pairs (a, b), a < b,
  // in increasing a, then the upper part of K_bb.
  std::vector<int> order(k.pairs.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int p, int q) {
    return k.pairs[p].second != k.pairs[q].second ? k.pairs[p].second < k.pairs[q].second
                                                  : k.pairs[p].first < k.pairs[q].first;
  });
  std::vector<int> column_start(nb + 1, 0);
  for (const auto& pr : k.pairs) ++column_start[pr.second + 1];
  for (int b = 0; b < nb; ++b) column_start[b + 1] += column_start[b];

  const size_t nnz = 36 * k.pairs.size() + 21 * static_cast<size_t>(nb);
  cholmod_sparse* a = cholmod_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &common_);
  auto* ap = static_cast<int*>(a->p);
  auto* ai = static_cast<int*>(a->i);
  auto* ax = static_cast<double*>(a->x);
  int pos = 0;
  for (int b = 0; b < nb; ++b) {
    for (int c = 0; c < 6; ++c) {
      ap[6 * b + c] = pos;
      for (int q = column_start[b]; q < column_start[b + 1]; ++q) {
        const int p = order[q];
        const int row_block = k.pairs[p].first;
        for (int r = 0; r < 6; ++r) {
          ai[pos] = 6 * row_block + r;
          ax[pos++] = k.off_diagonal[p](r, c);
        }
      }
      for (int r = 0; r <= c; ++r) {
        ai[pos] = 6 * b + r;
        ax[pos++] = k.diagonal[b](r, c);
      }
    }
  }
  ap[n] = pos;

  const bool warm = options_.reuse_factorization && factor_ != nullptr && static_cast<int>(factor_->n) == n &&
                    last_solution_.size() == n;
  if (warm) {
    x = last_solution_;
    int iterations = 0;
    const bool converged = preconditioned_cg(a, rhs, x, iterations);
    counters_.cg_iterations += iterations;
    if (converged && x.allFinite()) {
      ++counters_.cg_solves;
      cholmod_free_sparse(&a, &common_);
      last_solution_ = x;
      return true;
    }
  }
  const bool ok = refactorize(a, n, reason);
  cholmod_free_sparse(&a, &common_);
  if (!ok) return false;

  cholmod_dense* b = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common_);
  std::copy(rhs.data(), rhs.data() + n, static_cast<double*>(b->x));
  cholmod_dense* sol = cholmod_solve(CHOLMOD_A, factor_, b, &common_);
  cholmod_free_dense(&b, &common_);
  if (sol == nullptr) {
    reason = "CHOLMOD solve failed (status " + std::to_string(common_.status) + ")";
    return false;
  }
  x.resize(n);
  std::copy(static_cast<double*>(sol->x), static_cast<double*>(sol->x) + n, x.data());
  cholmod_free_dense(&sol, &common_);
  if (!x.allFinite()) {
    reason = "the solution has non-finite values (ill-conditioned system: penalty too stiff?)";
    return false;
  }
  last_solution_ = x;
  return true;
}

bool SparseSolver::refactorize(cholmod_sparse* a, int n, std::string& reason) {
  const auto start = std::chrono::steady_clock::now();
  const auto* ap = static_cast<const int*>(a->p);
  const auto* ai = static_cast<const int*>(a->i);
  const int pos = ap[n];
  const bool same_pattern = factor_ && static_cast<int>(pattern_columns_.size()) == n + 1 &&
                            std::equal(ap, ap + n + 1, pattern_columns_.begin()) &&
                            static_cast<int>(pattern_rows_.size()) == pos &&
                            std::equal(ai, ai + pos, pattern_rows_.begin());
  if (!same_pattern) {
    if (factor_) cholmod_free_factor(&factor_, &common_);
    factor_ = cholmod_analyze(a, &common_);
    pattern_columns_.assign(ap, ap + n + 1);
    pattern_rows_.assign(ai, ai + pos);
  }
  counters_.symbolic_analyses += !same_pattern;
  ++counters_.factorizations;
  bool ok = factor_ != nullptr && cholmod_factorize(a, factor_, &common_) != 0;
  if (ok && (common_.status == CHOLMOD_NOT_POSDEF || factor_->minor < static_cast<size_t>(n))) {
    ok = false;
    reason = "the system matrix is not positive definite (pivot " + std::to_string(factor_->minor / 6) +
             " of the free blocks)";
  } else if (!ok) {
    reason = "CHOLMOD factorisation failed (status " + std::to_string(common_.status) + ")";
  }
  if (!ok) {
    // Force a fresh analysis next time: the failed factor may be in an odd state.
    cholmod_free_factor(&factor_, &common_);
    pattern_columns_.clear();
    last_solution_.resize(0);
    return false;
  }
  factor_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

bool SparseSolver::preconditioned_cg(cholmod_sparse* a, const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
                                     int& iterations) {
  const auto start = std::chrono::steady_clock::now();
  const int n = static_cast<int>(rhs.size());
  // Iterations are worth it while they cost less than a factorisation; the first
  // attempts, before any iteration has been timed, may use the full allowance.
  int allowed = options_.max_iterations;
  if (iteration_seconds_ > 0.0)
    allowed = std::min(allowed, static_cast<int>(factor_seconds_ / iteration_seconds_));
  if (allowed < 1) return false;

  cholmod_dense* xd = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common_);
  cholmod_dense* rd = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common_);
  cholmod_dense* qd = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common_);
  auto* xp = static_cast<double*>(xd->x);
  auto* rp = static_cast<double*>(rd->x);
  Eigen::Map<Eigen::VectorXd> r(rp, n);
  // r = F - K x
  std::copy(x.data(), x.data() + n, xp);
  std::copy(rhs.data(), rhs.data() + n, rp);
  double minus_one[2] = {-1.0, 0.0}, one[2] = {1.0, 0.0}, zero[2] = {0.0, 0.0};
  cholmod_sdmult(a, 0, minus_one, one, xd, rd, &common_);
  const double target = options_.tolerance * rhs.norm();
  Eigen::VectorXd p, z, q(n);
  double rz = 0.0;
  bool converged = r.norm() <= target;
  iterations = 0;
  while (!converged && iterations < allowed) {
    cholmod_dense* zd = cholmod_solve(CHOLMOD_A, factor_, rd, &common_);
    if (zd == nullptr) break;
    z = Eigen::Map<Eigen::VectorXd>(static_cast<double*>(zd->x), n);
    cholmod_free_dense(&zd, &common_);
    const double rz_new = r.dot(z);
    p = iterations == 0 ? z : Eigen::VectorXd(z + (rz_new / rz) * p);
    rz = rz_new;
    // q = K p
    std::copy(p.data(), p.data() + n, xp);
    cholmod_sdmult(a, 0, one, zero, xd, qd, &common_);
    q = Eigen::Map<Eigen::VectorXd>(static_cast<double*>(qd->x), n);
    const double pq = p.dot(q);
    ++iterations;
    if (!(pq > 0.0)) break;  // not positive definite along p: let the factorisation decide
    const double alpha = rz / pq;
    x += alpha * p;
    r -= alpha * q;
    converged = r.norm() <= target;
  }
  cholmod_free_dense(&xd, &common_);
  cholmod_free_dense(&rd, &common_);
  cholmod_free_dense(&qd, &common_);
  if (iterations > 0) {
    const double per = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / iterations;
    iteration_seconds_ = iteration_seconds_ > 0.0 ? 0.9 * iteration_seconds_ + 0.1 * per : per;
  }
  return converged;
}

}  // namespace ddafit
