// ddafit: back-analysis of rapid landslides with DDA. This file only parses arguments
// and hands over to one function per subcommand.
#include <CLI/CLI.hpp>
#include <iostream>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"

int main(int argc, char** argv) {
  using namespace ddafit::app;
  CLI::App app{"ddafit: discontinuous deformation analysis for landslide back-analysis"};
  app.set_version_flag("--version", std::string("ddafit ") + DDAFIT_VERSION);
  app.require_subcommand(1);

  SimulateArgs sim;
  CLI::App* simulate = app.add_subcommand("simulate", "run a scene; writes history.csv and summary.json");
  simulate->add_option("scene", sim.scene, "scene file (YAML); without it, the built-in incline case");
  simulate->add_option("--out", sim.out, "output folder")->capture_default_str();
  simulate->add_option("--set", sim.sets, "override a scene value, KEY=VALUE (repeatable)");
  simulate->add_flag("--quiet", sim.quiet, "print nothing but errors");

  VerifyArgs ver;
  CLI::App* verify = app.add_subcommand("verify", "run the built-in analytic verification suite");
  verify->add_option("--only", ver.only, "run only the checks whose name contains this text");
  verify->add_flag("--stability-map", ver.stability_map,
                   "run the incline over a grid of time steps and penalties (docs/verification.md)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "ddafit: " << e.what() << " (ddafit --help)\n";
    return kExitBadInput;
  }
  if (*simulate) return run_simulate(sim);
  if (*verify) return run_verify(ver);
  return kExitBadInput;
}
