#include "verify/verification.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "forward/simulation.hpp"
#include "verify/analytic.hpp"
#include "verify/cases.hpp"

namespace ddafit::verification {
namespace {

CheckRow row(std::string case_name, std::string quantity, double analytic, double computed, double error,
             double tolerance, std::string why) {
  return {std::move(case_name), std::move(quantity), analytic, computed, error, tolerance,
          std::isfinite(error) && error <= tolerance, std::move(why), {}};
}

std::string bound_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

// A one-sided check: `computed` must satisfy `bound` (text, e.g. "<= 0.001"); `error` is
// how far past the bound it lies, and passes at <= tolerance.
CheckRow bound_row(std::string case_name, std::string quantity, std::string bound, double computed, double error,
                   double tolerance, std::string why) {
  CheckRow r = row(std::move(case_name), std::move(quantity), NAN, computed, error, tolerance, std::move(why));
  r.bound = std::move(bound);
  return r;
}

// The scene as given, run by the solver under test.
Scene with_solver(Scene scene, Integrator integrator) {
  scene.options.integrator = integrator;
  return scene;
}

// Downslope distance and speed of the slider's centre point from a run's history.
struct Trace {
  std::vector<double> time, distance, speed;
};

Trace incline_trace(const SimulationResult& r, const Vec2& along) {
  Trace trace;
  for (const HistoryRow& h : r.history) {
    trace.time.push_back(h.time);
    trace.distance.push_back(h.displacement.dot(along));
    trace.speed.push_back(h.velocity.dot(along));
  }
  return trace;
}

InclineAnalytic analytic_for(const InclineSetup& setup) {
  InclineAnalytic a;
  a.slope_angle = std::atan(setup.slope_ratio) * 180.0 / M_PI;
  a.friction_angle = setup.friction_angle;
  a.roughness_angle = setup.roughness_angle;
  a.critical_distance = 0.01 * kInclineBlockLength;
  return a;
}

std::string incline_name(const InclineSetup& s) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "incline phi=%g i=%g", s.friction_angle, s.roughness_angle);
  return buf;
}

// Worst relative errors of displacement (d >= 1 cm) and acceleration (central
// differences over the output interval, the same operator on both curves).
struct InclineErrors {
  double displacement = 0.0;
  double acceleration = 0.0;
  double worst_model_acceleration = 0.0, worst_exact_acceleration = 0.0;
};

InclineErrors incline_errors(const Trace& trace, const std::vector<double>& d, const std::vector<double>& v) {
  InclineErrors e;
  for (size_t k = 0; k < d.size(); ++k)
    if (d[k] >= 0.01) e.displacement = std::max(e.displacement, std::abs(trace.distance[k] - d[k]) / d[k]);
  for (size_t k = 1; k + 1 < trace.time.size(); ++k) {
    const double dt = trace.time[k + 1] - trace.time[k - 1];
    const double a_model = (trace.speed[k + 1] - trace.speed[k - 1]) / dt;
    const double a_exact = (v[k + 1] - v[k - 1]) / dt;
    const double error = std::abs(a_model - a_exact) / a_exact;
    if (error >= e.acceleration) {
      e.acceleration = error;
      e.worst_model_acceleration = a_model;
      e.worst_exact_acceleration = a_exact;
    }
  }
  return e;
}

// Displacement along the slope against Eq. 4 (constant friction) or the integrated
// Eq. 5. Compared where the block has moved at least 1 cm, so that the relative error
// is not dominated by the micrometre settling of the contact springs at the start.
CheckRow incline_displacement_row(const InclineSetup& setup, double tolerance, const std::string& why,
                                  Integrator integrator) {
  const SimulationResult r = simulate(with_solver(incline_scene(setup), integrator));
  if (r.summary.status != RunStatus::Completed)
    return row(incline_name(setup), "run failed: " + r.summary.message, 0, NAN, NAN, tolerance, why);
  const Vec2 along = Vec2(1.0, -setup.slope_ratio).normalized();
  const Trace trace = incline_trace(r, along);
  std::vector<double> d, v;
  analytic_for(setup).solve(trace.time, d, v);
  return row(incline_name(setup), "displacement at t=" + std::to_string(trace.time.back()).substr(0, 4) +
                                      " s (m); error = max relative over the run",
             d.back(), trace.distance.back(), incline_errors(trace, d, v).displacement, tolerance, why);
}

