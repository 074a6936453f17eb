#include "darcydem/simulation/describe_walls.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace darcydem {
namespace {

template <int D>
std::string vector_text(const Vec<D>& v) {
  std::string out = "(";
  for (int k = 0; k < D; ++k) out += fmt::format("{}{:.4g}", k == 0 ? "" : ", ", v[k]);
  return out + ")";
}

/// A servo's target: its value, or a schedule's first and last values and
/// its length, and its cycle.
std::string target_text(const ServoControl& s) {
  const char* unit = s.by_stress ? "Pa" : "N";
  const auto& values = s.schedule.values;
  std::string out =
      values.size() == 1
          ? fmt::format("{} {:.4g} {}", s.by_stress ? "target_stress" : "target_force", values.front(), unit)
          : fmt::format("{} from {:.4g} to {:.4g} {} over {:.4g} s ({} points, between {:.4g} and {:.4g} {})",
                        s.by_stress ? "target_stress" : "target_force", values.front(), values.back(), unit,
                        s.schedule.times.back(), values.size(),
                        *std::min_element(values.begin(), values.end()),
                        *std::max_element(values.begin(), values.end()), unit);
  if (s.cycle.active()) {
    out += fmt::format(" + {:.4g} {} sin(2 pi {:.4g} Hz t {} {:.4g} deg) (period {:.4g} s)",
                       s.cycle.amplitude, unit, s.cycle.frequency, s.cycle.phase < 0.0 ? "-" : "+",
                       std::abs(s.cycle.phase) * 180.0 / std::numbers::pi, 1.0 / s.cycle.frequency);
  }
  return out + (s.with_pore_water ? ", on the load of the grains and the pore water" : "");
}

/// The motion of a wall (or of a stage's change to it: both have these
/// members), "" when it stands still; `gravity` is the stage's.
template <int D, class Motion>
std::string motion_text(const Motion& m, bool cylinder, const Vec<D>& gravity) {
  std::string out;
  auto add = [&out](const std::string& part) { out += (out.empty() ? "" : "; ") + part; };
  if (m.motion == WallMotion::velocity) add("moves at " + vector_text<D>(m.velocity) + " m/s");
  if (m.motion == WallMotion::servo) add("servo, " + target_text(m.servo));
  if (m.spin != 0.0) add(fmt::format("turns at {:.4g} rad/s", m.spin));
  if (cylinder && m.radius_rate != 0.0) add(fmt::format("its radius changes at {:.4g} m/s", m.radius_rate));
  if (m.oscillation.active()) {
    const auto& o = m.oscillation;
    const double omega = 2.0 * std::numbers::pi * o.frequency;
    const double peak = o.amplitude.norm() * omega * omega;
    std::string shake = fmt::format(
        "oscillates, amplitude {} m at {:.4g} Hz, phase {:.4g} deg: peak acceleration "
        "{:.4g} m/s^2",
        vector_text<D>(o.amplitude), o.frequency, o.phase * 180.0 / std::numbers::pi, peak);
    const double g = gravity.norm();
    if (g > 0.0) {
      const double gamma = std::abs(o.amplitude.dot(gravity)) / g * omega * omega / g;
      shake += fmt::format(", Gamma = A omega^2 / g = {:.3g} along gravity{}", gamma,
                           gamma > 1.0 ? " (above 1: a bed resting on it leaves it once a cycle)" : "");
    }
    add(shake);
  }
  return out;
}

}  // namespace

template <int D>
std::string describe_wall_motions(const Scene<D>& scene) {
  const auto& walls = scene.simulation.walls;
  std::string out;
  Vec<D> gravity = Vec<D>::Zero();
  // The walls start with the first stage's gravity.
  if (!scene.stages.empty() && scene.stages.front().gravity) gravity = *scene.stages.front().gravity;
  for (const auto& w : walls) {
    const std::string text = motion_text<D>(w, w.is_cylinder(), gravity);
    if (!text.empty()) out += fmt::format("wall {}: {}\n", w.name, text);
  }
  for (const auto& stage : scene.stages) {
    if (stage.gravity) gravity = *stage.gravity;
    for (const auto& c : stage.walls) {
      const auto& w = walls[c.wall];
      const std::string text = motion_text<D>(c, w.is_cylinder(), gravity);
      out += fmt::format("stage {}: wall {} {}\n", stage.name, w.name, text.empty() ? "stops" : text);
    }
  }
  return out;
}

template std::string describe_wall_motions<2>(const Scene<2>&);
template std::string describe_wall_motions<3>(const Scene<3>&);

}  // namespace darcydem
