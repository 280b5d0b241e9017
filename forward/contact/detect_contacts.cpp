#include "forward/contact/detect_contacts.hpp"

#include "forward/contact/find_pairs.hpp"

namespace ddafit {

std::string prepare_detection(const BlockSystem& s, ContactDetection& detection) {
  return build_shapes(s, detection.shapes);
}

std::string detect_contacts(const BlockSystem& s, ContactDetection& detection, ContactSet& contacts) {
  CollideSettings& settings = detection.settings;
  const auto pairs = find_pairs(s, detection.shapes, settings.margin, settings.extra_reach);
  std::string problem = collide(s, detection, pairs, contacts);
  settings.first_step = false;
  return problem;
}

}  // namespace ddafit
