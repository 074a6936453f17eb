// darcydem from Python (pybind11), over the same library as the program:
//
//   import darcydem
//   darcydem.run("scene.toml", out="out/run")   # as `darcydem run`, returns a summary dict
//   model = darcydem.load("scene.toml")         # as `darcydem check`, at the first stage's start
//   model.apply_stage("settle")                 # a stage's settings, as a run starts it
//   model.set_wall_motion("drum", angular_velocity=2.0)  # a wall's motion between steps
//   model.set_wall_motion("table", angular_velocity=[0.0, 0.1, 0.0])  # a 3D plane or box turns
//   model.set_wall_servo("top", gain=5e-3, max_speed=0.05, target_stress=1e5)  # a stress-controlled wall
//   model.step(1000)                            # DEM steps, with the fluid's and inlets' steps among them
//   model.positions, model.velocities           # numpy arrays (N, D), particles in creation order
//   model.fluid.pressure                        # numpy array over the cells, indexed [i, j(, k)]
//   darcydem.consolidation_degree(t, height=H, conductivity=k, compressibility=m_v, fluid_storage=n/K_f)
//                                               # Terzaghi's closed forms (analysis/seepage_analytic.hpp)
//
// A bad scene raises darcydem.SceneError (a ValueError) with the file, line,
// key and what is allowed. Ctrl-C stops a step() or run() between steps,
// keeping what was computed (run() writes its checkpoint, as the program does).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <iostream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "contact_view.hpp"
#include "darcydem/analysis/seepage_analytic.hpp"
#include "darcydem/core/quoted.hpp"
#include "darcydem/output/checkpoint_archive.hpp"
#include "darcydem/particles/grading.hpp"
#include "darcydem/scene/scene.hpp"
#include "darcydem/scene/scene_cell.hpp"
#include "darcydem/scene/scene_clumps.hpp"
#include "darcydem/scene/scene_overrides.hpp"
#include "darcydem/scene/toml_reader.hpp"
#include "darcydem/simulation/run_checkpoint.hpp"
#include "darcydem/simulation/runner.hpp"
#include "darcydem/version.hpp"
#include "darcydem/walls/loaded_area.hpp"

namespace py = pybind11;

namespace darcydem::python {
namespace {

/// Steps between checks for Ctrl-C in step(), with the interpreter's lock
/// released in between.
constexpr std::uint64_t kSignalCheckSteps = 256;

/// Rows of D values per particle, in creation order (the simulation keeps
/// its particles sorted in space; `id` is the creation index).
template <int D, class V>
py::array_t<double> per_particle(const ParticleData<D>& p, const std::vector<V>& values, int width) {
  py::array_t<double> out({static_cast<py::ssize_t>(p.size()), static_cast<py::ssize_t>(width)});
  auto a = out.template mutable_unchecked<2>();
  const auto order = p.creation_order();  // those left, if a domain removed some
  for (std::size_t row = 0; row < order.size(); ++row) {
    for (int c = 0; c < width; ++c) a(row, c) = values[order[row]][c];
  }
  return out;
}

/// One value per particle, get(index), in creation order.
template <class T, int D, class Get>
py::array_t<T> per_particle_values(const ParticleData<D>& p, Get&& get) {
  py::array_t<T> out(static_cast<py::ssize_t>(p.size()));
  auto a = out.template mutable_unchecked<1>();
  const auto order = p.creation_order();
  for (std::size_t row = 0; row < order.size(); ++row) a(row) = get(order[row]);
  return out;
}

/// A cell field as an array indexed [i, j(, k)] (cell index i + nx (j + ny k)).
template <int D, class Value>
py::array_t<double> cell_field(const FluidGrid<D>& grid, const std::vector<Value>& values, int width) {
  std::vector<py::ssize_t> shape(grid.cells.begin(), grid.cells.end());
  if (width > 1) shape.push_back(width);
  py::array_t<double, py::array::f_style> out(shape);
  double* data = out.mutable_data();
  const std::size_t n = grid.size();
  for (std::size_t c = 0; c < n; ++c) {
    if constexpr (std::is_same_v<Value, double>) {
      data[c] = values[c];
    } else {
      for (int k = 0; k < width; ++k) data[c + n * static_cast<std::size_t>(k)] = values[c][k];
    }
  }
  return out;
}

template <int D>
py::tuple as_tuple(const Vec<D>& v) {
  py::tuple t(D);
  for (int k = 0; k < D; ++k) t[k] = v[k];
  return t;
}

template <int D>
Vec<D> as_vec(const std::vector<double>& v, const char* what) {
  if (v.size() != static_cast<std::size_t>(D))
    throw py::value_error(fmt::format("{}: {} numbers expected, {} given", what, D, v.size()));
  Vec<D> x;
  for (int k = 0; k < D; ++k) x[k] = v[static_cast<std::size_t>(k)];
  return x;
}

/// A wall's servo as model.walls reports it: None, or its target now
/// ({'target_force': N} or {'target_stress': Pa}) with its 'cycle' if it
/// cycles.
template <int D>
py::object servo_dict(const Wall<D>& w) {
  if (w.motion != WallMotion::servo) return py::none();
  py::dict d;
  if (w.servo.by_stress) {
    d["target_stress"] = w.servo.target_stress;
  } else {
    d["target_force"] = w.servo.target_force;
  }
  if (w.servo.cycle.active()) {
    d["cycle"] = py::dict(py::arg("amplitude") = w.servo.cycle.amplitude,
                          py::arg("frequency") = w.servo.cycle.frequency,
                          py::arg("phase") = w.servo.cycle.phase * 180.0 / std::numbers::pi);
  }
  return d;
}

/// The box [lo, hi] of a measurement, checked: D numbers each, hi > lo.
template <int D>
std::pair<Vec<D>, Vec<D>> as_box(const std::vector<double>& lo, const std::vector<double>& hi) {
  const Vec<D> a = as_vec<D>(lo, "min");
  const Vec<D> b = as_vec<D>(hi, "max");
  for (int k = 0; k < D; ++k) {
    if (!(b[k] > a[k]))
      throw py::value_error(
          fmt::format("max must be greater than min along every axis; along {} min = {} and "
                      "max = {}",
                      "xyz"[k], a[k], b[k]));
  }
  return {a, b};
}

/// A D x D tensor as a numpy array.
template <int D>
py::array_t<double> as_matrix(const Eigen::Matrix<double, D, D>& m) {
  py::array_t<double> out({static_cast<py::ssize_t>(D), static_cast<py::ssize_t>(D)});
  auto a = out.template mutable_unchecked<2>();
  for (int i = 0; i < D; ++i) {
    for (int j = 0; j < D; ++j) a(i, j) = m(i, j);
  }
  return out;
}

/// A scene built from its file and stepped from Python.
template <int D>
class Model {
 public:
  Model(const toml::table& root, const std::string& file, const std::string& text)
      : scene_(build_scene<D>(root, file, text)), contact_frictions_(sim().contact_table.frictions()) {
    // As a run starts: the first stage's settings, and the contact forces'
    // magnitudes summed (for unbalanced_force_ratio).
    if (!scene_.stages.empty()) {
      darcydem::apply_stage(sim(), fluid(), scene_.stages.front());
      apply_inlet_changes(scene_.inlets, scene_.stages.front(), sim().time);
    }
    sim().measure_contact_forces = true;
    sim().prepare();
    if (!scene_.stages.empty() && scene_.stages.front().make_bonds)
      sim().make_bonds(scene_.stages.front().bond_gap);
  }

  [[nodiscard]] Simulation<D>& sim() { return scene_.simulation; }
  [[nodiscard]] const Simulation<D>& sim() const { return scene_.simulation; }
  [[nodiscard]] PoreFluid<D>* fluid() { return scene_.fluid.get(); }
  [[nodiscard]] const Scene<D>& scene() const { return scene_; }

  [[nodiscard]] std::vector<std::string> stage_names() const {
    std::vector<std::string> names;
    for (const auto& s : scene_.stages) names.push_back(s.name);
    return names;
  }

  void apply_stage(const std::string& name) {
    for (std::size_t k = 0; k < scene_.stages.size(); ++k) {
      const auto& s = scene_.stages[k];
      if (s.name == name) {
        if (starts_new_coupling_interval(fluid(), s) && since_update_ > 0) fluid_step();
        darcydem::apply_stage(sim(), fluid(), s);
        apply_inlet_changes(scene_.inlets, s, sim().time);
        if (s.make_bonds) sim().make_bonds(s.bond_gap);
        stage_ = k;
        stage_start_step_ = sim().steps;
        return;
      }
    }
    std::string allowed;
    for (const auto& n : stage_names()) allowed += (allowed.empty() ? "" : ", ") + ("'" + n + "'");
    throw py::value_error(fmt::format("{}: no stage '{}' (the scene's stages: {})", scene_.file, name,
                                      allowed.empty() ? "none" : allowed));
  }

  /// Starts (the first insertion at once) or stops an [[inlet]] between
  /// steps, as a stage's `inlets.NAME = { active = ... }` does.
  void set_inlet_active(const std::string& name, bool active) {
    for (auto& in : scene_.inlets) {
      if (in.name != name) continue;
      if (active && !in.active) in.next_time = sim().time;
      in.active = active;
      return;
    }
    std::string allowed;
    for (const auto& in : scene_.inlets) allowed += (allowed.empty() ? "'" : ", '") + in.name + "'";
    throw py::value_error(fmt::format("set_inlet_active: no [[inlet]] '{}' (the scene's: {})", name,
                                      allowed.empty() ? "none" : allowed));
  }

  /// The periodic cell's motion changed between steps, as a stage's
  /// `periodic_cell` does (YADE's PeriTriaxController goals, PFC's domain
  /// strain rates): per axis {'strain_rate': 1/s} or {'stress': Pa}, the
  /// servo's gain and max_strain_rate.
  void set_cell(const py::object& x, const py::object& y, const py::object& z, const py::object& gain,
                const py::object& max_strain_rate, const py::object& load) {
    const std::string why = cell_deformation_obstacle(sim(), cell_neighbours(scene_));
    if (!why.empty()) throw py::value_error("set_cell: deforms the periodic cell, " + why);
    auto rate_ok = [&](double v, const char* what) {
      if (!CellMotion<D>::rate_allowed(v, sim().time_step)) {
        throw py::value_error(
            fmt::format("set_cell: {} must be {}, got {}", what, cell_rate_rule(sim().time_step), v));
      }
      return v;
    };
    CellChange<D> change;
    const std::array<const py::object*, 3> axes{&x, &y, &z};
    for (int k = 0; k < 3; ++k) {
      if (axes[k]->is_none()) continue;
      if (k >= D) throw py::value_error("set_cell: a 2D scene has no z axis");
      const std::string name(1, "xyz"[k]);
      if (!py::isinstance<py::dict>(*axes[k]) || py::len(*axes[k]) != 1) {
        throw py::value_error(fmt::format(
            "set_cell: {} must be {{'strain_rate': 1/s}} or {{'stress': Pa}} (compression positive)", name));
      }
      const auto d = axes[k]->cast<py::dict>();
      typename CellChange<D>::Axis a;
      if (d.contains("strain_rate")) {
        a.value = rate_ok(d["strain_rate"].cast<double>(), (name + "'s strain_rate").c_str());
      } else if (d.contains("stress")) {
        a.by_stress = true;
        a.value = d["stress"].cast<double>();
        if (!std::isfinite(a.value))
          throw py::value_error(fmt::format("set_cell: {}'s stress must be finite, got {}", name, a.value));
      } else {
        throw py::value_error(fmt::format(
            "set_cell: {} must be {{'strain_rate': 1/s}} or {{'stress': Pa}} (compression positive)", name));
      }
      change.axes[k] = a;
    }
    if (!gain.is_none()) {
      const double g = gain.cast<double>();
      if (!(g > 0.0) || !std::isfinite(g))
        throw py::value_error(fmt::format("set_cell: gain must be finite and > 0 1/(Pa s), got {}", g));
      change.gain = g;
    }
    if (!max_strain_rate.is_none()) {
      const double m = rate_ok(max_strain_rate.cast<double>(), "max_strain_rate");
      if (!(m > 0.0)) throw py::value_error(fmt::format("set_cell: max_strain_rate must be > 0, got {}", m));
      change.max_strain_rate = m;
    }
    if (!load.is_none()) {
      const auto l = load.cast<std::string>();
      if (l != "grains" && l != "total")
        throw py::value_error(fmt::format("set_cell: load must be 'grains' or 'total', got '{}'", l));
      if (l == "total" && fluid() == nullptr) {
        throw py::value_error(
            "set_cell: load 'total' adds the pore water's mean pressure to the contacts' stress, which needs "
            "a "
            "[fluid]");
      }
      change.total_stress = l == "total";
    }
    CellMotion<D> motion = sim().cell_motion;
    change.apply(motion);
    if (motion.servo_incomplete()) {
      throw py::value_error(
          "set_cell: an axis held by stress needs the servo's gain (1/(Pa s)) and max_strain_rate (1/s)");
    }
    sim().cell_motion = motion;
  }

