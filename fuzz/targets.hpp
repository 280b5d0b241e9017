// Fuzz targets: each takes arbitrary bytes, feeds them to one reader of ddafit's inputs,
// and returns 0. The contract they check is the one users rely on: any input either
// reads or is refused with one printable line (SceneReadError / StudyError); anything else
// (a signal, another exception, a multi-line or empty message) is a finding. They run
// under libFuzzer (scripts/fuzz.sh) and, over the checked-in corpora, as ordinary tests
// (tests/test_fuzz_regressions.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace ddafit::fuzz {

// A whole scene file, no base folder (so no CSV or base: files).
int scene_reader(const std::uint8_t* data, std::size_t size);

// A region scene and its CSV polyline: the bytes before the first line "%%" are the scene,
// the rest is written as surface.csv next to it; the mesher runs on whatever reads.
int region_mesh(const std::uint8_t* data, std::size_t size);

// A study file next to a copy of the twin scene (cases/inverse/two_sliders.yaml, built in),
// read, checked against the scene and, if it reads, fitted with a budget of 6 against a
// stand-in forward model (values smooth in the parameters, no physics).
int study(const std::uint8_t* data, std::size_t size);

// Lines KEY=VALUE applied as --set overrides to the incline scene.
int set_parser(const std::uint8_t* data, std::size_t size);

// A DDAML geometry file and, after a line "%%", its analysis file, imported as ddafit
// import does (SI units); the joint lines are cut into blocks.
int ddaml(const std::uint8_t* data, std::size_t size);

// Aborts with `what` on stderr: the finding libFuzzer reports.
[[noreturn]] void finding(const std::string& what);

// Checks a refusal's message: non-empty, one line, printable.
void check_message(const std::string& message);

// A fresh scratch folder for this process (under TMPDIR), created once.
std::string scratch_folder();

}  // namespace ddafit::fuzz
