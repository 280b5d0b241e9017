// Ensemble realisations: the same scene with its free blocks nudged, to measure how far
// a run's answer depends on its exact initial state. A rapid slide of many blocks is
// chaotic (docs/speed-accuracy.md): a difference of a rounding error grows into metres of
// runout; an ensemble of nudged runs gives the spread that any one run carries.
#pragma once

#include <cstdint>

#include "forward/scene.hpp"

namespace ddafit {

// Largest offset of a nudged block, as a fraction of its size sqrt(area), when the run
// does not set one. Not the 1e-4 first planned: in a packed mesh a nudge overlaps its
// neighbours by up to twice the offset, and on Vajont section I (34 m blocks) 1e-4 left
// overlaps that 7 of 7 implicit members and 3 of 8 substep members could not start from
// (their contacts released the overlaps' energy within 0.2 s); a 1e-6 nudge starts every
// member, and 1e-6 and 1e-8 give the same spread (docs/speed-accuracy.md, "Ensembles"):
// the spread is the slide's, not the nudge's.
constexpr double kJitterRatio = 1e-6;

// Realisation k >= 1 of `scene`: every free block shifted rigidly by an offset drawn
// uniformly from the disc of radius r x sqrt(its area), r = scene.options.jitter_ratio
// (kJitterRatio when unset); each measure point moves
// with the free block that holds it (it names a material point). The offsets come from
// SplitMix64 seeded with k (two draws per free block, in block order: the radius sqrt(u1)
// and the angle 2 pi u2, each u from the top 53 bits), so the same k gives the same scene
// with the same binary on any machine. Realisation 0 is the scene unchanged. The nudged
// scene may overlap by up to twice the offset where blocks touched: run it, do not
// validate it (simulate() applies the nudge after its checks).
Scene perturbed_scene(const Scene& scene, int realisation);

}  // namespace ddafit