  /// A wall's motion changed between steps, as a stage's `walls.NAME`
  /// entry does (YADE's state.vel and state.angVel, PFC's wall attribute
  /// velocity and spin): a velocity (which ends a servo) and, for a
  /// cylinder, its spin about its axis and the rate of change of its
  /// radius (which ends a servo).
  /// The wall called `name`; `who` names the caller in the error.
  Wall<D>& wall_named(const std::string& name, const char* who) {
    auto& walls = sim().walls;
    auto it = std::find_if(walls.begin(), walls.end(), [&](const Wall<D>& w) { return w.name == name; });
    if (it == walls.end()) {
      std::string names;
      for (const auto& w : walls) names += (names.empty() ? "" : ", ") + ("'" + w.name + "'");
      throw py::value_error(
          fmt::format("{}: no wall '{}' (the scene's walls: {})", who, name, names.empty() ? "none" : names));
    }
    return *it;
  }

  void set_wall_motion(const std::string& name, const std::optional<std::vector<double>>& velocity,
                       const py::object& angular_velocity, std::optional<double> radial_velocity,
                       const py::object& oscillation) {
    Wall<D>* it = &wall_named(name, "set_wall_motion");
    const bool turn = !angular_velocity.is_none();
    if (!velocity && !turn && !radial_velocity && oscillation.is_none())
      throw py::value_error(
          "set_wall_motion: give velocity = [D numbers] (m/s), and or instead an angular_velocity (rad/s), "
          "a cylinder's radial_velocity (m/s) or an oscillation");
    const std::optional<WallOscillation<D>> shake =
        oscillation.is_none() ? std::nullopt
                              : std::optional(read_oscillation(*it, oscillation, velocity.has_value()));
    if (radial_velocity) {
      if (!it->is_cylinder()) {
        throw py::value_error(fmt::format(
            "set_wall_motion: wall '{}' is not a cylinder, and only a cylinder changes its radius", name));
      }
      if (!std::isfinite(*radial_velocity))
        throw py::value_error("set_wall_motion: radial_velocity must be a finite number, m/s");
    }
    // A cylinder's spin about its axis (a number); a plane's or box's turn
    // about its rotation centre: 2D a number, 3D a vector.
    double spin = 0.0;
    Vec<D> spin_axis = Vec<D>::Zero();
    if (turn) {
      const bool number =
          py::isinstance<py::float_>(angular_velocity) || py::isinstance<py::int_>(angular_velocity);
      if (D == 3 && !it->is_cylinder() && !(number && angular_velocity.cast<double>() == 0.0)) {
        if (number || !py::isinstance<py::sequence>(angular_velocity))
          throw py::value_error(fmt::format(
              "set_wall_motion: wall '{}' is a plane or box, which turns about the axis of its angular "
              "velocity through its rotation centre: give angular_velocity = [wx, wy, wz], rad/s (or 0 to "
              "stop it)",
              name));
        const Vec<D> w = as_vec<D>(angular_velocity.cast<std::vector<double>>(), "angular_velocity");
        if (!w.allFinite()) throw py::value_error("set_wall_motion: angular_velocity must be finite, rad/s");
        spin = w.norm();
        if (spin > 0.0) spin_axis = w / spin;
      } else if (number) {
        spin = angular_velocity.cast<double>();
        if (!std::isfinite(spin))
          throw py::value_error("set_wall_motion: angular_velocity must be a finite number, rad/s");
      } else {
        throw py::value_error(
            fmt::format("set_wall_motion: wall '{}' turns about {}: give angular_velocity as a number, rad/s",
                        name, it->is_cylinder() ? "its axis" : "the normal to the plane of the discs"));
      }
      if (!it->is_cylinder() && spin != 0.0) check_can_turn(*it);
    }
    // Both checked before either is set.
    const Vec<D> v = velocity ? as_vec<D>(*velocity, "velocity") : Vec<D>::Zero();
    if (!v.allFinite()) throw py::value_error("set_wall_motion: velocity must be finite, m/s");
    if (velocity) {
      it->motion = WallMotion::velocity;
      it->velocity = v;
    }
    if (turn) {
      it->spin = spin;
      if (!it->is_cylinder() && spin != 0.0) it->axis = spin_axis;
    }
    if (radial_velocity) {
      // Its radius now follows the rate: a servo ends.
      if (it->motion == WallMotion::servo) it->motion = WallMotion::velocity;
      it->radius_rate = *radial_velocity;
    }
    if (shake) it->oscillation = *shake;
  }

  /// set_wall_motion's oscillation: {"amplitude": [D numbers] (m),
  /// "frequency": Hz, "phase": degrees (optional, 0)}, starting now, or
  /// False to stop one. Refused on a servo (unless a velocity is given too,
  /// which ends it) and on an impermeable plate (fixed in the fluid grid).
  WallOscillation<D> read_oscillation(const Wall<D>& w, const py::object& given, bool with_velocity) {
    const std::string form = fmt::format(
        "give oscillation = {{'amplitude': [{} numbers] (m), 'frequency': Hz, 'phase': degrees (optional, "
        "0)}}, or False to stop one",
        D);
    if (py::isinstance<py::bool_>(given)) {
      if (given.cast<bool>()) throw py::value_error("set_wall_motion: " + form);
      return WallOscillation<D>{};
    }
    if (!py::isinstance<py::dict>(given)) throw py::value_error("set_wall_motion: " + form);
    if (w.motion == WallMotion::servo && !with_velocity)
      throw py::value_error(
          fmt::format("set_wall_motion: wall '{}' has a servo, which sets its place from its load: give it a "
                      "velocity too (which ends the servo) to shake it",
                      w.name));
    if (const auto* f = fluid(); f != nullptr) {
      if (std::any_of(f->barriers.begin(), f->barriers.end(),
                      [&](const auto& b) { return b.name == w.name; }))
        throw py::value_error(fmt::format(
            "set_wall_motion: wall '{}' is an impermeable plate, fixed in the fluid grid: it cannot move",
            w.name));
    }
    const auto d = given.cast<py::dict>();
    for (const auto& [key, value] : d) {
      const auto k = py::str(key).cast<std::string>();
      if (k != "amplitude" && k != "frequency" && k != "phase")
        throw py::value_error(fmt::format("set_wall_motion: oscillation has no key '{}': {}", k, form));
    }
    if (!d.contains("amplitude") || !d.contains("frequency"))
      throw py::value_error("set_wall_motion: " + form);
    WallOscillation<D> o;
    o.amplitude = as_vec<D>(d["amplitude"].cast<std::vector<double>>(), "oscillation amplitude");
    o.frequency = d["frequency"].cast<double>();
    const double phase = d.contains("phase") ? d["phase"].cast<double>() : 0.0;
    if (!o.amplitude.allFinite() || o.amplitude.isZero(0.0))
      throw py::value_error(
          "set_wall_motion: the oscillation's amplitude must be finite and not all zero, m");
    if (!(std::isfinite(o.frequency) && o.frequency > 0.0))
      throw py::value_error("set_wall_motion: the oscillation's frequency must be > 0 Hz");
    if (!std::isfinite(phase))
      throw py::value_error("set_wall_motion: the oscillation's phase must be finite");
    o.phase = phase * std::numbers::pi / 180.0;
    o.start = sim().time;
    return o;
  }

  /// A plane or box may turn unless a servo drives it, the pore fluid needs
  /// it along the grid's axes (it displaces the fluid or bars it) or the
  /// boundaries are periodic (walls are not repeated across them).
  void check_can_turn(const Wall<D>& w) {
    const std::size_t index = static_cast<std::size_t>(&w - sim().walls.data());
    if (w.motion == WallMotion::servo)
      throw py::value_error(fmt::format(
          "set_wall_motion: wall '{}' has a servo, which moves it along a fixed direction: give it a "
          "velocity too (which ends the servo) to turn it",
          w.name));
    if (const auto* f = fluid(); f != nullptr) {
      const bool solid =
          std::find(f->solid_walls.begin(), f->solid_walls.end(), index) != f->solid_walls.end();
      const bool barrier = std::any_of(f->barriers.begin(), f->barriers.end(),
                                       [&](const auto& b) { return b.name == w.name; });
      if (solid || barrier)
        throw py::value_error(fmt::format(
            "set_wall_motion: wall '{}' displaces or bars the pore fluid, so it stays along the fluid "
            "grid's axes: it cannot turn",
            w.name));
    }
    for (int k = 0; k < D; ++k) {
      if (sim().periodic.periodic[k])
        throw py::value_error(
            "set_wall_motion: a plane or box wall cannot turn with periodic boundaries (walls are not "
            "repeated across them)");
    }
  }

  /// A value in time: a number, or {'times': [s from now, increasing],
  /// 'values': [...]} (a ramp or schedule), each value finite (and >= 0
  /// if `nonnegative`). `who` (the method) and `what` name it in messages.
  static TimeSeries read_schedule(const py::object& given, const std::string& who, const std::string& what,
                                  bool nonnegative) {
    const std::string form = fmt::format(
        "{} must be a number or {{'times': [s from now], 'values': [...]}} (a ramp or schedule)", what);
    TimeSeries s;
    if (py::isinstance<py::dict>(given)) {
      const auto d = given.cast<py::dict>();
      for (const auto& [key, value] : d) {
        const auto k = py::str(key).cast<std::string>();
        if (k != "times" && k != "values")
          throw py::value_error(fmt::format("{}: {} has no key '{}': {}", who, what, k, form));
      }
      if (!d.contains("times") || !d.contains("values")) throw py::value_error(who + ": " + form);
      s.times = d["times"].cast<std::vector<double>>();
      s.values = d["values"].cast<std::vector<double>>();
      if (s.times.empty() || s.times.size() != s.values.size())
        throw py::value_error(
            fmt::format("{}: {}'s times and values must have the same, non-zero length", who, what));
      for (std::size_t i = 0; i < s.times.size(); ++i) {
        if (!(s.times[i] >= 0.0) || !std::isfinite(s.times[i]) || (i > 0 && !(s.times[i] > s.times[i - 1])))
          throw py::value_error(
              fmt::format("{}: {}'s times must be finite, >= 0 and increase strictly", who, what));
      }
    } else if (py::isinstance<py::float_>(given) || py::isinstance<py::int_>(given)) {
      s = TimeSeries::constant(given.cast<double>());
    } else {
      throw py::value_error(who + ": " + form);
    }
    for (double v : s.values) {
      if (!std::isfinite(v) || (nonnegative && !(v >= 0.0)))
        throw py::value_error(
            fmt::format("{}: {} must be finite{}, got {}", who, what, nonnegative ? " and >= 0" : "", v));
    }
    return s;
  }

  /// A pair of materials' Coulomb coefficient set between steps, as a
  /// stage's contacts = [{ materials = [...], friction = mu }] entry does
  /// (YADE's compaction friction set from a script, PFC's contact property
  /// change): the contacts' tangential springs are held to it from the
  /// next force evaluation.
  void set_friction(const std::vector<std::string>& names, double mu) {
    const auto [a, b] = material_pair(names, "set_friction");
    if (!(mu >= 0.0 && std::isfinite(mu)))
      throw py::value_error(fmt::format("set_friction: friction must be a finite number >= 0, got {}", mu));
    auto& table = sim().contact_table;
    if (mu > 0.0 && contact_frictions_[a * table.materials() + b] == 0.0 && !table(a, b).bondable)
      throw py::value_error(fmt::format(
          "set_friction: the [[contact]] of {} / {} has no friction, so the time step does not allow for the "
          "grains its tangential spring turns; give the [[contact]] the most friction the run uses and lower "
          "it with set_friction or a stage",
          names[0], names[1]));
    table.set_friction(a, b, mu);
  }