std::vector<CheckRow> incline_degradation_rows(Integrator integrator) {
  InclineSetup setup;
  setup.roughness_angle = 5.0;
  const std::string name = incline_name(setup);
  const SimulationResult r = simulate(with_solver(incline_scene(setup), integrator));
  if (r.summary.status != RunStatus::Completed)
    return {row(name, "run failed: " + r.summary.message, 0, NAN, NAN, 0.01, "")};
  const Vec2 along = Vec2(1.0, -setup.slope_ratio).normalized();
  const Trace trace = incline_trace(r, along);
  const InclineAnalytic analytic = analytic_for(setup);
  std::vector<double> d, v;
  analytic.solve(trace.time, d, v);
  // The same central difference of velocity over the output interval is applied to
  // the model and to the exact solution, so only the model's error is measured.
  const InclineErrors errors = incline_errors(trace, d, v);
  // First and last output intervals: mean acceleration of the model against the exact
  // mean over the same interval (0.2956 and 1.1936 m/s^2 in the seed's notation).
  const size_t n = trace.time.size();
  const auto mean_acceleration = [&](const std::vector<double>& speed, size_t a, size_t b) {
    return (speed[b] - speed[a]) / (trace.time[b] - trace.time[a]);
  };
  const double a_start = mean_acceleration(trace.speed, 0, 1), exact_start = mean_acceleration(v, 0, 1);
  const double a_end = mean_acceleration(trace.speed, n - 2, n - 1), exact_end = mean_acceleration(v, n - 2, n - 1);
  return {
      row(name, "acceleration over the first output interval (m/s^2)", exact_start, a_start,
          std::abs(a_start - exact_start) / exact_start, 0.01, "seed Eq. 5 near d = 0; 1 % as for the curve"),
      row(name, "acceleration over the last output interval (m/s^2)", exact_end, a_end,
          std::abs(a_end - exact_end) / exact_end, 0.01, "seed Eq. 5 for d >= d_c; 1 % as for the curve"),
      row(name, "acceleration at the worst point of the curve (m/s^2); error = max relative",
          errors.worst_exact_acceleration, errors.worst_model_acceleration, errors.acceleration, 0.01,
          "issue: beat the seed's 4 % by staying within 1 %"),
  };
}


std::vector<CheckRow> thrown_block_rows(Integrator integrator) {
  const Scene scene = thrown_block_scene();
  const SimulationResult r = simulate(with_solver(scene, integrator));
  if (r.summary.status != RunStatus::Completed)
    return {row("thrown block", "run failed: " + r.summary.message, 0, NAN, NAN, 1e-9, "")};
  const Vec2 v0 = scene.blocks[0].velocity;
  double worst = 0.0;
  Vec2 exact_end = Vec2::Zero(), model_end = Vec2::Zero();
  for (const HistoryRow& h : r.history) {
    exact_end = v0 * h.time + 0.5 * scene.gravity * h.time * h.time;
    model_end = h.displacement;
    worst = std::max(worst, (model_end - exact_end).norm());
  }
  const double travel = exact_end.norm();
  return {row("thrown block", "height at the end (m); error = max position error / travel", exact_end.y(),
              model_end.y(), worst / travel, 1e-9,
              "constant-acceleration steps integrate free flight exactly: round-off only")};
}

std::vector<CheckRow> stable_block_rows(Integrator integrator) {
  InclineSetup setup;
  setup.friction_angle = 30.0;  // > alpha = 26.57 deg: the block must stay put
  setup.duration = 10.0;
  setup.output_interval = 0.1;
  const SimulationResult r = simulate(with_solver(incline_scene(setup), integrator));
  if (r.summary.status != RunStatus::Completed)
    return {row("stable block phi=30 > alpha", "run failed: " + r.summary.message, 0, NAN, NAN, 1e-3, "")};
  const double creep = r.summary.points[0].max_total_displacement;
  return {bound_row("stable block phi=30 > alpha", "creep in 10 s (m); error = creep, absolute", "<= 0.001", creep, creep, 1e-3,
              "issue: under 1 mm in 10 s (a public code crept 2.4 cm in 2 s)")};
}

