// A slider on a straight slope made of flush fixed blocks (joints across its path), shared
// by the joint-crossing and friction-law tests. Include after contact_scene_audit.hpp; like
// it, everything is in an anonymous namespace.
#pragma once

#include <functional>
#include <initializer_list>
#include <sstream>

#include "tests/contact_scene_audit.hpp"
#include "forward/mirror.hpp"
#include "verify/analytic.hpp"

namespace ddafit {
namespace {

constexpr double kDuration = 1.5, kStep = 1.0e-3, kOutput = 0.01;  // s

struct Slope {
  Vec2 along, up;
  explicit Slope(double degrees)
      : along(std::cos(degrees * kDegree), -std::sin(degrees * kDegree)), up(-along.y(), along.x()) {}
  Vec2 at(double s, double h) const { return s * along + h * up; }
};

struct Crossing {
  double slope = 28.0, friction = 18.0;  // alpha, phi_p (deg)
  double length = 1.2, height = 0.6;     // slider (m)
  double spacing = 1.0;                  // of the joints, along the slope (m)
  double speed = 0.0;                    // initial, down the slope (m/s)
  double front_gap = 0.05;               // from the slider's front to the first joint ahead (m)
  double roughness = 0.0, dc_ratio = 0.01;  // i (deg) and d_c / slider length (seed Eq. 2)
  FrictionLaw law = FrictionLaw::Bilinear;
  double weakening_velocity = 0.1;          // v_w (m/s), velocity_weakening
};

// The n-th case of a sweep that rotates its sliders {length, height} and front gaps through
// every slope {alpha, phi} and joint spacing, so that each value meets several others.
[[maybe_unused]] Crossing sweep_case(const double (&slope)[2], const double (&slider)[2], double spacing, int n) {
  Crossing c;
  c.slope = slope[0];
  c.friction = slope[1];
  c.length = slider[0];
  c.height = slider[1];
  c.spacing = spacing;
  c.front_gap = 0.01 + 0.02 * (n % 3);
  return c;
}

// The slider's elastic period L/c (L = sqrt(area), c = sqrt(E / rho) of the scenes' rock, E = 5 GPa).
[[maybe_unused]] double elastic_period(const Crossing& c) {
  return std::sqrt(c.length * c.height) / std::sqrt(5.0e9 / kRockDensity);
}

// time.step at `share` of the slider's L/c, with an output about every 0.01 s, a whole number of
// steps apart (no step is shortened to land on one).
[[maybe_unused]] void set_step_share(Scene& scene, const Crossing& c, double share) {
  scene.max_step = share * elastic_period(c);
  scene.output_interval = scene.max_step * std::max(1.0, std::round(0.01 / scene.max_step));
}

[[maybe_unused]] std::string describe(const Crossing& c, Integrator integrator) {
  std::ostringstream out;
  out << name_of(integrator) << ": alpha " << c.slope << ", phi " << c.friction << ", i " << c.roughness;
  if (c.law != FrictionLaw::Bilinear) out << " (" << to_string(c.law) << ")";
  out << ", slider "
      << c.length << " x " << c.height << ", joints every " << c.spacing << " m, v0 " << c.speed << " m/s";
  return out.str();
}

// A straight slope made of fixed blocks `spacing` long (flush: one line, joints across it),
// the slider on it with its front `front_gap` before a joint.
[[maybe_unused]] Scene crossing_scene(const Crossing& c, Integrator integrator) {
  Scene s = base_scene(kDuration, kStep, kOutput, integrator);
  Interface face;
  face.name = "slope";
  face.friction_angle = c.friction;
  face.roughness_angle = c.roughness;
  face.critical_distance_ratio = c.dc_ratio;
  face.law = c.law;
  face.weakening_velocity = c.weakening_velocity;
  s.interfaces.push_back(face);
  s.default_interface = 0;
  const Slope slope(c.slope);
  const double g = 9.81;
  // The slope reaches past where the slider gets at its residual friction.
  const double residual = (c.friction - c.roughness) * kDegree;
  const double a = g * (std::sin(c.slope * kDegree) - std::cos(c.slope * kDegree) * std::tan(residual));
  const double travel = c.speed * kDuration + 0.5 * std::max(a, 1.0) * kDuration * kDuration;
  int k = 1;
  while (k * c.spacing - c.front_gap - c.length < 0.2) ++k;
  const double rear = k * c.spacing - c.front_gap - c.length;
  const int blocks = static_cast<int>(std::ceil((rear + c.length + travel + 1.0) / c.spacing));
  for (int j = 0; j < blocks; ++j) {
    const double s0 = j * c.spacing, s1 = s0 + c.spacing;
    s.blocks.push_back(block("base_" + std::to_string(j),
                             {slope.at(s0, 0), slope.at(s0, -1), slope.at(s1, -1), slope.at(s1, 0)}, true, 0, "base"));
  }
  BlockInput slider = block("slider", box(slope.at(rear, 0), slope.along, slope.up, c.length, c.height), false);
  slider.velocity = c.speed * slope.along;
  s.blocks.push_back(slider);
  s.measure.push_back({"centre", slope.at(rear + 0.5 * c.length, 0.5 * c.height)});
  return s;
}

// A fixed plane `plane_length` long down `slope` (group "plane", 1 m thick) and on it a row of
// `row_blocks` free blocks `row_length` long and `row_height` thick from its top end (group
// "row"): the free row that test_free_row.cpp and test_stacked_slider.cpp drive sliders over.
[[maybe_unused]] void add_plane_and_free_row(Scene& s, const Slope& slope, double plane_length, double row_length,
                                             double row_height, int row_blocks) {
  s.blocks.push_back(block("plane", {slope.at(0, 0), slope.at(0, -1), slope.at(plane_length, -1),
                                     slope.at(plane_length, 0)}, true, 0, "plane"));
  for (int j = 0; j < row_blocks; ++j)
    s.blocks.push_back(block("row_" + std::to_string(j),
                             box(slope.at(j * row_length, 0), slope.along, slope.up, row_length, row_height), false,
                             0, "row"));
}

// Runs `s`, as its mirror image descending to the left if `mirrored` (the history turned
// back), and sets `row_moved` to how far any of blocks 1..row_blocks (add_plane_and_free_row's
// row) moved from its place at the first output, m.
[[maybe_unused]] SimulationResult run_watching_row(Scene s, int row_blocks, bool mirrored, double& row_moved) {
  std::vector<Vec2> start;
  row_moved = 0.0;
  SimulationHooks hooks;
  hooks.on_output = [&](double, const BlockSystem& system) {
    for (int b = 1; b <= row_blocks; ++b) {
      if (start.size() < static_cast<size_t>(row_blocks)) start.push_back(system.blocks[b].centroid);
      row_moved = std::max(row_moved, (system.blocks[b].centroid - start[b - 1]).norm());
    }
  };
  if (mirrored) s = mirrored_scene(s);
  SimulationResult r = simulate(s, hooks);
  if (mirrored) unmirror_history(r.history);
  return r;
}

// Seed Eq. 4's acceleration down a slope of `slope` degrees at friction `friction` degrees, m/s^2.
[[maybe_unused]] double eq4_acceleration(double slope, double friction) {
  return 9.81 * (std::sin(slope * kDegree) - std::cos(slope * kDegree) * std::tan(friction * kDegree));
}

// Distance down a slope at `times` for d'' = accel(d, d') from d = 0, d' = v0, by classical
// RK4 with 1e-5 s steps; the block sticks where it stops if accel(d, 0) <= 0 holds it.
[[maybe_unused]] std::vector<double> rk4_slide(const std::function<double(double, double)>& accel, double v0,
                                               const std::vector<double>& times) {
  constexpr double h = 1e-5;
  double t = 0.0, d = 0.0, v = v0;
  std::vector<double> out;
  for (const double target : times) {
    while (t < target - 1e-12) {
      const double step = std::min(h, target - t);
      const double k1v = accel(d, v), k1d = v;
      const double k2v = accel(d + 0.5 * step * k1d, v + 0.5 * step * k1v), k2d = v + 0.5 * step * k1v;
      const double k3v = accel(d + 0.5 * step * k2d, v + 0.5 * step * k2v), k3d = v + 0.5 * step * k2v;
      const double k4v = accel(d + step * k3d, v + step * k3v), k4d = v + step * k3v;
      d += step / 6.0 * (k1d + 2 * k2d + 2 * k3d + k4d);
      v += step / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
      t += step;
      if (v < 0.0 || (v == 0.0 && accel(d, 0.0) <= 0.0)) v = 0.0;
    }
    out.push_back(d);
  }
  return out;
}

// A run's slide down `slope` against d_exact(t) (rk4_slide at the run's output times): the
// worst relative error where the exact distance is at least 1 cm, when it happened, and the
// exact distance at the end.
struct SlideError {
  double worst = 0.0, when = 0.0, final_distance = 0.0;
};
[[maybe_unused]] SlideError slide_error(const SimulationResult& r, const Slope& slope,
                                        const std::function<std::vector<double>(const std::vector<double>&)>& exact_at) {
  std::vector<double> times, model;
  for (const HistoryRow& row : r.history) {
    times.push_back(row.time);
    model.push_back(row.displacement.dot(slope.along));
  }
  const std::vector<double> exact = exact_at(times);
  SlideError e;
  if (!exact.empty()) e.final_distance = exact.back();
  for (size_t k = 0; k < times.size(); ++k) {
    if (exact[k] < 0.01) continue;
    const double relative = std::abs(model[k] - exact[k]) / exact[k];
    if (relative > e.worst) e.worst = relative, e.when = times[k];
  }
  return e;
}

// The 1 % of the analytic displacement along the slope (test_joint_crossing.cpp says why).
constexpr double kDisplacementTolerance = 0.01;

// Largest relative error of the slider's displacement along the slope against seed Eq. 4
// (Eq. 5 by RK4 when it degrades) over the outputs where it has moved 1 cm (slide_error).
[[maybe_unused]] double displacement_error(const SimulationResult& r, const Crossing& c, double* worst_time) {
  const SlideError e = slide_error(r, Slope(c.slope), [&](const std::vector<double>& times) {
    std::vector<double> exact(times.size()), speed;
    if (c.roughness > 0.0) {
      verification::InclineAnalytic eq5;
      eq5.slope_angle = c.slope;
      eq5.friction_angle = c.friction;
      eq5.roughness_angle = c.roughness;
      eq5.critical_distance = c.dc_ratio * c.length;
      eq5.solve(times, exact, speed);  // from rest (the degrading cases start at rest)
    } else {
      const double a = eq4_acceleration(c.slope, c.friction);
      for (size_t k = 0; k < times.size(); ++k) exact[k] = c.speed * times[k] + 0.5 * a * times[k] * times[k];
    }
    return exact;
  });
  *worst_time = e.when;
  return e.worst;
}

// The fast sliders of a landslide (test_joint_crossing_coarse.cpp, test_step_by_turn.cpp): 10 and
// 30 m/s, on slopes that speed them up (28/18, 20/12, 35/33 deg) and one that slows them (10 deg at
// 20 deg friction), sliders of 0.5-3 m over joints every 0.3 and 2.5 m, each way down, at each of
// `steps`: run(c, step, mirrored) for each of them, 96 a step. Returns how many ran.
template <class Run>
int for_each_fast_slider(std::initializer_list<double> steps, Run&& run) {
  int runs = 0;
  for (const bool mirrored : {false, true})
    for (const double step : steps)
      for (const double speed : {10.0, 30.0})
        for (const auto& [slope, friction] : {std::pair{28.0, 18.0}, {20.0, 12.0}, {10.0, 20.0}, {35.0, 33.0}})
          for (const auto& [length, height] : {std::pair{0.5, 0.5}, std::pair{1.2, 0.6}, std::pair{3.0, 0.8}})
            for (const double spacing : {0.3, 2.5}) {
              Crossing c;
              c.slope = slope, c.friction = friction, c.length = length, c.height = height;
              c.spacing = spacing, c.speed = speed, c.front_gap = 0.03;
              run(c, step, mirrored);
              ++runs;
            }
  return runs;
}

// One crossing at `step` (time.step), on the slope as built or on its mirror image descending
// to the left (forward/mirror.hpp): the run completes and the slider keeps within 1 % of seed
// Eq. 4 where it has moved 1 cm. Returns the error; `label` names the run.
[[maybe_unused]] double expect_crossing_at_step(const Crossing& c, Integrator integrator, double step,
                                                bool mirrored, std::string& label) {
  Scene scene = crossing_scene(c, integrator);
  scene.max_step = step;
  if (mirrored) scene = mirrored_scene(scene);
  SimulationResult r = simulate(scene);
  if (mirrored) unmirror_history(r.history);
  label = describe(c, integrator) + ", step " + std::to_string(step) + " s" +
          (mirrored ? ", descending to the left" : "");
  EXPECT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
  if (r.summary.status != RunStatus::Completed) return 1.0;
  double when = 0.0;
  const double error = displacement_error(r, c, &when);
  EXPECT_LT(error, kDisplacementTolerance) << label << ": worst at t = " << when << " s";
  return error;
}

// Blocks that friction holds on a face, or that slide down it as one body: the friction angle
// (deg) whose tangent is tan(slope) / ratio (ratio < 1: held with 1 - ratio of the face's
// capacity to spare; ratio > 1: sliding).
[[maybe_unused]] double friction_for_ratio(double slope, double ratio) {
  return std::atan(std::tan(slope * kDegree) / ratio) / kDegree;
}

// A run's error on a face of `slope` deg whose friction is tan(slope) / ratio, at its first measure
// point: sliding, |s - s4| / s4 at the last output, s4 = g (sin a - cos a tan phi) t^2 / 2 (seed
// Eq. 4); held, its largest displacement over the run over `length`.
[[maybe_unused]] double held_or_sliding_error(const SimulationResult& r, double slope, double ratio, double length) {
  const double a = slope * kDegree;
  const double along = 9.81 * (std::sin(a) - std::cos(a) * std::tan(a) / ratio);
  double largest = 0.0, last = 0.0, time = 0.0;
  for (const HistoryRow& row : r.history) {
    if (row.point != 0) continue;
    largest = std::max(largest, row.displacement.norm());
    last = row.displacement.norm(), time = row.time;
  }
  if (along <= 0.0) return largest / length;
  const double expected = 0.5 * along * time * time;
  return std::abs(last - expected) / expected;
}

// A square block of side L resting on a free plate three times its length and `thickness` L
// thick, on a fixed face of `slope` deg that runs 6 L (room for a plate sliding for a second):
// the face's friction tan(slope) / face_ratio, the joint's between block and plate
// tan(slope) / joint_ratio; a time step of `share` of the block's L / c. Measures the block's centre.
struct PlateOnFace {
  double side, thickness, slope, face_ratio, joint_ratio, share;
};

[[maybe_unused]] Scene block_on_free_plate(const PlateOnFace& p, Integrator integrator, double output_interval) {
  Scene s = base_scene(1.0, p.share * p.side / std::sqrt(5.0e9 / kRockDensity), output_interval, integrator);
  const int joint = add_interface(s, "joint", friction_for_ratio(p.slope, p.joint_ratio));
  const int face = add_interface(s, "face", friction_for_ratio(p.slope, p.face_ratio));
  s.default_interface = joint;
  s.contact_rules.push_back({"base", "plate", face});
  const Slope slope(p.slope);
  const double side = p.side, t = p.thickness * side;
  s.blocks.push_back(
      block("base", {slope.at(0, 0), slope.at(0, -side), slope.at(6 * side, -side), slope.at(6 * side, 0)}, true));
  s.blocks.push_back(block("plate", box(slope.at(0.5 * side, 0), slope.along, slope.up, 3 * side, t), false));
  s.blocks.push_back(block("block", box(slope.at(side, t), slope.along, slope.up, side, side), false));
  s.measure.push_back({"centre", slope.at(1.5 * side, t + 0.5 * side)});
  return s;
}

}  // namespace
}  // namespace ddafit