  /// A pair of materials' Coulomb coefficient now.
  [[nodiscard]] double friction(const std::vector<std::string>& names) const {
    const auto [a, b] = material_pair(names, "friction");
    return sim().contact_table(a, b).friction;
  }

  /// The materials' indices of a pair with a [[contact]], by their names;
  /// `who` names the caller in the error.
  [[nodiscard]] std::pair<std::size_t, std::size_t> material_pair(const std::vector<std::string>& names,
                                                                  const char* who) const {
    const auto& s = sim();
    if (names.size() != 2)
      throw py::value_error(
          fmt::format("{}: materials must name exactly two materials, e.g. ['sand', 'sand']", who));
    std::array<std::size_t, 2> m{};
    for (int k = 0; k < 2; ++k) {
      std::string allowed;
      m[k] = s.materials.size();
      for (std::size_t j = 0; j < s.materials.size(); ++j) {
        allowed += (allowed.empty() ? "'" : ", '") + s.materials[j].name + "'";
        if (s.materials[j].name == names[k]) m[k] = j;
      }
      if (m[k] == s.materials.size())
        throw py::value_error(
            fmt::format("{}: no material '{}' (the scene's materials: {})", who, names[k], allowed));
    }
    const PairParameters& pair = s.contact_table(m[0], m[1]);
    const bool defined =
        pair.law == NormalLaw::linear ? pair.normal_stiffness > 0.0 : pair.hertz_modulus > 0.0;
    if (!defined)
      throw py::value_error(fmt::format("{}: the pair {} / {} has no [[contact]]", who, names[0], names[1]));
    return {m[0], m[1]};
  }

  /// Sets a [[fluid.source]]'s inflow or the pressure it holds between
  /// steps, as a stage's fluid.sources.NAME = { inflow = ... } or {
  /// pressure = ... } does, a series counted from now.
  void set_fluid_source(const std::string& name, const py::object& inflow, const py::object& pressure) {
    PoreFluid<D>* f = fluid();
    if (f == nullptr) throw py::value_error("set_fluid_source: the scene has no [fluid]");
    std::vector<std::string> names;
    for (const auto& source : f->sources) names.push_back(source.name);
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end()) {
      throw py::value_error(
          names.empty()
              ? std::string("set_fluid_source: the scene has no [[fluid.source]]")
              : fmt::format("set_fluid_source: no [[fluid.source]] named \"{}\" (the scene has: {})", name,
                            fmt::join(names, ", ")));
    }
    if (inflow.is_none() == pressure.is_none())
      throw py::value_error(
          "set_fluid_source: give one of inflow (m^3/s into the pore water, 2D per metre; negative out) and "
          "pressure (Pa, held in the source's cell)");
    const bool by_inflow = !inflow.is_none();
    TimeSeries series = read_schedule(by_inflow ? inflow : pressure, "set_fluid_source",
                                      by_inflow ? "the inflow" : "the pressure", false);
    series.start = sim().time;
    auto& source = f->sources[static_cast<std::size_t>(at - names.begin())];
    source.type = by_inflow ? FluidSourceType::inflow : FluidSourceType::pressure;
    source.value = series;
  }

  /// A side's or a patch's condition set between steps, as a stage's
  /// fluid.boundary.NAME = { type = ..., ... } does, a series counted from
  /// now (YADE's FlowEngine bndCondIsPressure and bndCondValue).
  void set_fluid_boundary(const std::string& name, const py::object& pressure, const py::object& flux,
                          bool no_flow) {
    PoreFluid<D>* f = fluid();
    if (f == nullptr) throw py::value_error("set_fluid_boundary: the scene has no [fluid]");
    std::vector<std::string> names(side_names, side_names + 2 * D);
    for (const auto& patch : f->patches) names.push_back(patch.name);
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end()) {
      throw py::value_error(fmt::format("set_fluid_boundary: no side or patch \"{}\" (the grid's: {})", name,
                                        fmt::join(names, ", ")));
    }
    const auto index = static_cast<std::size_t>(at - names.begin());
    if (index < 2 * D && f->grid.periodic[index / 2]) {
      throw py::value_error(fmt::format(
          "set_fluid_boundary: the scene is periodic along {}: the fluid grid's two {} sides are one face "
          "between its last and first cells, which takes no condition",
          "xyz"[index / 2], "xyz"[index / 2]));
    }
    if (static_cast<int>(!pressure.is_none()) + static_cast<int>(!flux.is_none()) +
            static_cast<int>(no_flow) !=
        1)
      throw py::value_error(
          "set_fluid_boundary: give one of pressure (Pa: drained at that excess pressure), flux (m/s: the "
          "Darcy "
          "velocity into the grid) and no_flow=True");
    FluidBoundary b;
    if (no_flow) {
      b.type = FluidBoundaryType::no_flow;
    } else {
      const bool drained = !pressure.is_none();
      b.type = drained ? FluidBoundaryType::drained : FluidBoundaryType::flux;
      b.value = read_schedule(drained ? pressure : flux, "set_fluid_boundary",
                              drained ? "the pressure" : "the flux", false);
    }
    b.value.start = sim().time;
    if (b.type == FluidBoundaryType::drained && f->uniform_pressure) {
      // Drained, the one cell's pressure varies and its gradient stiffens
      // the grains: the step the scene took without that must still do.
      const double critical = fluid_step_with_gradient();
      if (sim().time_step > critical) {
        throw py::value_error(fmt::format(
            "set_fluid_boundary: draining \"{}\" lets the one cell's pressure vary, and its gradient "
            "stiffens the grains: the critical step falls to {:.4g} s, below the scene's time step {:.4g} s "
            "(taken for a sealed cell); drain it in the scene instead, or through a [[fluid.source]]",
            name, critical, sim().time_step));
      }
      f->uniform_pressure = false;
    }
    if (index < 2 * D) {
      f->sides[index] = b;
    } else {
      f->patches[index - 2 * D].condition = b;
    }
  }

  /// The particles' critical step now, with the pore water's stiffness and
  /// drag if any (what "auto" took its safety factor of at load).
  [[nodiscard]] double critical_step() {
    const double dry = sim().critical_time_step();
    return fluid() != nullptr ? fluid()->critical_time_step(sim().particles, dry) : dry;
  }

  /// A new time step between steps, checked as the scene's own.
  void set_time_step(double dt) {
    if (!(std::isfinite(dt) && dt > 0.0))
      throw py::value_error(fmt::format("time_step: give a step in seconds, > 0 (not {})", dt));
    const double critical = critical_step();
    if (dt > critical) {
      throw py::value_error(fmt::format(
          "time_step: {:.4g} s is above the critical step of the particles as they are now, {:.4g} s (the "
          "contacts'{}); give at most that",
          dt, critical, fluid() != nullptr ? ", with the pore water's stiffness and drag" : ""));
    }
    if (fluid() != nullptr && since_update_ != 0) {
      throw py::value_error(fmt::format(
          "time_step: the pore fluid steps every {} DEM steps and {} have gone since its last step, which "
          "it takes at the step they were made with; step({}) to its next step first",
          fluid()->steps_per_update, since_update_, fluid()->steps_per_update - since_update_));
    }
    sim().time_step = dt;
  }

  /// The pore fluid's critical step with the water's stiffness against the
  /// grains counted, as if its pressure could vary.
  [[nodiscard]] double fluid_step_with_gradient() {
    return fluid()->critical_time_step(sim().particles, sim().critical_time_step(), true);
  }

  /// A servo's cycle = {'amplitude': N or Pa, 'frequency': Hz, 'phase':
  /// degrees (optional, 0)} about `target`, which it must not take below 0.
  static ServoCycle read_servo_cycle(const py::object& given, double target) {
    const std::string form =
        "give cycle = {'amplitude': the target's units, 'frequency': Hz, 'phase': degrees (optional, 0)}";
    if (!py::isinstance<py::dict>(given)) throw py::value_error("set_wall_servo: " + form);
    const auto d = given.cast<py::dict>();
    for (const auto& [key, value] : d) {
      const auto k = py::str(key).cast<std::string>();
      if (k != "amplitude" && k != "frequency" && k != "phase")
        throw py::value_error(fmt::format("set_wall_servo: cycle has no key '{}': {}", k, form));
    }
    if (!d.contains("amplitude") || !d.contains("frequency"))
      throw py::value_error("set_wall_servo: " + form);
    ServoCycle c;
    c.amplitude = d["amplitude"].cast<double>();
    c.frequency = d["frequency"].cast<double>();
    const double phase = d.contains("phase") ? d["phase"].cast<double>() : 0.0;
    if (!(std::isfinite(c.amplitude) && c.amplitude > 0.0 && c.amplitude <= target))
      throw py::value_error(fmt::format(
          "set_wall_servo: the cycle's amplitude must be > 0 and at most the target ({}), so that the target "
          "stays >= 0, got {}",
          target, c.amplitude));
    if (!(std::isfinite(c.frequency) && c.frequency > 0.0))
      throw py::value_error("set_wall_servo: the cycle's frequency must be > 0 Hz");
    if (!std::isfinite(phase)) throw py::value_error("set_wall_servo: the cycle's phase must be finite");
    c.phase = phase * std::numbers::pi / 180.0;
    return c;
  }

  /// Makes a wall a servo between steps, as a stage's walls.NAME = { servo
  /// = ... } does: one of target_force (N) and target_stress (Pa, a plane
  /// or cylinder whose loaded area the other walls bound), gain and
  /// max_speed; a box needs its direction (unless it is a servo already).
  void set_wall_servo(const std::string& name, double gain, double max_speed, const py::object& target_force,
                      const py::object& target_stress, const std::optional<std::vector<double>>& direction,
                      const py::object& cycle, const std::string& load) {
    auto& walls = sim().walls;
    auto& w = wall_named(name, "set_wall_servo");
    const std::size_t index = static_cast<std::size_t>(&w - walls.data());
    if (target_force.is_none() == target_stress.is_none()) {
      throw py::value_error(
          "set_wall_servo: give one of target_force (N, the load wanted on the wall) or target_stress (Pa, a "
          "plane's load over the cross-section the other walls bound)");
    }
    const bool by_stress = !target_stress.is_none();
    const TimeSeries schedule =
        read_schedule(by_stress ? target_stress : target_force, "set_wall_servo", "the target", true);
    // The least the target takes (a cycle must not take it below 0).
    const double target = *std::min_element(schedule.values.begin(), schedule.values.end());
    if (!(gain > 0.0) || !std::isfinite(gain))
      throw py::value_error(fmt::format("set_wall_servo: gain must be finite and > 0 m/(s N), got {}", gain));
    if (!(max_speed > 0.0) || !std::isfinite(max_speed))
      throw py::value_error(
          fmt::format("set_wall_servo: max_speed must be finite and > 0 m/s, got {}", max_speed));
    if (by_stress) {
      if (const LoadedArea a = loaded_area(walls, index, sim().periodic); !a.why_not.empty())
        throw py::value_error(
            fmt::format("set_wall_servo: wall '{}' has no loaded area: {}", name, a.why_not));
    }
    Vec<D> axis = w.servo_axis;
    if (w.is_solid_body()) {
      if (direction) {
        axis = as_vec<D>(*direction, "direction");
        if (!axis.allFinite() || axis.norm() == 0.0)
          throw py::value_error("set_wall_servo: direction must be finite and non-zero");
        axis.normalize();
      } else if (axis.norm() == 0.0) {
        throw py::value_error(
            fmt::format("set_wall_servo: box wall '{}' needs direction = [D numbers], the way it moves to "
                        "load the grains "
                        "more",
                        name));
      }
    } else if (direction) {
      throw py::value_error(
          w.is_cylinder()
              ? "set_wall_servo: a cylinder's servo changes its radius; direction is for box walls"
              : "set_wall_servo: a plane moves along its normal; direction is for box walls");
    }
    if (!w.is_cylinder() && w.spin != 0.0)
      throw py::value_error(fmt::format(
          "set_wall_servo: wall '{}' turns, and a servo moves a wall along a fixed direction: stop its turn "
          "first (set_wall_motion(\"{}\", angular_velocity=0))",
          name, name));
    if (w.oscillation.active())
      throw py::value_error(fmt::format(
          "set_wall_servo: wall '{}' oscillates, and a servo sets its place from its load: stop the "
          "oscillation first (set_wall_motion(\"{}\", oscillation=False))",
          name, name));
    // All checked: set.
    if (load != "grains" && load != "total")
      throw py::value_error(
          fmt::format("set_wall_servo: load must be 'grains' (the grains' push) or 'total' (and the pore "
                      "water's thrust), "
                      "got '{}'",
                      load));
    const auto* f = fluid();
    if (load == "total" && (f == nullptr || std::find(f->solid_walls.begin(), f->solid_walls.end(), index) ==
                                                f->solid_walls.end()))
      throw py::value_error(
          fmt::format("set_wall_servo: load 'total' adds the pore water's thrust, which only a wall that "
                      "displaces the fluid "
                      "takes, and wall '{}' does not",
                      name));
    ServoControl servo;
    servo.with_pore_water = load == "total";
    servo.by_stress = by_stress;
    servo.schedule = schedule;
    servo.schedule.start = sim().time;
    if (!cycle.is_none()) servo.cycle = read_servo_cycle(cycle, target);
    (by_stress ? servo.target_stress : servo.target_force) = servo.target_at(sim().time);
    servo.gain = gain;
    servo.max_speed = max_speed;
    w.motion = WallMotion::servo;
    w.servo = servo;
    w.servo_axis = axis;
  }

