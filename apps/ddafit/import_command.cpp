// `ddafit import FILE.geo [--analysis FILE.ana] --units kN|SI --out scene.yaml`: the input
// of the UC Berkeley DDA codes as a ddafit scene (forward/io/ddaml_import.hpp). The scene
// written is read back before the command says it is done, so what it wrote runs.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "forward/io/ddaml_import.hpp"
#include "forward/io/scene_reader.hpp"

namespace ddafit::app {

int run_import(const ImportArgs& args) {
  io::DdamlImport imported;
  try {
    imported = io::import_ddaml(args.geometry, args.analysis,
                                args.units == "kN" ? io::DdamlUnits::KiloNewton : io::DdamlUnits::SI);
  } catch (const io::SceneReadError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
  const std::string yaml = "# Imported by ddafit import from " + args.geometry +
                           (args.analysis.empty() ? "" : " and " + args.analysis) + " (units: " + args.units + ")\n" +
                           io::scene_to_yaml(imported.scene);
  {
    std::ofstream out(args.out);
    out << yaml;
    if (!out) {
      std::cerr << args.out << ": --out: cannot write the scene\n";
      return kExitBadInput;
    }
  }
  try {
    const Scene back = io::read_scene(args.out);
    int fixed = 0;
    for (const BlockInput& b : back.blocks) fixed += b.fixed ? 1 : 0;
    for (const std::string& note : imported.notes) std::cerr << "note: " << note << "\n";
    std::cout << "wrote " << args.out << ": " << back.blocks.size() << " blocks (" << fixed << " fixed), "
              << back.materials.size() << " materials, " << back.interfaces.size() << " interfaces, "
              << back.measure.size() << " measure points\n";
  } catch (const io::SceneReadError& e) {
    std::cerr << args.geometry << ": the imported scene is not usable: " << e.what() << "\n";
    return kExitBadInput;
  }
  return kExitSuccess;
}

}  // namespace ddafit::app
