#include "verify/cases.hpp"

#include <cmath>

namespace ddafit::verification {
namespace {

Scene base_scene(double duration, double step, double output_interval) {
  Scene s;
  s.duration = duration;
  s.max_step = step;
  s.output_interval = output_interval;
  s.materials.push_back({"rock", 2700.0, 5.0e9, 0.25});
  return s;
}

std::vector<Vec2> box(Vec2 origin, Vec2 along, Vec2 up, double length, double height) {
  return {origin, origin + length * along, origin + length * along + height * up, origin + height * up};
}


double shift_of_top(int courses, double w) { return ((courses - 1) % 2) ? 0.5 * w : 0.0; }

}  // namespace

Scene incline_scene(const InclineSetup& setup) {
  Scene s = base_scene(setup.duration, setup.time_step, setup.output_interval);
  Interface face;
  face.name = "interface";
  face.friction_angle = setup.friction_angle;
  face.roughness_angle = setup.roughness_angle;
  face.critical_distance_ratio = 0.01;
  s.interfaces.push_back(face);
  s.default_interface = 0;
  // The slope descends to the right: 30 m run, 15 m drop for a 2:1 slope.
  const double run = 30.0, drop = run * setup.slope_ratio;
  s.blocks.push_back(block("plane", {{0, 0}, {run, -drop}, {run, -drop - 2}, {0, -2}}, true));
  const Vec2 along = Vec2(run, -drop).normalized();
  const Vec2 up(-along.y(), along.x());
  const Vec2 origin = 2.0 * along;
  s.blocks.push_back(block("slider", box(origin, along, up, kInclineBlockLength, kInclineBlockHeight), false));
  s.measure.push_back({"P1", origin + 0.5 * kInclineBlockLength * along + 0.5 * kInclineBlockHeight * up});
  return s;
}

Scene thrown_block_scene() {
  Scene s = base_scene(2.0, 1.0e-3, 0.01);
  BlockInput b = block("stone", box({0, 0}, {1, 0}, {0, 1}, 1.0, 0.5), false);
  b.velocity = Vec2(5.0, 10.0);
  s.blocks.push_back(b);
  s.measure.push_back({"C", {0.5, 0.25}});
  return s;
}

Scene spinning_block_scene(double turns) {
  Scene s = base_scene(turns, 1.0e-3, 0.1);  // 2 pi rad/s: one turn per second
  s.gravity = Vec2::Zero();
  BlockInput b = block("wheel", box({-0.5, -0.5}, {1, 0}, {0, 1}, 1.0, 1.0), false);
  b.angular_velocity = 2.0 * M_PI;
  s.blocks.push_back(b);
  s.measure.push_back({"corner", {0.4999, 0.4999}});
  return s;
}

Scene stack_scene() {
  Scene s = base_scene(5.0, 1.0e-3, 0.05);
  Interface face;
  face.name = "joint";
  face.friction_angle = 30.0;
  s.interfaces.push_back(face);
  s.default_interface = 0;
  s.blocks.push_back(block("ground", box({-2, -1}, {1, 0}, {0, 1}, 5.0, 1.0), true));
  for (int k = 0; k < 5; ++k) {
    const std::string name = std::string("b").append(std::to_string(k + 1));  // GCC 12 -Wrestrict false positive on "b" + string
    s.blocks.push_back(block(name, box({0, static_cast<double>(k)}, {1, 0}, {0, 1}, 1.0, 1.0), false));
  }
  s.measure.push_back({"top", {0.5, 4.5}});
  return s;
}

Scene collision_scene() {
  Scene s = base_scene(0.5, 1.0e-4, 0.01);
  s.gravity = Vec2::Zero();
  Interface face;
  face.name = "smooth";
  face.friction_angle = 0.0;
  s.interfaces.push_back(face);
  s.default_interface = 0;
  BlockInput a = block("striker", box({0, 0}, {1, 0}, {0, 1}, 1.0, 1.0), false);
  a.velocity = Vec2(4.0, 0.0);
  s.blocks.push_back(a);
  s.blocks.push_back(block("target", box({1.5, 0}, {1, 0}, {0, 1}, 1.0, 1.0), false));
  s.measure.push_back({"striker", {0.5, 0.5}});
  s.measure.push_back({"target", {2.0, 0.5}});
  return s;
}

Scene rocking_column_scene(const RockingSetup& setup) {
  Scene s = base_scene(setup.duration, setup.step, setup.step);
  Interface face;
  face.name = "joint";
  face.friction_angle = 42.0;
  s.interfaces.push_back(face);
  s.default_interface = 0;
  const double b = setup.base, H = setup.height, t = H / setup.blocks;
  const double theta = setup.tilt_share * std::atan(b / H);
  const Vec2 pivot(0.5 * b, 0.0);
  const auto tilt = [&](Vec2 p) {  // clockwise by theta about the pivot
    const Vec2 d = p - pivot;
    return Vec2(pivot.x() + std::cos(theta) * d.x() + std::sin(theta) * d.y(),
                pivot.y() - std::sin(theta) * d.x() + std::cos(theta) * d.y());
  };
  s.blocks.push_back(block("floor", box({-10.0 * b, -b}, {1, 0}, {0, 1}, 20.0 * b, b), true));
  for (int i = 0; i < setup.blocks; ++i) {
    const std::string name = setup.blocks == 1 ? std::string("block") : std::string("block_").append(std::to_string(i));
    s.blocks.push_back(block(name,
                             {tilt({-0.5 * b, i * t}), tilt({0.5 * b, i * t}), tilt({0.5 * b, (i + 1) * t}),
                              tilt({-0.5 * b, (i + 1) * t})},
                             false));
  }
  s.measure.push_back({"base", tilt({0.0, 0.05 * b})});
  s.measure.push_back({"top", tilt({0.0, H - 0.05 * b})});
  return s;
}

Scene rocking_block_scene() { return rocking_column_scene(RockingSetup{}); }

Scene arch_scene(double thickness_ratio) {
  constexpr int kVoussoirs = 15;
  Scene s = rock_scene(2700.0, 40.0, 2.0, 1.0e-3, 0.05);
  const double inner = 1.0 - 0.5 * thickness_ratio, outer = 1.0 + 0.5 * thickness_ratio;
  s.blocks.push_back(block("floor", box({-3.0, -1.0}, {1, 0}, {0, 1}, 6.0, 1.0), true));
  for (int k = 0; k < kVoussoirs; ++k) {  // from the right springing to the left, counter-clockwise
    const double a0 = M_PI * k / kVoussoirs, a1 = M_PI * (k + 1) / kVoussoirs;
    const Vec2 d0(std::cos(a0), std::sin(a0)), d1(std::cos(a1), std::sin(a1));
    const std::string name = std::string("voussoir_").append(std::to_string(k));
    s.blocks.push_back(block(name, {inner * d0, outer * d0, outer * d1, inner * d1}, false));
  }
  s.measure.push_back({"crown", {0.0, 1.0}});
  return s;
}

Scene brick_wall_scene(int courses, int per_course, double duration) {
  Scene s = base_scene(duration, 1.0e-3, 0.01);
  Interface face;
  face.name = "joint";
  face.friction_angle = 35.0;
  s.interfaces.push_back(face);
  s.default_interface = 0;
  const double w = 1.0, h = 0.5;
  s.blocks.push_back(block("floor", box({-2, -1}, {1, 0}, {0, 1}, per_course * w + 4, 1.0), true));
  for (int c = 0; c < courses; ++c) {
    // Odd courses are shifted by half a brick, as in a real wall.
    const double shift = (c % 2) ? 0.5 * w : 0.0;
    for (int k = 0; k < per_course; ++k) {
      const std::string name = std::string("brick_").append(std::to_string(c)).append("_").append(std::to_string(k));
      s.blocks.push_back(block(name, box({shift + k * w, c * h}, {1, 0}, {0, 1}, w, h), false));
    }
  }
  s.measure.push_back({"top", {shift_of_top(courses, w) + 0.5 * w, (courses - 0.5) * h}});
  return s;
}

Scene rock_scene(double density, double friction_angle, double duration, double step, double output_interval) {
  Scene s;
  s.duration = duration;
  s.max_step = step;
  s.output_interval = output_interval;
  s.materials.push_back({"rock", density, 5.0e9, 0.25});
  Interface joint;
  joint.name = "joint";
  joint.friction_angle = friction_angle;
  s.interfaces.push_back(joint);
  s.default_interface = 0;
  return s;
}

BlockInput block(const std::string& name, std::vector<Vec2> polygon, bool fixed) {
  BlockInput b;
  b.name = name;
  b.group = name;
  b.material = 0;
  b.fixed = fixed;
  b.polygon = std::move(polygon);
  return b;
}

}  // namespace ddafit::verification