  /// `count` DEM steps, with a fluid step after every steps_per_update of
  /// them and the inlets' insertions when they are due, as a run takes them.
  void step(std::uint64_t count) {
    while (count > 0) {
      std::uint64_t run = std::min(count, kSignalCheckSteps);
      if (fluid() != nullptr)
        run = std::clamp<std::uint64_t>(static_cast<std::uint64_t>(fluid()->steps_per_update) - since_update_,
                                        1, run);
      {
        py::gil_scoped_release unlocked;
        run = std::min(run, insert_due_grains());
        // The last step keeps the forces it applies, for model.contacts.
        sim().record_contact_forces = true;
        sim().advance(run);
        since_update_ += run;
        if (fluid() != nullptr && since_update_ >= static_cast<std::uint64_t>(fluid()->steps_per_update))
          fluid_step();
      }
      count -= run;
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
  }

  /// The index of the particle numbered `number` (model.ids), or a
  /// ValueError naming the call.
  std::size_t particle_index(std::int64_t number, const char* call) {
    const auto& s = sim();
    const auto& p = s.particles;
    const std::size_t i = number >= 0 && number <= std::numeric_limits<std::uint32_t>::max()
                              ? p.index_of(static_cast<std::uint32_t>(number))
                              : p.size();
    if (i == p.size())
      throw py::value_error(
          fmt::format("{}: there is no particle {} (the numbers are model.ids: {} particles{})", call, number,
                      p.size(), s.removed_count > 0 ? ", some removed outside the [domain]" : ""));
    return i;
  }

  /// A clump's member moves with its clump: it cannot be set on its own.
  void refuse_clump_member(std::size_t i, std::int64_t number, const char* call) {
    if (sim().particles.fixed[i] != ParticleData<D>::clump_member) return;
    throw py::value_error(
        fmt::format("{}: particle {} is a member of clump {}, which moves it as a rigid body: it cannot be "
                    "set on its own",
                    call, number, sim().clumps.clump_of[i]));
  }

  /// Fixes a particle (it keeps its velocity, driven, as the scene's fixed
  /// grains) or frees it (its mass and inertia from its material, its
  /// critical time step checked as add_particle's), between steps: YADE's
  /// blockedDOFs, PFC's ball fix. The kinetic energy it takes out of the
  /// free grains' or brings in is external work in the energy budget.
  void set_particle_fixed(std::int64_t number, bool fixed) {
    auto& s = sim();
    auto& p = s.particles;
    const std::size_t i = particle_index(number, "set_particle_fixed");
    refuse_clump_member(i, number, "set_particle_fixed");
    if ((p.fixed[i] != 0) == fixed) return;
    auto kinetic = [&] {
      return 0.5 * p.velocity[i].squaredNorm() / p.inv_mass[i] +
             0.5 * p.angular_velocity[i].squaredNorm() / p.inv_inertia[i];
    };
    // The force the next step's first half kick uses is the last
    // evaluation's, which counts a free grain's weight and not a fixed
    // one's: it changes with it.
    const double m = ParticleData<D>::mass_of(s.materials[p.material[i]].density, p.radius[i]);
    if (fixed) {
      if (s.energy.started) s.energy.external_work -= kinetic();
      p.force[i] -= m * s.gravity;
      p.inv_mass[i] = 0.0;
      p.inv_inertia[i] = 0.0;
      p.fixed[i] = 1;
      return;
    }
    p.inv_mass[i] = 1.0 / m;
    p.inv_inertia[i] = 1.0 / (inertia_factor<D> * m * p.radius[i] * p.radius[i]);
    p.fixed[i] = 0;
    const double critical = critical_step();
    if (s.time_step > critical) {
      p.inv_mass[i] = 0.0;
      p.inv_inertia[i] = 0.0;
      p.fixed[i] = 1;
      throw py::value_error(fmt::format(
          "set_particle_fixed: particle {} free would need a time step of at most {:.4g} s; the scene's is "
          "{:.4g} s",
          number, critical, s.time_step));
    }
    p.force[i] += m * s.gravity;
    if (s.energy.started) s.energy.external_work += kinetic();
  }

  /// A particle's velocity and angular velocity set between steps (YADE's
  /// state.vel and state.angVel, PFC's ball velocity and spin). A free
  /// grain then moves on from it; a fixed one keeps it (a grain driven at
  /// a set velocity). The kinetic energy it gives a free grain is work done
  /// on it from outside, which the energy budget counts as external work.
  void set_particle_velocity(std::int64_t number, const std::optional<std::vector<double>>& velocity,
                             const py::object& angular_velocity) {
    auto& s = sim();
    auto& p = s.particles;
    const std::size_t i = particle_index(number, "set_particle_velocity");
    refuse_clump_member(i, number, "set_particle_velocity");
    if (!velocity && angular_velocity.is_none())
      throw py::value_error(
          "set_particle_velocity: give velocity = [D numbers] (m/s) and or angular_velocity (rad/s: a number "
          "in 2D, counter-clockwise; [wx, wy, wz] in 3D)");
    Vec<D> v = p.velocity[i];
    AngVec<D> w = p.angular_velocity[i];
    if (velocity) {
      v = as_vec<D>(*velocity, "set_particle_velocity: velocity");
      if (!v.allFinite()) throw py::value_error("set_particle_velocity: velocity must be finite, m/s");
    }
    if (!angular_velocity.is_none()) {
      const bool number_given =
          py::isinstance<py::float_>(angular_velocity) || py::isinstance<py::int_>(angular_velocity);
      if constexpr (D == 2) {
        if (!number_given)
          throw py::value_error(
              "set_particle_velocity: a disc turns in the plane: give angular_velocity as a number, rad/s, "
              "counter-clockwise");
        w[0] = angular_velocity.cast<double>();
      } else {
        if (number_given || !py::isinstance<py::sequence>(angular_velocity))
          throw py::value_error(
              "set_particle_velocity: a sphere's angular_velocity is a vector: give [wx, wy, wz], rad/s");
        w = as_vec<3>(angular_velocity.cast<std::vector<double>>(),
                      "set_particle_velocity: angular_velocity");
      }
      if (!w.allFinite())
        throw py::value_error("set_particle_velocity: angular_velocity must be finite, rad/s");
    }
    if (s.energy.started && p.inv_mass[i] > 0.0) {
      auto kinetic = [&](const Vec<D>& u, const AngVec<D>& spin) {
        return 0.5 * u.squaredNorm() / p.inv_mass[i] + 0.5 * spin.squaredNorm() / p.inv_inertia[i];
      };
      s.energy.external_work += kinetic(v, w) - kinetic(p.velocity[i], p.angular_velocity[i]);
    }
    p.velocity[i] = v;
    p.angular_velocity[i] = w;
  }

  /// A free particle added between steps (YADE's O.bodies.append, PFC's
  /// ball create), checked as an inlet's grains are; returns its id.
  std::uint32_t add_particle(const std::vector<double>& position, double radius, const std::string& material,
                             const std::vector<double>& velocity) {
    auto& s = sim();
    const Vec<D> x = as_vec<D>(position, "position");
    const Vec<D> v = velocity.empty() ? Vec<D>::Zero() : as_vec<D>(velocity, "velocity");
    if (!x.allFinite() || !v.allFinite())
      throw py::value_error("add_particle: position and velocity must be finite");
    if (!(radius > 0.0 && std::isfinite(radius)))
      throw py::value_error(fmt::format("add_particle: radius must be > 0 m, got {}", radius));
    const std::uint16_t mat = grain_material(material, "add_particle");
    const Vec<D> reach = Vec<D>::Constant(radius);
    check_place(x, x - reach, x + reach, 2.0 * radius, "2 x radius", "add_particle");
    const Added before = added_so_far();
    s.add_particle(x, radius, mat, v);
    check_critical_step(before, false, fmt::format("add_particle: a grain of radius {} m", radius));
    return s.particles.id.back();
  }

  /// A clump added between steps (YADE's O.bodies.appendClumped, PFC's
  /// clump create): its members given where they stand, [x, y, (z,) r]
  /// each, checked as add_particle's grain, its centre of mass as the
  /// grain's centre; returns its members' numbers.
  std::vector<std::uint32_t> add_clump(const std::vector<std::vector<double>>& members,
                                       const std::string& material, const std::vector<double>& velocity) {
    auto& s = sim();
    const char* form = D == 2 ? "[x, y, r]" : "[x, y, z, r]";
    if (members.empty())
      throw py::value_error(fmt::format("add_clump: give members = [{}, ...] (m), at least one", form));
    std::vector<Vec<D>> centres;
    std::vector<double> radii;
    Vec<D> lo = Vec<D>::Constant(std::numeric_limits<double>::infinity());
    Vec<D> hi = -lo;
    for (std::size_t k = 0; k < members.size(); ++k) {
      const auto& m = members[k];
      const bool finite = std::all_of(m.begin(), m.end(), [](double e) { return std::isfinite(e); });
      if (m.size() != D + 1 || !finite || !(m[D] > 0.0))
        throw py::value_error(fmt::format("add_clump: member {} must be {}, finite, the radius > 0 m; got {}",
                                          k, form, fmt::join(m, ", ")));
      centres.push_back(Eigen::Map<const Vec<D>>(m.data()));
      radii.push_back(m[D]);
      lo = lo.cwiseMin(centres.back() - Vec<D>::Constant(m[D]));
      hi = hi.cwiseMax(centres.back() + Vec<D>::Constant(m[D]));
    }
    const Vec<D> v = velocity.empty() ? Vec<D>::Zero() : as_vec<D>(velocity, "velocity");
    if (!v.allFinite()) throw py::value_error("add_clump: velocity must be finite");
    const std::uint16_t mat = grain_material(material, "add_clump");
    ClumpShape<D> shape;
    try {
      shape = make_clump_shape<D>(centres, radii);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(fmt::format("add_clump: {}", e.what()));
    }
    // Placed as it stands, its members where they were given.
    const auto [size, x] = clump_as_given<D>(shape, centres[0], radii[0]);
    const double largest = *std::max_element(radii.begin(), radii.end());
    check_place(x, lo, hi, std::max(2.0 * largest, size),
                "the larger of 2 x its largest radius and its reach", "add_clump");
    const Added before = added_so_far();
    s.add_clump(shape, size, x, ClumpShape<D>::identity_orientation(), mat, v);
    check_critical_step(before, true, "add_clump: the clump");
    return {s.particles.id.begin() + static_cast<std::ptrdiff_t>(before.particles), s.particles.id.end()};
  }

 private:
  /// A material the scene's grains use, by name: their contacts with
  /// everything they can meet were checked when it loaded.
  std::uint16_t grain_material(const std::string& material, const char* call) {
    auto& s = sim();
    std::vector<bool> used(s.materials.size(), false);
    for (auto m : s.particles.material) used[m] = true;
    for (const auto& in : scene_.inlets) used[in.material] = true;
    std::string allowed;
    for (std::size_t m = 0; m < s.materials.size(); ++m) {
      if (!used[m]) continue;
      allowed += (allowed.empty() ? "'" : ", '") + s.materials[m].name + "'";
      if (s.materials[m].name == material) return static_cast<std::uint16_t>(m);
    }
    throw py::value_error(fmt::format("{}: material '{}' is not one the scene's grains use ({})", call,
                                      material, allowed.empty() ? "none" : allowed));
  }

  /// A new grain's place: its centre x inside the [domain] and the period
  /// (the period longer than 2 x (span + skin)), its box [lo, hi] outside
  /// the fluid grid.
  void check_place(const Vec<D>& x, const Vec<D>& lo, const Vec<D>& hi, double span, const char* span_text,
                   const char* call) {
    auto& s = sim();
    for (int k = 0; k < D; ++k) {
      if (s.has_domain && (x[k] < s.domain_lower[k] || x[k] > s.domain_upper[k]))
        throw py::value_error(fmt::format("{}: the centre is outside the [domain] along {}", call, "xyz"[k]));
      const auto& cell = s.periodic;
      if (cell.periodic[k] && (x[k] < cell.lower[k] || x[k] >= cell.lower[k] + cell.length[k]))
        throw py::value_error(fmt::format("{}: the centre is outside the period along {}", call, "xyz"[k]));
      if (cell.periodic[k] && !(cell.length[k] > 2.0 * (span + s.skin)))
        throw py::value_error(
            fmt::format("{}: the period along {} must exceed 2 x ({} + skin)", call, "xyz"[k], span_text));
    }
    // As an inlet's box: outside the grid, or its water would be
    // compressed at once by the grain's volume.
    if (fluid() != nullptr && !box_beside<D>(lo, hi, fluid()->grid.origin, fluid()->grid.upper(), s.periodic))
      throw py::value_error(fmt::format(
          "{}: the grain must lie outside the fluid grid (a grain that appeared in a cell would compress its "
          "pore water at once); place it above the grid and let it fall in",
          call));
  }

  /// What the simulation had added before a grain or clump was added.
  struct Added {
    std::size_t particles;
    std::uint64_t count;
    double mass;
    double kinetic;
  };
  Added added_so_far() {
    const auto& s = sim();
    return {s.particles.size(), s.inserted_count, s.inserted_mass, s.energy.inserted_kinetic};
  }

  /// Takes back what was added since `before` (a clump if `clump`: the
  /// last one) if its critical step is below the time step.
  void check_critical_step(const Added& before, bool clump, const std::string& what) {
    auto& s = sim();
    const double critical = critical_step();
    if (s.time_step <= critical) return;
    std::vector<std::uint32_t> keep(before.particles);
    for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = static_cast<std::uint32_t>(i);
    s.particles.permute(keep);
    s.inserted_count = before.count;
    s.inserted_mass = before.mass;
    s.energy.inserted_kinetic = before.kinetic;
    if (clump) {
      std::vector<std::uint8_t> kept(s.clumps.size(), 1);
      kept.back() = 0;
      s.clumps.keep(kept);
      s.clumps.refresh(s.particles);
    }
    throw py::value_error(
        fmt::format("{} would need a time step of at most {:.4g} s; the scene's is {:.4g} s", what, critical,
                    s.time_step));
  }

  /// The inlets' insertions due now, as a run makes them; returns the
  /// steps to the next one (as many as there may be when none is coming).
  std::uint64_t insert_due_grains() {
    auto& sim = this->sim();
    insert_all_due(scene_.inlets, sim);
    // As the run counts: one step short of the predicted crossing, then
    // step by step, so that rounding in the clock cannot skip it.
    const double dt = sim.time_step;
    const double ahead = std::floor((next_insertion_time(scene_.inlets) - 0.5 * dt - sim.time) / dt) - 1.0;
    return ahead >= 1.0 ? static_cast<std::uint64_t>(std::min(ahead, 1e18)) : 1;
  }

  void fluid_step() {
    darcydem::fluid_step(sim(), *fluid(), since_update_);
    since_update_ = 0;
  }

  /// The run's state as a checkpoint holds it, by reference: the model's
  /// position (the stage applied last, the steps since, the DEM steps
  /// since the last fluid step) in `position`.
  RunState<D> run_state(RunPosition& position) {
    return RunState<D>{position,   sim(),      scene_.inlets, fluid(),    analysis_ ? &*analysis_ : nullptr,
                       series_[0], series_[1], series_[2],    series_[3], series_[4]};
  }

 public:
  /// Writes the model's whole state to `path` (YADE's O.save): the
  /// program's checkpoint format, which darcydem.load(scene,
  /// checkpoint=path) reads back into a model of the same scene file.
  void save(const std::string& path) {
    RunPosition position;
    position.stage = stage_;
    position.stage_steps = sim().steps - stage_start_step_;
    position.since_update = since_update_;
    position.probes_bytes = saved_by_model;  // no output directory to go on with
    write_checkpoint(path, scene_, run_state(position));
  }

  /// Loads a checkpoint of this scene over the model (YADE's O.load): one a
  /// model saved, or one an interrupted `darcydem run` left in its output
  /// directory. The model goes on from its state: its time, grains, walls,
  /// pore fluid and the stage under way, with that stage's settings.
  void restore(const std::string& path) {
    RunPosition position;
    read_checkpoint(path, scene_, run_state(position));  // darcydem.CheckpointError if it does not fit
    stage_ = static_cast<std::size_t>(position.stage);
    stage_start_step_ = sim().steps - position.stage_steps;
    since_update_ = position.since_update;
    sim().measure_contact_forces = true;
  }

 private:
  Scene<D> scene_;
  /// The [[contact]]s' Coulomb coefficients as the scene gives them,
  /// before any stage: set_friction gives friction only to pairs that
  /// have it there, as a stage's contacts entry may (the time step counts
  /// the tangential spring's turning only for them).
  std::vector<double> contact_frictions_;
  std::uint64_t since_update_ = 0;  ///< DEM steps since the last fluid step
  std::size_t stage_ = 0;           ///< the stage applied last (the first at the start)
  std::uint64_t stage_start_step_ = 0;
  /// What a run's checkpoint holds besides: its seepage-column analysis
  /// and its VTK series (a model writes neither, but keeps them to save).
  std::optional<SeepageColumnAnalysis<D>> analysis_ =
      scene_.seepage_column
          ? std::optional<SeepageColumnAnalysis<D>>(std::in_place, *scene_.seepage_column, scene_)
          : std::nullopt;
  std::array<PvdSeries, 5> series_{PvdSeries(""), PvdSeries(""), PvdSeries(""), PvdSeries(""), PvdSeries("")};
};

/// The pore fluid of a model, read through it (it lives as long as the model).
template <int D>
struct FluidView {
  py::object owner;  ///< keeps the model alive
  PoreFluid<D>* fluid = nullptr;
};

/// A Python value as TOML text, for a scene override: bool, int, float,
/// str (a TOML string), list or tuple (an array), dict (an inline table),
/// and numpy's arrays and scalars (as their tolist()).
std::string toml_text(const py::handle& v, const std::string& path) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(v)) return py::str(v).cast<std::string>();
  if (py::isinstance<py::str>(v)) return quoted(v.cast<std::string>());
  // A numpy array or scalar: as the Python values it holds.
  if (py::hasattr(v, "tolist") && !py::isinstance<py::str>(v)) return toml_text(v.attr("tolist")(), path);
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    std::string out;
    for (const auto& item : v) out += (out.empty() ? "" : ", ") + toml_text(item, path);
    return "[" + out + "]";
  }
  if (py::isinstance<py::dict>(v)) {
    std::string out;
    for (const auto& [key, item] : v.cast<py::dict>()) {
      out += fmt::format("{}{} = {}", out.empty() ? "" : ", ", toml_text(key, path), toml_text(item, path));
    }
    return "{ " + out + " }";
  }
  if (py::hasattr(v, "__float__")) {
    const double x = v.cast<double>();
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    // The shortest text that reads back to x, with a point so that TOML
    // takes it as a float.
    const std::string text = fmt::format("{}", x);
    return text.find_first_of(".e") == std::string::npos ? text + ".0" : text;
  }
  throw py::value_error(fmt::format("set: the value for '{}' is a {}; give a number, str, bool, list or dict",
                                    path, py::str(py::type::of(v).attr("__name__")).cast<std::string>()));
}

