// The forward model's revision: part of the inversion cache's key, so that evaluations
// cached by an older physics are never replayed. Bump it with every change that alters
// what simulate() returns for some scene (contact rules, integration, defaults).
#pragma once

namespace ddafit {

inline constexpr const char* kModelRevision = "2026-11-22.3";

}  // namespace ddafit
