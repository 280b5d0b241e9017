// The XML input (DDAML) of the public UC Berkeley DDA codes (github doolin/ntdda) as a
// ddafit scene: `ddafit import FILE.geo [--analysis FILE.ana] --units kN|SI`. The
// geometry's joint lines are cut into blocks (forward/mesh/joint_lines.hpp); fixed,
// measured and hole points, material lines, block materials, joint properties, the time
// step, number of steps, gravity and penalty are carried over. What ddafit cannot
// represent is refused with its element and line: load points, bolts, seismic points,
// boundary lines, a block held by one fixed point (a pin: ddafit fixes whole blocks),
// initial stresses or strains, a static analysis. docs/scene-format.md, "Importing DDA input".
#pragma once

#include <string>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit::io {

// The classic files carry no units. KiloNewton: m, t (unit mass in t/m^3), kN (unit
// weight in kN/m^3), kPa (Young's modulus, cohesion, tensile strength). SI: m, kg, N, Pa.
enum class DdamlUnits { KiloNewton, SI };

struct DdamlImport {
  Scene scene;
  std::vector<std::string> notes;  // what was carried over differently, for the user to read
};

// Reads the files and builds the scene. `analysis_path` may be empty: the scene then gets
// placeholder material, interface and time settings, named in the notes. Throws
// SceneReadError "FILE: line N: PROBLEM" (one line).
DdamlImport import_ddaml(const std::string& geometry_path, const std::string& analysis_path, DdamlUnits units);

}  // namespace ddafit::io