/// The `set` argument of load and run, {PATH: value}, as `--set PATH=VALUE`
/// strings (scene/scene_overrides.hpp).
std::vector<std::string> scene_overrides(const std::optional<py::dict>& set) {
  std::vector<std::string> out;
  if (!set) return out;
  for (const auto& [key, value] : *set) {
    if (!py::isinstance<py::str>(key))
      throw py::value_error("set: its keys are dotted paths, e.g. {'fluid.bulk_modulus': 1e5}");
    const auto path = key.cast<std::string>();
    out.push_back(path + "=" + toml_text(value, path));
  }
  return out;
}

/// Reads and parses the scene file, applies the overrides, then calls
/// f.template operator()<D>(root, file, text).
template <class F>
py::object with_scene(const std::string& file, const std::vector<std::string>& overrides, F&& f) {
  std::string text;
  toml::table root = parse_toml_file(file, text);
  apply_scene_overrides(root, overrides, file, text);
  const int dim = scene_dimension(root, file);
  return dim == 2 ? f.template operator()<2>(root, file, text) : f.template operator()<3>(root, file, text);
}

/// The one process-wide flag a signal handler may set, as in the program.
std::atomic<bool>& interrupt_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}

extern "C" void on_interrupt(int) { interrupt_flag().store(true); }

template <int D>
py::dict run_one(Scene<D>& scene, RunOptions options) {
  interrupt_flag().store(false);
  options.interrupt = &interrupt_flag();
  // SIGINT stops the run between steps, as in the program; Python's own
  // handler is back once the run ends.
  auto* previous = std::signal(SIGINT, on_interrupt);
  RunSummary summary;
  try {
    py::gil_scoped_release unlocked;
    summary = run_scene<D>(scene, options);
  } catch (...) {
    std::signal(SIGINT, previous);
    throw;
  }
  std::signal(SIGINT, previous);
  py::dict d;
  d["steps"] = summary.steps;
  d["simulated_time"] = summary.simulated_time;
  d["wall_time"] = summary.wall_time;
  d["status"] = summary.interrupted ? "interrupted" : "completed";
  d["checkpoint_written"] = summary.checkpoint_written;
  d["stages_completed"] = summary.stages_completed;
  d["out"] = options.out_dir;
  if (summary.seepage_column) {
    const auto& s = *summary.seepage_column;
    py::dict c;
    c["uplift_rms_error"] = s.uplift_rms_error;
    c["pressure_max_error"] = s.pressure_max_error;
    c["passed"] = s.passed;
    d["seepage_column"] = c;
  }
  return d;
}

