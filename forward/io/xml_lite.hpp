// Just enough XML for the input files of the DDA codes before ddafit (DDAML): elements
// with attributes, text, comments, the XML declaration and a DOCTYPE (never loaded), each
// element with the line it starts on. Names are kept without their namespace prefix
// ("Berkeley:Geometry" is "Geometry"), as the DDAML readers match them. No entities beyond
// the five predefined ones, no CDATA; a file that needs more is refused.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ddafit::io {

struct XmlElement {
  std::string name;  // local name
  std::vector<std::pair<std::string, std::string>> attributes;  // local names
  std::string text;  // the element's own text, children's excluded, entities resolved
  int line = 0;
  std::vector<XmlElement> children;

  // The attribute's value, or nullptr.
  const std::string* attribute(const std::string& name) const;
};

// "FILE: line N: PROBLEM", one line.
struct XmlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Parses a document's text; returns its root element. Throws XmlError naming file_label.
XmlElement parse_xml(const std::string& text, const std::string& file_label);

}  // namespace ddafit::io
