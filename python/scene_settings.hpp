// A scene in Python (ddafit.Scene): read from its file with settings applied as the
// command line's --set does, its settings readable by key (scene["interfaces.clay.
// friction_angle"]) and changeable (the file is read again with the change, so every check
// of the reader applies and a recut follows a mesh key), its blocks' outlines as arrays.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "forward/io/scene_reader.hpp"
#include "forward/scene.hpp"

namespace ddafit::python {

struct PyScene {
  Scene scene;
  std::string path;
  io::Overrides overrides;  // the settings changed from the file, in order
};

void bind_scene(pybind11::module_& m);

// A Python value as the scene files write it (the text of a --set): True/False as
// true/false, numbers and names as their str().
std::string setting_text(const pybind11::handle& value);

}  // namespace ddafit::python