template <int D>
void bind_model(py::module_& m, const char* model_name, const char* fluid_name) {
  using M = Model<D>;
  using F = FluidView<D>;
  py::class_<F>(m, fluid_name, "The pore fluid of a model: its grid and cell fields (copies).")
      .def_property_readonly("cells", [](const F& f) { return f.fluid->grid.cells; })
      .def_property_readonly(
          "origin", [](const F& f) { return as_tuple<D>(f.fluid->grid.origin); },
          "lower corner of the grid, m")
      .def_property_readonly(
          "spacing", [](const F& f) { return as_tuple<D>(f.fluid->grid.spacing); },
          "cell size along each axis, m (nan along a graded axis: see faces)")
      .def_property_readonly(
          "faces",
          [](const F& f) {
            const auto& g = f.fluid->grid;
            py::list axes;
            for (int k = 0; k < D; ++k) {
              py::list at;
              for (int i = 0; i <= g.cells[k]; ++i) at.append(g.face_at(k, i));
              axes.append(at);
            }
            return axes;
          },
          "the faces' coordinates along each axis (cells + 1 each), m, uniform or graded")
      .def_property_readonly(
          "pressure", [](const F& f) { return cell_field<D>(f.fluid->grid, f.fluid->pressure(), 1); },
          "excess pore pressure per cell, Pa, indexed [i, j(, k)]")
      .def_property_readonly(
          "porosity", [](const F& f) { return cell_field<D>(f.fluid->grid, f.fluid->porosity(), 1); },
          "porosity per cell: 1 - (grains' + walls' volume) / cell volume")
      .def_property_readonly(
          "solid_volume", [](const F& f) { return cell_field<D>(f.fluid->grid, f.fluid->solid_volume(), 1); },
          "the grains' volume in each cell, m^3 (2D: per metre), exact")
      .def_property_readonly(
          "wall_volume", [](const F& f) { return cell_field<D>(f.fluid->grid, f.fluid->wall_volume(), 1); },
          "the volume of the walls that displace the fluid in each cell, m^3 (2D: per metre), exact (the "
          "planes' "
          "union where they meet)")
      .def_property_readonly(
          "permeability",
          [](const F& f) { return cell_field<D>(f.fluid->grid, f.fluid->permeability_field(), D); },
          "intrinsic permeability per cell and axis, m^2, indexed [i, j(, k), axis]")
      .def_property_readonly(
          "darcy_velocity",
          [](const F& f) { return cell_field<D>(f.fluid->grid, f.fluid->darcy_velocity(), D); },
          "Darcy (superficial) velocity per cell, m/s, the mean of its faces', indexed [i, j(, k), axis]")
      .def(
          "pressure_at",
          [](const F& f, const std::vector<double>& x) {
            return f.fluid->pressure_at(as_vec<D>(x, "point"));
          },
          py::arg("point"), "excess pore pressure at a point, Pa, between the cell centres")
      .def_property_readonly(
          "sources",
          [](const F& f) {
            py::list out;
            for (std::size_t i = 0; i < f.fluid->sources.size(); ++i) {
              const auto& source = f.fluid->sources[i];
              py::dict d;
              d["name"] = source.name;
              d["position"] = std::vector<double>(source.position.data(), source.position.data() + D);
              const auto c = f.fluid->grid.coords(f.fluid->source_cell(i));
              d["cell"] = std::vector<int>(c.begin(), c.end());
              d["type"] = source.type == FluidSourceType::inflow ? "inflow" : "pressure";
              d["inflow"] = f.fluid->source_inflow(i);
              d["radius"] = source.radius;
              d["well_pressure"] = f.fluid->well_pressure(i);
              d["well_index"] = f.fluid->well_index(i);
              d["drain"] = source.drain;
              d["open"] = !source.drain || f.fluid->drain_open(i);
              if (source.screened()) {
                d["screen"] = std::vector<double>{source.screen[0], source.screen[1]};
                py::list cells;
                const auto nodes = f.fluid->screen_well_indices(i);
                const auto inflows = f.fluid->screen_inflows(i);
                for (std::size_t k = 0; k < nodes.size(); ++k) {
                  const auto at = f.fluid->grid.coords(nodes[k].first);
                  cells.append(py::dict(py::arg("cell") = std::vector<int>(at.begin(), at.end()),
                                        py::arg("well_index") = nodes[k].second,
                                        py::arg("inflow") = inflows[k]));
                }
                d["screen_cells"] = cells;
              } else {
                d["screen"] = py::none();
              }
              out.append(d);
            }
            return out;
          },
          "the [[fluid.source]]s: name, position (m), the cell it feeds (indices), type ('inflow' or "
          "'pressure': what it imposes) and inflow, what it gave in the last fluid step, m^3/s (2D: per "
          "metre); radius, a well's, m (0: none), well_pressure, Pa, at its bore with a radius (its cell's "
          "plus inflow / well_index), else its cell's, and well_index, m^3/(s Pa) (0 without a radius); "
          "screen, a screened well's [from, to] along its screen_axis ('x', 'y' or 'z'), m (None for a point "
          "source), screen_cells, each cell it passes through in order along it: cell (indices), "
          "well_index and inflow, what that "
          "cell took from the bore in the last fluid step, m^3/s (they add up to the well's); drain, whether "
          "it takes water out only, and open, whether it stood open in the last fluid step (True for any "
          "other source)")
      .def_property_readonly(
          "balance",
          [](const F& f) {
            const FluidBalance& b = f.fluid->total_balance();
            py::dict d;
            d["inflow"] = b.inflow;
            d["stored"] = b.stored;
            d["pore_change"] = b.pore_change;
            d["imbalance"] = b.imbalance();
            d["gross"] = b.gross;
            return d;
          },
          "volumes since the start, m^3 (2D: per metre): inflow = stored + pore change + imbalance; "
          "gross: every term's magnitude summed step by step (each side's flow on its own), against which "
          "the imbalance (the pressure solve's residual and round-off) is measured");

  py::class_<M>(m, model_name, "A scene built from its file, stepped from Python.")
      .def_property_readonly("dimension", [](const M&) { return D; })
      .def_property_readonly("file", [](const M& s) { return s.scene().file; })
      .def_property_readonly(
          "time", [](const M& s) { return s.sim().time; }, "simulated time, s")
      .def_property(
          "time_step", [](const M& s) { return s.sim().time_step; }, &M::set_time_step,
          "s; set between steps (YADE's O.dt = ...): at most critical_time_step, and with a pore fluid that "
          "steps every M > 1 DEM steps, right after one of its steps")
      .def_property_readonly(
          "critical_time_step", &M::critical_step,
          "s: the critical step of the particles as they are now (the contacts', with the pore water's "
          "undrained stiffness and drag if any), of which \"auto\" took its safety_factor at load "
          "(YADE's PWaveTimeStep, PFC's timestep); inf if no particle is free to move")
      .def_property_readonly("steps", [](const M& s) { return s.sim().steps; })
      .def_property_readonly("stages", &M::stage_names, "the scene's stage names, in order")
      .def_property_readonly("particle_count", [](const M& s) { return s.sim().particles.size(); })
      .def_property_readonly(
          "positions",
          [](const M& s) { return per_particle<D>(s.sim().particles, s.sim().particles.position, D); },
          "particle centres, m, (N, D), in creation order")
      .def_property_readonly(
          "velocities",
          [](const M& s) { return per_particle<D>(s.sim().particles, s.sim().particles.velocity, D); },
          "particle velocities, m/s, (N, D), in creation order")
      .def_property_readonly(
          "angular_velocities",
          [](const M& s) {
            const auto& p = s.sim().particles;
            py::array_t<double> w = per_particle<D>(p, p.angular_velocity, rotation_dim<D>);
            return D == 2 ? py::array_t<double>(w.attr("reshape")(-1)) : w;
          },
          "particle angular velocities, rad/s, in creation order: (N,) counter-clockwise in 2D, (N, 3) in 3D")
      .def_property_readonly(
          "forces", [](const M& s) { return per_particle<D>(s.sim().particles, s.sim().particles.force, D); },
          "the resultant force on each particle at the last step, N (2D: per metre), (N, D), in creation "
          "order: its contacts', its weight, the pore water's force and any load, before damping (zero "
          "for a grain in equilibrium)")
      .def_property_readonly(
          "torques",
          [](const M& s) {
            const auto& p = s.sim().particles;
            py::array_t<double> t = per_particle<D>(p, p.torque, rotation_dim<D>);
            return D == 2 ? py::array_t<double>(t.attr("reshape")(-1)) : t;
          },
          "the contacts' moment on each particle about its centre at the last step, N m (2D: per metre), "
          "(N,) in 2D, (N, 3) in 3D, in creation order: their forces' and couples' (rolling resistance, "
          "a bond's moment)")
      .def_property_readonly(
          "contacts", [](const M& s) { return contact_arrays<D>(s.sim()); },
          "the contacts of the last step, one row per contact, sorted by particle number (YADE's "
          "O.interactions): particles (M, 2), the pair's numbers, the lower first, -1 second for a wall; "
          "wall (M,), the wall's index in model.walls, -1 between particles; point (M, D), m; normal "
          "(M, D), unit, from the first particle towards the second or the wall; overlap (M,), m "
          "(negative for a bond whose grains are apart); force (M, D), on the first particle, N (2D: per "
          "metre; on the second, its opposite); normal_force (M,), -force . normal, compression "
          "positive; shear_force (M, D), the force's part across the normal; bonded (M,); bending_moment "
          "and twisting_moment (M,), a bond's, N m")
      .def_property_readonly(
          "fluid_forces",
          [](const M& s) {
            const auto& p = s.sim().particles;
            const auto& f = s.sim().field_forces();
            if (f.size() == p.size()) return per_particle<D>(p, f, D);
            const std::vector<Vec<D>> none(p.size(), Vec<D>::Zero());  // no pore fluid: none acts
            return per_particle<D>(p, none, D);
          },
          "the pore fluid's force on each particle as the last step applied it (buoyancy, pressure "
          "gradient and drag), N (2D: per metre), (N, D), in creation order; zero without a [fluid]")
      .def_property_readonly(
          "radii",
          [](const M& s) {
            const auto& p = s.sim().particles;
            return per_particle_values<double>(p, [&](std::size_t i) { return p.radius[i]; });
          },
          "particle radii, m, (N,), in creation order")
      .def_property_readonly(
          "ids",
          [](const M& s) {
            const auto& p = s.sim().particles;
            return per_particle_values<std::int64_t>(p, [&](std::size_t i) { return p.id[i]; });
          },
          "each row's particle number (its index in creation order), (N,), increasing; with a [domain] "
          "the numbers of the particles removed are missing")
      .def_property_readonly(
          "removed_count", [](const M& s) { return s.sim().removed_count; },
          "particles removed outside the [domain] so far")
      .def_property_readonly(
          "removed_mass", [](const M& s) { return s.sim().removed_mass; }, "their mass, kg (2D: per metre)")
      .def_property_readonly(
          "inserted_count", [](const M& s) { return s.sim().inserted_count; },
          "particles the [[inlet]]s have added so far")
      .def_property_readonly(
          "inserted_mass", [](const M& s) { return s.sim().inserted_mass; }, "their mass, kg (2D: per metre)")
      .def_property_readonly(
          "inlets",
          [](const M& s) {
            py::list out;
            for (const auto& in : s.scene().inlets) {
              py::dict d;
              d["name"] = in.name;
              d["active"] = in.active;
              d["inserted"] = in.inserted;
              d["particles"] = in.inserted_particles();
              d["mass"] = in.inserted_mass;
              d["exhausted"] = in.exhausted();
              d["next_time"] = in.active && !in.exhausted() ? py::cast(in.next_time) : py::none();
              d["short_of_room"] = in.short_events;
              d["clump"] = in.clump ? py::cast(in.clump_name) : py::none();
              out.append(d);
            }
            return out;
          },
          "the [[inlet]]s, a dict each: name, active, inserted (grains, or clumps), particles (a clump's "
          "members each), mass (kg; 2D per metre), exhausted (it has added all it may), next_time (s, its "
          "next insertion; None when inactive or exhausted), short_of_room (insertions that found no room "
          "for all that was due), clump (its template's name, or None)")
      .def("set_inlet_active", &M::set_inlet_active, py::arg("name"), py::arg("active"),
           "starts an [[inlet]] (its first insertion at once) or stops it, between steps, as a stage's "
           "inlets.NAME = { active = ... }")
      .def(
          "make_bonds", [](M& s, double gap) { return s.sim().make_bonds(gap); }, py::arg("gap") = 0.0,
          "bonds every pair that touches or is less than gap (m, below the skin) apart whose [[contact]] has "
          "a "
          "'bond' (as a stage's make_bonds = true, bond_gap); returns how many were bonded now")
      .def_property_readonly(
          "bond_count", [](const M& s) { return s.sim().bond_count(); }, "contact bonds intact now")
      .def_property_readonly(
          "broken_bonds", [](const M& s) { return s.sim().broken_bonds; }, "contact bonds broken so far")
      .def_property(
          "gravity", [](const M& s) { return as_tuple<D>(s.sim().gravity); },
          [](M& s, const std::vector<double>& g) { s.sim().gravity = as_vec<D>(g, "gravity"); }, "m/s^2")
      .def_property_readonly(
          "clumps",
          [](const M& s) {
            const auto& c = s.sim().clumps;
            const auto& p = s.sim().particles;
            py::list out;
            for (std::size_t k = 0; k < c.size(); ++k) {
              py::dict d;
              d["position"] = as_tuple<D>(c.position[k]);
              d["velocity"] = as_tuple<D>(c.velocity[k]);
              if constexpr (D == 2) {
                d["angle"] = c.orientation[k][0];
                d["angular_velocity"] = c.angular_velocity[k][0];
                d["inertia"] = c.inertia[k][0];
              } else {
                d["orientation"] = py::make_tuple(c.orientation[k][0], c.orientation[k][1],
                                                  c.orientation[k][2], c.orientation[k][3]);
                d["angular_velocity"] = as_tuple<D>(c.angular_velocity[k]);
                d["inertia"] = as_tuple<D>(c.inertia[k]);
              }
              d["mass"] = c.mass[k];
              d["force"] = as_tuple<D>(c.force[k]);
              py::list members;
              for (std::uint32_t m = c.first[k]; m < c.first[k + 1]; ++m)
                members.append(p.id[c.member_index[m]]);
              d["members"] = members;
              out.append(d);
            }
            return out;
          },
          "the clumps (rigid bodies of particles), a dict each: position (its centre of mass, m), velocity, "
          "orientation (3D: a unit quaternion w, x, y, z; 2D: angle, rad), angular_velocity (rad/s), mass "
          "(kg), "
          "inertia (principal moments, kg m^2), force (N: the last resultant), members (particle numbers, "
          "model.ids)")
      .def_property_readonly(
          "walls",
          [](const M& s) {
            py::list walls;
            for (const auto& w : s.sim().walls) {
              py::dict d;
              d["name"] = w.name;
              d["point"] = as_tuple<D>(w.point);
              d["force"] = as_tuple<D>(w.force);
              d["water_force"] = as_tuple<D>(w.water_force);
              d["shape"] = w.is_cylinder() ? "cylinder" : w.is_box() ? "box" : w.is_mesh() ? "mesh" : "plane";
              d["velocity"] = as_tuple<D>(w.translation_velocity());
              if (D == 3 && !w.is_cylinder()) {
                d["angular_velocity"] = as_tuple<D>(Vec<D>(w.spin * w.axis));
                d["rotation_centre"] = as_tuple<D>(w.pivot);
              } else {
                d["angular_velocity"] = w.spin;
                if (!w.is_cylinder()) d["rotation_centre"] = as_tuple<D>(w.pivot);
              }
              if (w.is_mesh()) {
                d["facets"] = w.mesh->triangle.size();
                d["area"] = w.mesh->area();
              }
              if (w.is_solid_body()) {
                py::list axes;
                for (int k = 0; k < D; ++k) axes.append(as_tuple<D>(Vec<D>(w.axes.col(k))));
                d["axes"] = axes;
              }
              if (w.is_plane()) d["normal"] = as_tuple<D>(w.normal);
              d["oscillation"] =
                  w.oscillation.active()
                      ? py::object(py::dict(py::arg("amplitude") = as_tuple<D>(w.oscillation.amplitude),
                                            py::arg("frequency") = w.oscillation.frequency,
                                            py::arg("phase") = w.oscillation.phase * 180.0 / std::numbers::pi,
                                            py::arg("start") = w.oscillation.start))
                      : py::object(py::none());
              d["torque"] = w.torque;
              if (w.is_cylinder()) {
                d["radius"] = w.radius;
                d["radial_load"] = w.radial_load;
              }
              const double stress = wall_stress(s.sim().walls, walls.size(), s.sim().periodic);
              d["stress"] = std::isnan(stress) ? py::object(py::none()) : py::object(py::float_(stress));
              d["servo"] = servo_dict(w);
              walls.append(d);
            }
            return walls;
          },
          "each wall's name, point (a box: its centre; a cylinder: its centre, on its axis), m, the force "
          "the particles exert on it, N, "
          "on a box that displaces the fluid the pore water's thrust, N (zero on other walls), its shape "
          "('plane', 'box', 'cylinder'), velocity, m/s, and a cylinder's angular_velocity about its axis, "
          "rad/s, torque, the particles' moment on it about its axis, N m (the probe wall_torque; "
          "zero on other walls), radius, m, and radial_load, the sum of the particles' pushes normal to "
          "it, N (cylinders only); stress, a plane's load over the cross-section the other walls bound or "
          "a cylinder's over its lateral surface, Pa "
          "(the probe wall_stress; None where they bound none); servo, None or {'target_force': N} or "
          "{'target_stress': Pa} (the target now), with 'cycle': {'amplitude', 'frequency' (Hz), 'phase' "
          "(degrees)} where it cycles; oscillation, None or {'amplitude': m, 'frequency': Hz, 'phase': "
          "degrees, "
          "'start': s}")
      .def("set_wall_servo", &M::set_wall_servo, py::arg("name"), py::arg("gain"), py::arg("max_speed"),
           py::arg("target_force") = py::none(), py::arg("target_stress") = py::none(),
           py::arg("direction") = py::none(), py::arg("cycle") = py::none(), py::arg("load") = "grains",
           "makes a wall a servo between steps, as a stage's walls.NAME = { servo = ... } does: one of "
           "target_force (N) or target_stress (Pa: a plane, its load over the cross-section the other walls "
           "bound, as a triaxial test's; a cylinder, over its lateral surface; taken again at every step; a "
           "cylinder's servo changes its radius), each a number or {'times': [s from now], 'values': [...]} "
           "(a ramp or schedule, piecewise linear, held after its last point), gain (m/(s N)), max_speed "
           "(m/s); a box "
           "moves along direction = [D numbers]; cycle = {'amplitude': the target's units, 'frequency': Hz, "
           "'phase': degrees (optional, 0)} adds amplitude sin(2 pi f t + phase) to the target, t from now "
           "(cyclic loading); load = 'grains' (their push) or 'total' (with the pore water's thrust, on a "
           "wall that displaces the fluid)")
      .def("set_friction", &M::set_friction, py::arg("materials"), py::arg("friction"),
           "sets the Coulomb coefficient of a pair of materials between steps, as a stage's contacts = [{ "
           "materials = [...], friction = mu }] entry does: materials = ['sand', 'sand'] (a pair with a "
           "[[contact]]), friction >= 0, more than 0 only where the [[contact]] has friction (the time step "
           "counts the turning of the tangential spring only there); the contacts' tangential springs are "
           "held "
           "to it from the next step (YADE's compaction friction, PFC's contact property change)")
      .def("friction", &M::friction, py::arg("materials"),
           "the Coulomb coefficient of a pair of materials now, materials = ['sand', 'sand']")
      .def("set_fluid_boundary", &M::set_fluid_boundary, py::arg("name"), py::arg("pressure") = py::none(),
           py::arg("flux") = py::none(), py::arg("no_flow") = false,
           "sets a side's (x_min ... z_max) or a patch's condition between steps, as a stage's "
           "fluid.boundary.NAME does: one of pressure (Pa: drained at that excess pressure), flux (m/s: the "
           "Darcy velocity into the grid, negative out) and no_flow=True; pressure and flux each a number or "
           "{'times': [s from now], 'values': [...]}; draining a grid of one sealed cell, whose time step "
           "left the water's stiffness out, is refused if the step is then above the critical step")
      .def("set_fluid_source", &M::set_fluid_source, py::arg("name"), py::arg("inflow") = py::none(),
           py::arg("pressure") = py::none(),
           "sets a [[fluid.source]]'s condition between steps, as a stage's fluid.sources.NAME does: one of "
           "inflow (m^3/s into the pore water, 2D per metre, negative pumping out) and pressure (Pa, held in "
           "its cell), each a number or {'times': [s from now], 'values': [...]}")
      .def("set_wall_motion", &M::set_wall_motion, py::arg("name"), py::arg("velocity") = py::none(),
           py::arg("angular_velocity") = py::none(), py::arg("radial_velocity") = py::none(),
           py::arg("oscillation") = py::none(),
           "sets a wall's velocity, m/s (ending a servo); its angular_velocity, rad/s: a cylinder's about "
           "its axis (a number, right-handed about it), a plane's or box's about its rotation centre (3D: "
           "[wx, wy, wz]; 2D: a number, counter-clockwise); and a cylinder's radial_velocity, the rate of "
           "change of its radius, m/s (ending a servo); an oscillation, a harmonic translation on top of its "
           "motion from now on (a shaking table): {'amplitude': [D numbers] (m), 'frequency': Hz, 'phase': "
           "degrees (optional, 0)}, or False to stop it; between steps, as a stage's walls.NAME entry does")
      .def(
          "kinetic_energy", [](const M& s) { return s.sim().kinetic_energy(); }, "J")
      .def(
          "elastic_energy", [](const M& s) { return s.sim().elastic_energy(); },
          "J stored in the contacts' and bonds' springs (the probe elastic_energy)")
      .def(
          "gravitational_energy", [](const M& s) { return s.sim().gravitational_energy(); },
          "J, -sum m g.x, zero at the origin (the probe gravitational_energy)")
      .def_property_readonly(
          "cell",
          [](const M& s) -> py::object {
            const auto& sim = s.sim();
            for (int k = 0; k < D; ++k) {
              if (!sim.periodic.periodic[k]) return py::none();
            }
            const auto& m = sim.cell_motion;
            py::dict d;
            d["lower"] = as_tuple<D>(sim.periodic.lower);
            d["length"] = as_tuple<D>(sim.periodic.length);
            d["strain_rate"] = as_tuple<D>(m.strain_rate);
            py::list controls;
            for (int k = 0; k < D; ++k) controls.append(m.by_stress[k] ? "stress" : "strain_rate");
            d["controls"] = controls;
            d["target_stress"] = as_tuple<D>(m.target_stress);
            d["gain"] = m.gain;
            d["max_strain_rate"] = m.max_strain_rate;
            const auto stress = sim.cell_stress();
            py::list rows;
            for (int k = 0; k < D; ++k) rows.append(as_tuple<D>(Vec<D>(stress.row(k).transpose())));
            d["stress"] = rows;
            return d;
          },
          "the periodic cell (None unless every axis repeats): lower and length (m), strain_rate (1/s, as "
          "the last step took it), controls ('strain_rate' or 'stress' per axis), target_stress (Pa), gain "
          "(1/(Pa s)), max_strain_rate (1/s), stress (the contacts' mean stress over the cell, rows of a "
          "D x D tensor, Pa, compression positive: the probe cell_stress)")
      .def("set_cell", &M::set_cell, py::arg("x") = py::none(), py::arg("y") = py::none(),
           py::arg("z") = py::none(), py::arg("gain") = py::none(), py::arg("max_strain_rate") = py::none(),
           py::arg("load") = py::none(),
           "deforms the periodic cell from the next step on, as a stage's periodic_cell does: per axis "
           "{'strain_rate': 1/s} (negative: it shrinks) or {'stress': Pa} (compression positive, held by the "
           "servo, which needs gain, 1/(Pa s), and max_strain_rate, 1/s); axes not given keep theirs; load "
           "'total' makes the servo hold the contacts' stress plus the pore water's mean pressure, 'grains' "
           "the contacts' alone. The cell must repeat along every axis, and the scene have no walls, fluid "
           "sources or barriers, inlets, clumps or domain")
      .def_property(
          "fluid_drained",
          [](M& s) {
            if (s.fluid() == nullptr) throw py::value_error("fluid_drained: the scene has no [fluid]");
            return s.fluid()->drained;
          },
          [](M& s, bool on) {
            if (s.fluid() == nullptr) throw py::value_error("fluid_drained: the scene has no [fluid]");
            s.fluid()->drained = on;
          },
          "every cell open to water at zero excess pressure from the next fluid step on, as a stage's "
          "fluid.drained: the pore volume's change flows in or out where it happens")
      .def_property(
          "track_energy", [](const M& s) { return s.sim().track_energy; },
          [](M& s, bool on) { s.sim().track_energy = on; },
          "track the energy budget from the next step on (YADE's O.trackEnergy; the budget's probes turn it "
          "on): the step then accounts each force's work (up to a tenth more time on one thread); the motion "
          "is the same, bit for bit")
      .def(
          "energy",
          [](const M& s) {
            const auto& sim = s.sim();
            py::dict d;
            d["kinetic"] = sim.kinetic_energy();
            d["elastic"] = sim.elastic_energy();
            d["gravitational"] = sim.gravitational_energy();
            d["gravity_work"] = sim.energy.gravity_work;
            d["fluid_work"] = sim.energy.field_work;
            d["external_work"] = sim.energy.external_work;
            d["boundary_work"] = sim.energy.boundary_work;
            d["damping_dissipation"] = sim.energy.damping_dissipation();
            d["contact_dissipation"] = sim.contact_dissipation();
            d["inserted_kinetic"] = sim.energy.inserted_kinetic;
            d["removed_kinetic"] = sim.energy.removed_kinetic;
            d["unaccounted"] = sim.unaccounted_energy();
            return d;
          },
          "the energies now and the budget since tracking began, J (the probes of the same names): "
          "kinetic, elastic, gravitational; gravity_work, fluid_work, boundary_work (done on the grains), "
          "damping_dissipation, contact_dissipation (taken from them, the latter inferred: it closes the "
          "budget, kinetic + elastic + the two dissipations - the three works, at its start); "
          "inserted_kinetic, "
          "removed_kinetic (brought in by grains inlets added, taken out by grains the domain removed); "
          "unaccounted, the kinetic energy's change that none of these explains (round-off)")
      .def(
          "stress",
          [](const M& s, const std::vector<double>& lo, const std::vector<double>& hi) {
            const auto [a, b] = as_box<D>(lo, hi);
            return as_matrix<D>(s.sim().contact_stress(a, b));
          },
          py::arg("min"), py::arg("max"),
          "(D, D): the contacts' mean stress of the grains whose centres lie in the box, Pa, compression "
          "positive (the probe stress; with a pore fluid, the effective stress)")
      .def(
          "fabric",
          [](const M& s, const std::vector<double>& lo, const std::vector<double>& hi) {
            const auto [a, b] = as_box<D>(lo, hi);
            return as_matrix<D>(s.sim().contact_fabric(a, b));
          },
          py::arg("min"), py::arg("max"),
          "(D, D): Satake's fabric tensor of the contacts between grains of which one at least has its "
          "centre in the box, (1/N_c) sum n n^T, trace 1 (the probe fabric); NaN without a contact")
      .def(
          "unbalanced_force_ratio", [](M& s) { return s.sim().unbalanced_force_ratio(); },
          "mean unbalanced force / mean contact force of the last step")
      .def("apply_stage", &M::apply_stage, py::arg("name"),
           "applies a stage's settings (gravity, damping, walls, fluid conditions), as a run starts it")
      .def("add_particle", &M::add_particle, py::arg("position"), py::arg("radius"), py::arg("material"),
           py::arg("velocity") = std::vector<double>{},
           "adds a free particle between steps (its weight as its force, the others' contact histories kept) "
           "and returns its id; the material one the scene's grains use, the centre inside the [domain] and "
           "period, the grain outside the fluid grid, its critical time step above the scene's")
      .def("add_clump", &M::add_clump, py::arg("members"), py::arg("material"),
           py::arg("velocity") = std::vector<double>{},
           "adds a free clump between steps (YADE's appendClumped): members = [[x, y, (z,) r], ...] (m) "
           "where they stand, touching or overlapping (then the mass and inertia of their union); moving at "
           "velocity without spin; checked as add_particle's grain, its centre of mass as the grain's "
           "centre; returns its members' numbers (model.ids), and model.clumps lists it last")
      .def("set_particle_velocity", &M::set_particle_velocity, py::arg("particle"),
           py::arg("velocity") = py::none(), py::arg("angular_velocity") = py::none(),
           "sets a particle's velocity (m/s, D numbers) and or angular velocity (rad/s: 2D a number, "
           "counter-clockwise; 3D [wx, wy, wz]) between steps, particle by its number (model.ids): a free "
           "grain moves on from it (the kinetic energy it gains is external work in the energy budget), a "
           "fixed one keeps it")
      .def("set_particle_fixed", &M::set_particle_fixed, py::arg("particle"), py::arg("fixed") = true,
           "fixes a particle between steps (it keeps its velocity: set_particle_velocity drives it) or, "
           "fixed=False, frees it (its mass and inertia from its material; refused if it would need a "
           "shorter time step), particle by its number (model.ids); the kinetic energy it takes from or "
           "brings to the free grains is external work in the energy budget (YADE's blockedDOFs, PFC's ball "
           "fix)")
      .def_property_readonly(
          "fixed",
          [](const M& s) {
            const auto& p = s.sim().particles;
            return per_particle_values<bool>(p, [&](std::size_t i) { return p.fixed[i] != 0; });
          },
          "whether each particle is fixed, (N,), in creation order")
      .def("step", &M::step, py::arg("count") = 1,
           "advances count DEM steps, with the pore fluid's steps among them as in a run")
      .def("save", &M::save, py::arg("path"),
           "writes the model's whole state to path (YADE's O.save), in the program's checkpoint format: "
           "darcydem.load(scene, checkpoint=path) goes on from it, bit for bit, in a model of the same "
           "scene file")
      .def_property_readonly(
          "fluid",
          [](py::object self) -> py::object {
            M& s = self.cast<M&>();
            if (s.fluid() == nullptr) return py::none();
            return py::cast(F{self, s.fluid()});
          },
          "the pore fluid ([fluid]), or None");
}

}  // namespace
}  // namespace darcydem::python

