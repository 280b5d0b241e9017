// The forward model's revision: part of the inversion cache's key, so that evaluations
// cached by an older physics are never replayed. Bump it with every change that alters
// what simulate() returns for some scene (contact rules, integration, defaults). The
// solver that runs is fixed by the scene, the parameters and this revision (the Auto rule
// lives in forward/simulation.cpp), so the key identifies it.
#pragma once

namespace ddafit {

inline constexpr const char* kModelRevision = "2026-12-07.5";

}  // namespace ddafit