std::vector<CheckRow> spinning_block_rows(Integrator integrator) {
  const double turns = 100.0;
  const Scene scene = spinning_block_scene(turns);
  std::vector<double> areas;
  SimulationHooks hooks;
  hooks.on_output = [&](double, const BlockSystem& s) { areas.push_back(s.blocks[0].area); };
  const SimulationResult r = simulate(with_solver(scene, integrator), hooks);
  if (r.summary.status != RunStatus::Completed)
    return {row("spinning block", "run failed: " + r.summary.message, 0, NAN, NAN, 1e-6, "")};
  double area_error = 0.0;
  for (double a : areas) area_error = std::max(area_error, std::abs(a - areas.front()) / areas.front());
  const Vec2 centre(0.0, 0.0);
  const double r0 = (scene.measure[0].at - centre).norm();
  double radius_error = 0.0;
  for (const HistoryRow& h : r.history) radius_error = std::max(radius_error, std::abs((h.position - centre).norm() - r0) / r0);
  const std::string why = "exact rotation update: a first-order update would grow the area by (1+r0^2) per step";
  return {row("spinning block 100 turns", "area (m^2); error = max relative change", areas.front(), areas.back(),
              area_error, 1e-6, why),
          row("spinning block 100 turns", "corner radius (m); error = max relative change", r0,
              (r.history.back().position - centre).norm(), radius_error, 1e-6, why)};
}

std::vector<CheckRow> stack_rows(Integrator integrator) {
  const SimulationResult r = simulate(with_solver(stack_scene(), integrator));
  if (r.summary.status != RunStatus::Completed)
    return {row("stack of five", "run failed: " + r.summary.message, 0, NAN, NAN, 1e-3, "")};
  const double moved = r.summary.points[0].max_total_displacement;
  return {bound_row("stack of five blocks", "top block movement in 5 s (m); error = movement, absolute", "<= 0.001", moved, moved,
              1e-3, "a stack on a level base is in equilibrium: only spring settling (micrometres) is allowed")};
}

std::vector<CheckRow> collision_rows(Integrator integrator) {
  const Scene scene = collision_scene();
  const SimulationResult r = simulate(with_solver(scene, integrator));
  if (r.summary.status != RunStatus::Completed)
    return {row("collision", "run failed: " + r.summary.message, 0, NAN, NAN, 1e-9, "")};
  // Both blocks have the same mass, so momentum is proportional to the sum of velocities.
  const HistoryRow& striker = r.history[r.history.size() - 2];
  const HistoryRow& target = r.history.back();
  const double before = scene.blocks[0].velocity.x();
  const double after = striker.velocity.x() + target.velocity.x();
  const double energy_before = before * before;
  const double energy_after = striker.velocity.squaredNorm() + target.velocity.squaredNorm();
  const double gap = (target.position.x() - striker.position.x()) - 1.0;  // centre distance minus one width
  return {row("collision of two blocks", "momentum / mass after impact (m/s); error = relative", before, after,
              std::abs(after - before) / before, 1e-9, "contact forces are equal and opposite: exact"),
          bound_row("collision of two blocks", "kinetic energy ratio after/before; error = gain above 1", "<= 1",
              energy_after / energy_before, std::max(0.0, energy_after / energy_before - 1.0), 1e-9,
              "a penalty contact in this scheme can only dissipate"),
          bound_row("collision of two blocks", "target moving after impact (m/s); error = 1 if not",
              "> " + bound_text(0.1 * before),
              target.velocity.x(), target.velocity.x() > 0.1 * before ? 0.0 : 1.0, 0.0,
              "the impact must transmit momentum, not let the blocks pass"),
          bound_row("collision of two blocks", "gap between faces at the end (m); error = overlap, absolute", ">= 0", gap,
              std::max(0.0, -gap), 1.25e-3, "penetration limit: 1e-3 x half the model size")};
}

