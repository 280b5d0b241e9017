// Ensemble realisations: the same scene with its free blocks nudged, to measure how far
// a run's answer depends on its exact initial state. A rapid slide of many blocks is
// chaotic (docs/speed-accuracy.md): a difference of a rounding error grows into metres of
// runout; an ensemble of nudged runs gives the spread that any one run carries.
#pragma once

#include <cstdint>

#include "forward/scene.hpp"

namespace ddafit {

// Largest offset of a nudged block, as a fraction of its size sqrt(area).
constexpr double kJitterRatio = 1e-4;

// Realisation k >= 1 of `scene`: every free block shifted rigidly by an offset drawn
// uniformly from the disc of radius kJitterRatio x sqrt(its area); each measure point moves
// with the free block that holds it (it names a material point). The offsets come from
// SplitMix64 seeded with k (two draws per free block, in block order: the radius sqrt(u1)
// and the angle 2 pi u2, each u from the top 53 bits), so the same k gives the same scene
// with the same binary on any machine. Realisation 0 is the scene unchanged. The nudged
// scene may overlap by up to twice the offset where blocks touched: run it, do not
// validate it (simulate() applies the nudge after its checks).
Scene perturbed_scene(const Scene& scene, int realisation);

}  // namespace ddafit