PYBIND11_MODULE(darcydem, m) {
  using namespace darcydem::python;
  m.doc() = "darcydem: DEM of discs and spheres coupled with Darcy pore-fluid flow";
  m.attr("__version__") = darcydem::version_string;
  py::register_exception<darcydem::SceneError>(m, "SceneError", PyExc_ValueError);
  py::register_exception<darcydem::CheckpointError>(m, "CheckpointError", PyExc_RuntimeError);
  bind_model<2>(m, "Model2D", "Fluid2D");
  bind_model<3>(m, "Model3D", "Fluid3D");
  m.def(
      "load",
      [](const std::string& file, const std::optional<std::string>& checkpoint,
         const std::optional<py::dict>& set) {
        return with_scene(file, scene_overrides(set),
                          [&]<int D>(const toml::table& root, const std::string& f, const std::string& text) {
                            auto model = std::make_unique<Model<D>>(root, f, text);
                            if (checkpoint) model->restore(*checkpoint);
                            return py::cast(std::move(model));
                          });
      },
      py::arg("scene"), py::arg("checkpoint") = py::none(), py::kw_only(), py::arg("set") = py::none(),
      "builds a scene from its TOML file (checked as `darcydem check` does); raises SceneError on bad input. "
      "set = {'fluid.bulk_modulus': 1e5, 'wall.floor.velocity': [0.0, -0.1], 'stage.shear.duration': 0.2} "
      "changes it first, as `--set PATH=VALUE` does (a str is a TOML string, a list an array, a dict an "
      "inline table). "
      "With checkpoint = a file model.save wrote, or the checkpoint.bin an interrupted `darcydem run` of "
      "the same scene file left, the model goes on from that state (YADE's O.load)");
  m.def(
      "run",
      [](const std::string& file, const std::string& out, bool force, bool resume, double checkpoint_every,
         int threads, bool log, std::uint64_t stop_at_step, const std::optional<py::dict>& set) {
        if (force && resume) throw py::value_error("run: force and resume exclude each other");
        if (!force && !resume && !darcydem::output_dir_is_free(out))
          throw py::value_error(
              fmt::format("output directory '{}' is not empty; use force=True to write into it", out));
        if (threads < 0) throw py::value_error("run: threads must be >= 0 (0: all cores)");
        if (threads > 0) omp_set_num_threads(threads);
        darcydem::RunOptions options;
        options.out_dir = out;
        options.resume = resume;
        options.checkpoint_every = checkpoint_every;
        options.stop_at_step = stop_at_step;
        options.log = log ? &std::cerr : nullptr;  // the program's run log and progress lines
        const auto overrides = scene_overrides(set);
        return with_scene(file, overrides,
                          [&]<int D>(const toml::table& root, const std::string& f, const std::string& text) {
                            auto scene = darcydem::build_scene<D>(root, f, text);
                            scene.overrides = overrides;
                            return py::object(run_one<D>(scene, options));
                          });
      },
      py::arg("scene"), py::arg("out"), py::arg("force") = false, py::arg("resume") = false,
      py::arg("checkpoint_every") = 0.0, py::arg("threads") = 0, py::arg("log") = false,
      py::arg("stop_at_step") = 0, py::arg("set") = py::none(),
      "runs a scene as `darcydem run` does, writing its output directory; returns a summary; set = {PATH: "
      "value} changes the scene first, as load's set and `--set PATH=VALUE` do; with "
      "log=True the program's run log and progress lines go to stderr; stop_at_step = N stops it as if "
      "interrupted once N steps are done (checked every 256 steps), leaving its checkpoint (resume=True "
      "goes on with it; darcydem.load(scene, checkpoint=out + '/checkpoint.bin') loads it into a model)");
  m.def(
      "grading",
      [](const std::vector<double>& radii, int dimension) {
        if (radii.empty()) throw py::value_error("grading: no radii");
        for (double r : radii) {
          if (!(r > 0.0) || !std::isfinite(r))
            throw py::value_error("grading: radii must be positive and finite");
        }
        if (dimension != 2 && dimension != 3) throw py::value_error("grading: dimension must be 2 or 3");
        const auto g = dimension == 2 ? darcydem::grading_of<2>(radii) : darcydem::grading_of<3>(radii);
        py::dict out;
        out["d_min"] = g.d_min;
        out["d_max"] = g.d_max;
        out["d10"] = g.d10;
        out["d30"] = g.d30;
        out["d50"] = g.d50;
        out["d60"] = g.d60;
        out["uniformity"] = g.uniformity();
        out["curvature"] = g.curvature();
        return out;
      },
      py::arg("radii"), py::kw_only(), py::arg("dimension") = 3,
      "the grains' grading by mass, as the run log gives it: d_min, d_max and D10, D30, D50, D60 (m; D_x the "
      "smallest diameter that with all grains no larger carries x of the mass: spheres d^3, discs of unit "
      "thickness d^2), the coefficients of uniformity D60/D10 and curvature D30^2/(D10 D60)");
  // Terzaghi's 1D consolidation (top drained, bottom sealed, drainage path
  // `height`), as the verification tests take it, for scripts that compare
  // a run with it (examples/fluid_cases/run_oedometer.py).
  auto terzaghi = [](double height, double conductivity, double compressibility, double fluid_storage,
                     double unit_weight) {
    darcydem::SeepageColumnParameters p;
    p.height = height;
    p.conductivity = conductivity;
    p.compressibility = compressibility;
    p.fluid_storage = fluid_storage;
    p.unit_weight = unit_weight;
    return p;
  };
  m.def(
      "consolidation_degree",
      [terzaghi](double time, double height, double conductivity, double compressibility,
                 double fluid_storage, double unit_weight) {
        return darcydem::consolidation_degree(
            terzaghi(height, conductivity, compressibility, fluid_storage, unit_weight), time);
      },
      py::arg("time"), py::kw_only(), py::arg("height"), py::arg("conductivity"), py::arg("compressibility"),
      py::arg("fluid_storage") = 0.0, py::arg("unit_weight") = 9806.65,
      "Terzaghi's settlement at `time` (s) after a load step over its final value, the immediate part 1 - B "
      "included, B = m_v / (m_v + n/K_f); SI units (m, m/s, 1/Pa, N/m^3)");
  m.def(
      "consolidation_pressure",
      [terzaghi](double time, double distance, double stress, double height, double conductivity,
                 double compressibility, double fluid_storage, double unit_weight) {
        return darcydem::consolidation_pressure(
            terzaghi(height, conductivity, compressibility, fluid_storage, unit_weight), stress, distance,
            time);
      },
      py::arg("time"), py::arg("distance"), py::arg("stress"), py::kw_only(), py::arg("height"),
      py::arg("conductivity"), py::arg("compressibility"), py::arg("fluid_storage") = 0.0,
      py::arg("unit_weight") = 9806.65,
      "Terzaghi's excess pore pressure (Pa) at `distance` (m) from the drained end, `time` (s) after a load "
      "step `stress` (Pa)");
}
