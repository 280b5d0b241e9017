// SparseSolver's CHOLMOD side (private to forward/: sparse_system.cpp and factor_update.cpp
// include it; nothing else compiles against SuiteSparse): the workspace, the last factor and
// its pattern, the CG timings, and what a factor update needs to know about the factor.
#pragma once

#include <cholmod.h>

#include <Eigen/Core>
#include <vector>

#include "forward/low_rank_change.hpp"

namespace ddafit {

struct SparseBackend {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  // The system matrix, kept from solve to solve: allocated afresh for every pass it was freed
  // at the top of the heap, which glibc then returned to the system and faulted back in
  // (100,000 page faults on the 411-block wall's 150 steps, a quarter of its run time).
  cholmod_sparse* matrix = nullptr;
  Eigen::VectorXd last_solution;
  double factor_seconds = 0.0;     // wall time of the last factorisation
  double iteration_seconds = 0.0;  // running mean wall time of one CG iteration
  std::vector<int> pattern_columns;
  std::vector<int> pattern_rows;
  // Factor updates (SolverOptions::update_factorization). `updated` is a simplicial LDL'
  // copy of `factor` that the rank-one terms of the passes since it was made have changed;
  // `factored` is the system the factor in use (updated when in_use_updated) stands for.
  cholmod_factor* updated = nullptr;
  bool in_use_updated = false;
  AssembledTerms factored;
  AssembledTerms current;  // the pass's own terms, while it is being solved on an update
  bool factored_valid = false;
  // Of the fill-reducing ordering: the permuted position of each unknown, and for each permuted
  // column the entries of L on its path to the root of the elimination tree (an update's cost).
  std::vector<int> inverse_perm;
  std::vector<double> path_entries;
  double factor_entries_squared = 0.0;  // sum over L's columns of their entry count squared (a factorisation's cost)
};

// x = K^-1 rhs with `factor` (supernodal LL' or simplicial LDL').
bool solve_with(cholmod_factor* factor, cholmod_common& common, const Eigen::VectorXd& rhs, Eigen::VectorXd& x);
// r = rhs - K x with the assembled K (`a`, upper triangle); returns |r| / |rhs|.
double relative_residual(cholmod_sparse* a, cholmod_common& common, const Eigen::VectorXd& rhs, const Eigen::VectorXd& x,
                         Eigen::VectorXd& r);

// Factor updates (SolverOptions::update_factorization; low_rank_change.hpp).
// After a new ordering's first factorisation: the permutation's inverse and each column's path cost.
void note_ordering(SparseBackend& be);
// Solves the pass's system K (assembled as `a`, made of the terms `now`) on the factor in use,
// updated by the rank-one terms of the change since be.factored, when their paths cost at most
// cost_share of a factorisation, and checks |K x - rhs| <= tolerance |rhs| after at most one
// refinement. Returns the terms applied, or -1: refactorise (`x` is then undefined).
int solve_updated(SparseBackend& be, const AssembledTerms& now, cholmod_sparse* a, const Eigen::VectorXd& rhs,
                  Eigen::VectorXd& x, double cost_share, double tolerance);

}  // namespace ddafit