// Housner (1963, verify/analytic.hpp): the block first strikes the floor after t1, and each
// impact keeps r^2 of the rocking energy; the peaks of its tilt give the share each of the
// first three impacts kept.
std::vector<CheckRow> rocking_rows(Integrator integrator) {
  const RockingSetup setup;
  const Scene scene = rocking_block_scene();
  const SimulationResult r = simulate(with_solver(scene, integrator));
  const std::string name = "rocking block 1 x 4.5 m";
  if (r.summary.status != RunStatus::Completed)
    return {row(name, "run failed: " + r.summary.message, 0, NAN, NAN, 0.03, "")};
  const HousnerRocking housner{setup.base, setup.height, scene.gravity.norm()};
  const double t1 = housner.first_impact(setup.tilt_share * housner.alpha()), rr = housner.energy_kept();
  const RockingTrace trace = rocking_trace(r.history);
  const double first = trace.first_impact < 0.0 ? NAN : trace.first_impact;
  double most = NAN, least = NAN;
  for (size_t k = 0; k + 1 < trace.peaks.size() && k < 3; ++k) {
    const double share = housner.energy(trace.peaks[k + 1]) / housner.energy(trace.peaks[k]);
    most = std::isnan(most) ? share : std::max(most, share);
    least = std::isnan(least) ? share : std::min(least, share);
  }
  const std::string kept = "energy share an impact keeps, ";
  return {row(name, "time of the first impact (s); error = relative", t1, first, std::abs(first - t1) / t1, 0.03,
              "Housner's t1; 5 ms steps are 0.7 % of it"),
          bound_row(name, kept + "largest of the first three; error = gain above r^2", "<= " + bound_text(rr), most,
                    std::isnan(most) ? NAN : std::max(0.0, most - rr), 0.02,
                    "an impact may lose more than Housner's instantaneous one, not gain"),
          bound_row(name, kept + "smallest of the first three; error = loss below r^2", ">= " + bound_text(rr), least,
                    std::isnan(least) ? NAN : std::max(0.0, rr - least), 0.12,
                    "a discretised impact loses a little more (Yagoda-Biran & Hatzor 2010 found the same of DDA)")};
}

// Heyman (1969): a semicircular arch stands only if t >= 0.1075 R. Above the limit (t/R 0.15)
// the crown may move by the joints' elastic closure only; below it (t/R 0.08) four hinges form
// and the crown falls most of R.
std::vector<CheckRow> arch_rows(Integrator integrator) {
  std::vector<CheckRow> rows;
  for (const double ratio : {0.15, 0.08}) {
    const SimulationResult r = simulate(with_solver(arch_scene(ratio), integrator));
    const bool stands = ratio > 0.1075;
    const std::string name = std::string("arch 15 voussoirs t/R=").append(stands ? "0.15" : "0.08");
    if (r.summary.status != RunStatus::Completed) {
      rows.push_back(row(name, "run failed: " + r.summary.message, 0, NAN, NAN, 1e-3, ""));
      continue;
    }
    const double moved = r.summary.points[0].max_total_displacement;  // R = 1 m
    if (stands)
      rows.push_back(bound_row(name, "crown movement in 2 s (m); error = movement, absolute", "<= 0.001", moved, moved,
                               1e-3, "above Heyman's minimum thickness 0.1075 R the arch stands"));
    else
      rows.push_back(bound_row(name, "crown fall in 2 s (m); error = shortfall below R/2", ">= 0.5", moved,
                               std::max(0.0, 0.5 - moved), 0.0, "below Heyman's minimum thickness four hinges form"));
  }
  return rows;
}

}  // namespace

