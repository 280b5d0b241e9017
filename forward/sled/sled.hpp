// Fidelity 0: the slide as a flexible sled (docs/vajont.md, "The sled"). The free blocks are
// cut into vertical slices; every slice keeps its mass and moves with the others by one
// distance u along the path the fixed blocks' top surface makes (the basal surface, the
// valley floor, the opposite bank), without internal strength. Its base carries Coulomb
// friction from the interface the DDA run would use there, through the same friction laws
// (forward/contact/friction_law.hpp), with the slip u and its speed, and
// d_c = critical_distance_ratio x mesh.block_size (the overriding block's length the DDA run
// would have; for a scene of explicit blocks, the lowest free block's length along the path).
//   M du'' = sum_i m_i g (sin b_i - sgn(u') mu_i cos b_i),   b_i the path's dip at s_i + u
// and at rest while |sum m g sin b| <= sum mu m g cos b. Integrated by RK4 at the scene's step;
// a sled that stops between steps stops there. On one plane it is seed Eq. 4 and Eq. 5.
// Its static friction angle, atan(sum m sin b / sum m cos b), is the coherent-mass limit
// equilibrium of the section.
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/run_record.hpp"

namespace ddafit {

// Runs the sled on the scene's blocks for the scene's duration: moves each free block with the
// slice under its centroid (a translation along the path; the history, summary and ground
// surface are the recorder's, as for the DDA solvers) and returns its own record.
SledRecord run_sled(const Scene& scene, BlockSystem& system, RunRecorder& recorder, SimulationSummary& summary);

}  // namespace ddafit