std::vector<StabilityPoint> incline_stability_map(const std::vector<double>& penalty_factors,
                                                  const std::vector<double>& time_steps, Integrator integrator) {
  std::vector<StabilityPoint> map;
  InclineSetup setup;
  setup.roughness_angle = 5.0;
  const Vec2 along = Vec2(1.0, -setup.slope_ratio).normalized();
  for (double factor : penalty_factors) {
    for (double step : time_steps) {
      setup.time_step = step;
      Scene scene = incline_scene(setup);
      scene.options.penalty_factor = factor;
      const SimulationResult r = simulate(with_solver(scene, integrator));
      StabilityPoint p;
      p.penalty_factor = factor;
      p.time_step = step;
      const double mass = scene.materials[0].density * kInclineBlockLength * kInclineBlockHeight;
      p.omega = step * std::sqrt(factor * scene.materials[0].young_modulus / mass);
      p.warned = !r.summary.warnings.empty();
      if (r.summary.status != RunStatus::Completed) {
        p.displacement_error = p.acceleration_error = NAN;
      } else {
        const Trace trace = incline_trace(r, along);
        std::vector<double> d, v;
        analytic_for(setup).solve(trace.time, d, v);
        const InclineErrors e = incline_errors(trace, d, v);
        p.displacement_error = e.displacement;
        p.acceleration_error = e.acceleration;
      }
      map.push_back(p);
    }
  }
  return map;
}

std::vector<SubstepStabilityPoint> substep_stability_map(const std::vector<double>& time_steps,
                                                         const std::vector<int>& substeps) {
  std::vector<SubstepStabilityPoint> map;
  InclineSetup setup;
  setup.roughness_angle = 5.0;
  const Vec2 along = Vec2(1.0, -setup.slope_ratio).normalized();
  for (const std::string name : {"incline", "stack"}) {
    for (double step : time_steps) {
      for (int n : substeps) {
        setup.time_step = step;
        Scene scene = name == "incline" ? incline_scene(setup) : stack_scene();
        scene.max_step = step;
        scene.output_interval = std::max(scene.output_interval, step);
        scene.options.substeps = n;
        const SimulationResult r = simulate(with_solver(scene, Integrator::Substep));
        SubstepStabilityPoint p{name, step, n, r.summary.status == RunStatus::Completed, NAN, r.summary.message};
        if (p.completed && name == "incline") {
          const Trace trace = incline_trace(r, along);
          std::vector<double> d, v;
          analytic_for(setup).solve(trace.time, d, v);
          p.error = incline_errors(trace, d, v).displacement;
        } else if (p.completed) {
          p.error = r.summary.points[0].max_total_displacement;
        }
        map.push_back(p);
      }
    }
  }
  return map;
}

std::vector<Check> all_checks(Integrator integrator) {
  std::vector<Check> checks;
  const std::string suffix = integrator == Integrator::Implicit ? "" : std::string("/") + to_string(integrator);
  checks.push_back({"incline_constant_friction" + suffix, [=] {
                      return std::vector<CheckRow>{incline_displacement_row(
                          InclineSetup{}, 0.005, "seed Fig. 6 reached 0.5 %", integrator)};
                    }});
  checks.push_back({"incline_degradation_i5" + suffix, [=] { return incline_degradation_rows(integrator); }});
  for (double i : {1.0, 2.0, 10.0}) {
    checks.push_back({"incline_degradation_i" + std::to_string(static_cast<int>(i)) + suffix, [=] {
                        InclineSetup setup;
                        setup.roughness_angle = i;
                        return std::vector<CheckRow>{incline_displacement_row(
                            setup, 0.005, "seed Fig. 6; same bound as constant friction", integrator)};
                      }});
  }
  checks.push_back({"thrown_block" + suffix, [=] { return thrown_block_rows(integrator); }});
  checks.push_back({"stable_block" + suffix, [=] { return stable_block_rows(integrator); }});
  checks.push_back({"spinning_block" + suffix, [=] { return spinning_block_rows(integrator); }});
  checks.push_back({"stack" + suffix, [=] { return stack_rows(integrator); }});
  checks.push_back({"collision" + suffix, [=] { return collision_rows(integrator); }});
  checks.push_back({"rocking_block" + suffix, [=] { return rocking_rows(integrator); }});
  checks.push_back({"arch" + suffix, [=] { return arch_rows(integrator); }});
  return checks;
}

}  // namespace ddafit::verification
