#include "darcydem/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>

#include <unistd.h>

#include <fmt/format.h>

#include "darcydem/contact/contact_laws.hpp"
#include "darcydem/generation/generators.hpp"
#include "darcydem/neighbour/linked_cells.hpp"
#include "darcydem/particles/grading.hpp"
#include "darcydem/scene/scene_cell.hpp"
#include "darcydem/scene/scene_clumps.hpp"
#include "darcydem/scene/scene_fluid.hpp"
#include "darcydem/scene/scene_inlet.hpp"
#include "darcydem/scene/scene_region.hpp"
#include "darcydem/scene/scene_sizes.hpp"
#include "darcydem/scene/toml_reader.hpp"
#include "darcydem/walls/loaded_area.hpp"
#include "darcydem/walls/triangle_mesh.hpp"

namespace darcydem {
namespace {

/// Refuses a generator's particle count that this machine's memory could
/// not hold: 256 bytes a particle is less than its state alone (a
/// checkpoint takes about 350), so only counts that cannot run are refused,
/// before the generator tries to make them.
void check_count_fits(const TableReader& r, std::string_view key, double count) {
  constexpr double bytes_each = 256.0;
  const double memory =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (memory > 0.0 && count * bytes_each > memory) {
    r.fail(key, fmt::format("{:.4g} particles would need at least {:.3g} GB ({} bytes each), more than this "
                            "machine's {:.3g} GB of memory",
                            count, count * bytes_each / 1e9, bytes_each, memory / 1e9));
  }
}

const std::vector<std::string> kTopLevel = {"simulation", "periodic", "material", "contact",       "wall",
                                            "particles",  "output",   "probe",    "stage",         "fluid",
                                            "analysis",   "domain",   "inlet",    "clump_template"};

template <int D>
Vec<D> to_vec(const std::vector<double>& v) {
  Vec<D> out;
  for (int k = 0; k < D; ++k) out[k] = v[k];
  return out;
}

/// Iterates an array of tables, giving a reader for each.
template <class F>
void for_each_table(TableReader& parent, std::string_view key, const std::string& label, F&& f) {
  const toml::array* arr = parent.optional_array(key);
  if (arr == nullptr) return;
  int index = 0;
  for (const auto& node : *arr) {
    ++index;
    const toml::table* t = node.as_table();
    if (t == nullptr) parent.fail(key, fmt::format("must be an array of tables ([[{}]])", key));
    TableReader r(*t, fmt::format("[[{}]] #{}", label, index), parent.file());
    f(r, index);
    r.finish();
  }
}

struct MaterialRef {
  std::map<std::string, std::uint16_t> index;
  std::vector<std::string> names;
  std::uint16_t lookup(TableReader& r, std::string_view key, const std::string& name) const {
    auto it = index.find(name);
    if (it == index.end()) {
      std::string hint;
      if (auto s = did_you_mean(name, names); !s.empty()) hint = fmt::format(" (did you mean \"{}\"?)", s);
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + ("\"" + n + "\"");
      r.fail(key, fmt::format("no material named \"{}\"{}; defined: {}", name, hint, list));
    }
    return it->second;
  }
};

/// A note when the grains drawn from a grading miss its D10, D50 or D60 by
/// more than 10 %: a grading by mass over a wide range rests its mass on
/// few coarse grains, which a small sample lacks.
template <int D>
std::optional<std::string> grading_followed_loosely(const RadiusDistribution& curve,
                                                    const std::vector<double>& radius,
                                                    const std::string& where) {
  if (radius.empty()) return std::nullopt;
  const GradingSummary made = grading_of<D>(radius);
  const std::array<double, 3> wanted = {curve.passing_diameter(0.1), curve.passing_diameter(0.5),
                                        curve.passing_diameter(0.6)};
  const std::array<double, 3> got = {made.d10, made.d50, made.d60};
  bool loose = false;
  for (std::size_t k = 0; k < 3; ++k) loose = loose || std::abs(got[k] / wanted[k] - 1.0) > 0.1;
  if (!loose) return std::nullopt;
  return fmt::format(
      "{}: the {} grains drawn follow the grading curve loosely: D10, D50, D60 {:.4g}, {:.4g}, {:.4g} mm "
      "against the curve's {:.4g}, {:.4g}, {:.4g} mm (more grains, or a narrower grading, follow it "
      "closer{})",
      where, radius.size(), got[0] * 1e3, got[1] * 1e3, got[2] * 1e3, wanted[0] * 1e3, wanted[1] * 1e3,
      wanted[2] * 1e3, curve.weight_exponent > 0 ? "; by mass the few coarse grains carry much of it" : "");
}

template <int D>
Vec<D> read_direction(TableReader& r, std::string_view key, std::optional<Vec<D>> fallback) {
  auto v = r.optional_numbers(key, D);
  if (!v) {
    if (!fallback) r.fail_table(fmt::format("missing required key '{}' (an array of {} numbers)", key, D));
    return *fallback;
  }
  Vec<D> out = to_vec<D>(*v);
  if (!(out.norm() > 0.0)) r.fail(key, "must be a non-zero vector");
  return out.normalized();
}

/// A box wall's `rotation` about its centre: in 2D an angle (degrees,
/// counter-clockwise), in 3D `{ axis = [3 numbers], angle = degrees }`.
/// Returns the box's own axes as the columns of the rotation.
template <int D>
Eigen::Matrix<double, D, D> read_box_rotation(TableReader& r) {
  Eigen::Matrix<double, D, D> axes = Eigen::Matrix<double, D, D>::Identity();
  if constexpr (D == 2) {
    const double angle = r.number("rotation") * std::numbers::pi / 180.0;
    if (!std::isfinite(angle)) r.fail("rotation", "must be a finite angle in degrees");
    axes << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  } else {
    const toml::node* n = r.raw("rotation");
    const toml::table* t = n != nullptr ? n->as_table() : nullptr;
    if (t == nullptr) r.fail("rotation", "must be a table: rotation = { axis = [x, y, z], angle = degrees }");
    TableReader rr(*t, r.where() + " rotation", r.file());
    const Vec<3> u = read_direction<3>(rr, "axis", std::nullopt);
    const double angle = rr.number("angle") * std::numbers::pi / 180.0;
    if (!std::isfinite(angle)) rr.fail("angle", "must be a finite angle in degrees");
    rr.finish();
    // Rodrigues: R = cos I + sin [u]x + (1 - cos) u u^T.
    Eigen::Matrix<double, 3, 3> ux;
    ux << 0.0, -u.z(), u.y(), u.z(), 0.0, -u.x(), -u.y(), u.x(), 0.0;
    axes = std::cos(angle) * Eigen::Matrix<double, 3, 3>::Identity() + std::sin(angle) * ux +
           (1.0 - std::cos(angle)) * u * u.transpose();
  }
  return axes;
}

/// For a `wall_fluid_force` probe on wall w: the index of its barrier in
/// the fluid's if it is an impermeable plate (`impermeable`: the walls'
/// barriers come after the [[fluid.barrier]] tables and take their walls'
/// names, which are unique, so the last of that name is the wall's), or -1
/// for a wall that displaces the fluid. Refused at the probe's 'wall' for
/// any other wall, which the water passes through.
template <int D>
std::int64_t fluid_thrust_barrier(TableReader& r, const PoreFluid<D>& fluid,
                                  const std::vector<Wall<D>>& walls, std::size_t w, bool impermeable) {
  if (std::find(fluid.solid_walls.begin(), fluid.solid_walls.end(), w) != fluid.solid_walls.end()) return -1;
  for (std::size_t b = fluid.barriers.size(); impermeable && b-- > 0;) {
    if (fluid.barriers[b].name == walls[w].name) return static_cast<std::int64_t>(b);
  }
  r.fail("wall", fmt::format("wall \"{}\" lets the pore water through, so the water pushes on it nowhere: "
                             "\"wall_fluid_force\" needs a wall with displaces_fluid = true or an "
                             "impermeable plate (impermeable = true)",
                             walls[w].name));
}

/// The barrier of an impermeable wall (`impermeable = true`): it must be a
/// fixed, unturned box flat along one axis (a plate); the barrier lies on
/// that plane over the box's corners as given, lo and hi. Refused at the
/// wall's 'impermeable' key otherwise; the grid checks it later.
template <int D>
WallBarrier<D> plate_barrier(TableReader& r, const Wall<D>& w, const Vec<D>& box_lo, const Vec<D>& box_hi) {
  // A plate that the pore fluid cannot cross either: a barrier on its plane.
  int flat = -1;
  int flats = 0;
  for (int k = 0; k < D; ++k) {
    if (w.half[k] == 0.0) {
      flat = k;
      ++flats;
    }
  }
  if (flats != 1) {
    r.fail("impermeable",
           "needs a plate: a box with min = max along exactly one axis (its normal), e.g. a sheet pile");
  }
  if (w.axes != Eigen::Matrix<double, D, D>::Identity()) {
    r.fail("impermeable", "an impermeable plate lies on the fluid grid's faces: it cannot be rotated");
  }
  if (w.motion != WallMotion::fixed || w.spin != 0.0 || w.oscillation.active()) {
    r.fail("impermeable", "an impermeable wall cannot move: its barrier is fixed in the fluid grid");
  }
  WallBarrier<D> b;
  b.barrier.name = w.name;
  b.barrier.axis = flat;
  b.barrier.at = box_lo[flat];
  for (int k = 0; k < D; ++k) {
    // As given: a face whose centre lies on the plate's edge is in it.
    b.barrier.lo[k] = box_lo[k];
    b.barrier.hi[k] = box_hi[k];
  }
  b.error_prefix =
      fmt::format("{}: error: {} key 'impermeable': ", r.location(r.raw("impermeable")->source()), r.where());
  return b;
}

/// A cylinder wall (`cylinder = { centre, radius, axis (3D), touched_from }`):
/// in 3D infinite along its axis through `centre`, in 2D a circle.
template <int D>
void read_cylinder(TableReader& r, const toml::table& table, Wall<D>& w) {
  for (auto k : {"point", "normal", "box"}) {
    if (r.has(k))
      r.fail(k, fmt::format("a cylinder wall is placed by 'cylinder' alone; remove '{}' (a plane has 'point' "
                            "and 'normal', a box 'box', a cylinder 'cylinder = {{ centre = [...], radius = "
                            "... }}')",
                            k));
  }
  TableReader cr(table, r.where() + " cylinder", r.file());
  w.shape = WallShape::cylinder;
  w.point = to_vec<D>(cr.numbers("centre", D));
  w.radius = cr.check(
      "radius", cr.number("radius"), [](double x) { return x > 0.0; }, "> 0 m");
  if constexpr (D == 3) {
    w.axis = read_direction<D>(cr, "axis", std::nullopt);
  } else if (cr.has("axis")) {
    cr.fail("axis", "a 2D cylinder is a circle about 'centre' in the plane of the discs: it has no axis");
  }
  w.from_inside = cr.optional_choice("touched_from", {"inside", "outside"}).value_or("inside") == "inside";
  cr.finish();
}

/// A mesh wall (`mesh = { file = "x.stl", scale = ... }` or `mesh = {
/// vertices = [[x, y, z], ...], triangles = [[i, j, k], ...] }`), 3D: its
/// facets in its own frame about the centre of their bounding box, which
/// is the wall's point and its default rotation centre.
/// Returns a note for the run log and `darcydem check`: what was read and
/// where it stands (a wrong `scale` shows there).
template <int D>
std::string read_mesh(TableReader& r, const toml::table& table, const std::filesystem::path& base,
                      Wall<D>& w) {
  for (auto k : {"point", "normal", "box", "cylinder"}) {
    if (r.has(k))
      r.fail(k, fmt::format("a mesh wall is placed by 'mesh' alone; remove '{}' (a plane has 'point' and "
                            "'normal', a box 'box', a cylinder 'cylinder', a mesh 'mesh = {{ file = "
                            "\"...stl\" }}')",
                            k));
  }
  if (D != 3) {
    r.fail("mesh",
           "a mesh wall is a surface of triangles, in 3D; in 2D a segment is a box wall of zero thickness "
           "(box = { min = [...], max = [...] } with min = max along one axis, turned by 'rotation')");
  }
  TableReader mr(table, r.where() + " mesh", r.file());
  TriangleMesh mesh;
  std::size_t slivers = 0;
  if (mr.has("file") == mr.has("vertices")) {
    mr.fail_table(
        "give 'file' (an STL file, ASCII or binary, relative to the scene) or 'vertices' = [[x, y, z], ...] "
        "with 'triangles' = [[i, j, k], ...] (vertex numbers from 0), one of the two");
  }
  if (mr.has("file")) {
    const double scale = mr.check("scale", mr.number_or("scale", 1.0), is_positive,
                                  "> 0: the file's unit in m (e.g. 0.001 for a file in mm)");
    const std::string rel = mr.string("file");
    try {
      mesh = read_stl((base / rel).string(), scale);
    } catch (const std::runtime_error& e) {
      mr.fail("file", e.what());
    }
    // CAD tessellations leave slivers of no area: they take no load.
    slivers = mesh.drop_slivers();
  } else {
    if (mr.has("scale")) mr.fail("scale", "scales an STL file; give 'vertices' in m");
    auto rows = [&](std::string_view key, const char* what) {
      const toml::array* a = mr.optional_array(key);
      if (a == nullptr || a->empty())
        mr.fail(key, fmt::format("must be a non-empty array of {} (arrays of 3 numbers each)", what));
      std::vector<std::array<double, 3>> out;
      for (std::size_t i = 0; i < a->size(); ++i) {
        const toml::array* row = (*a)[i].as_array();
        std::array<double, 3> v{};
        bool ok = row != nullptr && row->size() == 3;
        for (std::size_t c = 0; ok && c < 3; ++c) {
          const auto x = (*row)[c].value<double>();
          ok = x.has_value() && std::isfinite(*x);
          if (ok) v[c] = *x;
        }
        if (!ok)
          mr.fail(key, fmt::format("entry {} (from 0) must be an array of 3 finite numbers ({})", i, what));
        out.push_back(v);
      }
      return out;
    };
    for (const auto& v : rows("vertices", "vertices, m")) mesh.vertex.emplace_back(v[0], v[1], v[2]);
    for (const auto& t : rows("triangles", "vertex numbers, from 0")) {
      std::array<std::uint32_t, 3> tri{};
      for (int c = 0; c < 3; ++c) {
        if (!(t[c] >= 0.0 && t[c] < static_cast<double>(mesh.vertex.size()) && t[c] == std::floor(t[c])))
          mr.fail("triangles", fmt::format("vertex number {} is not one of 0 .. {} (the vertices, from 0)",
                                           TableReader::format_number(t[c]), mesh.vertex.size() - 1));
        tri[c] = static_cast<std::uint32_t>(t[c]);
      }
      mesh.triangle.push_back(tri);
    }
  }
  // Moved as a whole (m), after the scale.
  if (mr.has("translate")) {
    const Vec<3> shift = to_vec<3>(mr.numbers("translate", 3));
    if (!shift.allFinite()) mr.fail("translate", "must be 3 finite numbers, m");
    for (auto& v : mesh.vertex) v += shift;
  }
  // Turned about the centre of its bounding box (its axes; as a box's).
  if (mr.has("rotation")) w.axes = read_box_rotation<D>(mr);
  mr.finish();
  // Its own frame: about the centre of its bounding box.
  Vec<3> lo = Vec<3>::Constant(std::numeric_limits<double>::infinity());
  Vec<3> hi = -lo;
  for (const auto& v : mesh.vertex) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec<3> centre = 0.5 * (lo + hi);
  for (auto& v : mesh.vertex) v -= centre;
  if (const std::string why = mesh.finish(); !why.empty())
    mr.fail(mr.has("file") ? "file" : "triangles", fmt::format("the mesh cannot be used: {}", why));
  w.shape = WallShape::mesh;
  for (int k = 0; k < D; ++k) w.point[k] = centre[k];
  // Where it stands, turned.
  Vec<3> world_lo = Vec<3>::Constant(std::numeric_limits<double>::infinity());
  Vec<3> world_hi = -world_lo;
  for (const auto& v : mesh.vertex) {
    Vec<3> x = centre;
    for (int k = 0; k < D; ++k)
      for (int j = 0; j < D; ++j) x[k] += w.axes(k, j) * v[j];
    world_lo = world_lo.cwiseMin(x);
    world_hi = world_hi.cwiseMax(x);
  }
  const std::string note = fmt::format(
      "{}: wall \"{}\" is a mesh of {} facets ({} vertices{}), area {:.6g} m^2, from ({:.6g}, {:.6g}, "
      "{:.6g}) to ({:.6g}, {:.6g}, {:.6g}) m{}",
      r.where(), w.name, mesh.triangle.size(), mesh.vertex.size(),
      mr.has("file") ? ", from " + mr.string("file") : std::string(), mesh.area(), world_lo[0], world_lo[1],
      world_lo[2], world_hi[0], world_hi[1], world_hi[2],
      slivers > 0 ? fmt::format("; {} facets of no area in the file left out", slivers) : std::string());
  w.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  return note;
}

/// A wall's `oscillation` (none if not given): a harmonic translation on top
/// of its motion, refused with a servo (which sets the wall's place from its
/// load).
template <int D>
WallOscillation<D> read_oscillation(TableReader& r) {
  WallOscillation<D> o;
  const toml::table* t = r.optional_table("oscillation");
  if (t == nullptr) {
    if (r.has("oscillation"))
      r.fail("oscillation", "must be a table: { amplitude = [" + std::to_string(D) +
                                " numbers] (m), frequency = Hz, phase = degrees (optional, default 0) }");
    return o;
  }
  if (r.has("servo")) {
    r.fail("oscillation",
           "a servo sets the wall's place from its load; give a servo wall no oscillation (or give the wall "
           "a 'velocity' or 'fixed' to shake it)");
  }
  TableReader orr(*t, r.where() + " oscillation", r.file());
  orr.allow({"amplitude", "frequency", "phase"});
  o.amplitude = to_vec<D>(orr.numbers("amplitude", D));
  if (!o.amplitude.allFinite() || o.amplitude.isZero(0.0))
    orr.fail("amplitude", "must be finite and not all zero: the wall's displacement amplitude, m, a vector");
  o.frequency = orr.check(
      "frequency", orr.number("frequency"), [](double f) { return std::isfinite(f) && f > 0.0; }, "> 0 Hz");
  const double phase = orr.check(
      "phase", orr.optional_number("phase").value_or(0.0), [](double x) { return std::isfinite(x); },
      "a finite number of degrees: the sine's phase at the start (0: the wall starts at its mean place "
      "moving at full speed; -90: at rest, at one end of its stroke)");
  o.phase = phase * std::numbers::pi / 180.0;
  orr.finish();
  return o;
}

/// A servo's target: `target_force` (N) or, with `by_stress`,
/// `target_stress` (Pa), each a number or a table { times, values } (a ramp,
/// a load schedule: s from the stage's start), plus an optional
/// `cycle = { amplitude, frequency, phase }` on top (cyclic loading). The
/// target must stay >= 0 (compressive) throughout.
void read_servo_target(TableReader& sr, bool by_stress, WallShape shape, ServoControl& servo) {
  const char* key = by_stress ? "target_stress" : "target_force";
  const std::string unit = by_stress ? "Pa"
                           : shape == WallShape::cylinder
                               ? "N, the sum of the grains' pushes normal to the cylinder"
                               : "N";
  servo.by_stress = by_stress;
  servo.schedule = read_time_series(sr, key, unit);
  const auto& values = servo.schedule.values;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] >= 0.0) continue;
    if (values.size() == 1)
      sr.fail(key, fmt::format("must be >= 0 {}, got {}", unit, TableReader::format_number(values[i])));
    sr.fail(key, fmt::format("must be >= 0 {} at every time (a compressive load), got {} at {} s", unit,
                             TableReader::format_number(values[i]),
                             TableReader::format_number(servo.schedule.times[i])));
  }
  if (const toml::table* c = sr.optional_table("cycle")) {
    TableReader cr(*c, sr.where() + " cycle", sr.file());
    cr.allow({"amplitude", "frequency", "phase"});
    servo.cycle.amplitude = cr.check(
        "amplitude", cr.number("amplitude"), [](double a) { return std::isfinite(a) && a > 0.0; },
        fmt::format("> 0 {}: the target's swing either side of '{}'", by_stress ? "Pa" : "N", key));
    servo.cycle.frequency = cr.check(
        "frequency", cr.number("frequency"), [](double f) { return std::isfinite(f) && f > 0.0; }, "> 0 Hz");
    servo.cycle.phase =
        cr.check(
            "phase", cr.optional_number("phase").value_or(0.0), [](double x) { return std::isfinite(x); },
            "a finite number of degrees: the sine's phase at the start (0: the target starts "
            "at '" +
                std::string(key) + "' and rises; -90: at its lowest, without a jump)") *
        std::numbers::pi / 180.0;
    const double lowest = *std::min_element(values.begin(), values.end());
    if (servo.cycle.amplitude > lowest) {
      cr.fail(
          "amplitude",
          fmt::format("must be at most the least of '{}' ({}): the target, {} plus the cycle, must stay >= 0 "
                      "(a compressive load)",
                      key, TableReader::format_number(lowest), key));
    }
    cr.finish();
  }
  (by_stress ? servo.target_stress : servo.target_force) = servo.target_at(0.0);
}

/// A wall's motion: `velocity`, `servo` or `fixed`, and its
/// `angular_velocity` (a cylinder's spin about its axis; a plane's or
/// box's turn about its rotation centre: 2D a number, 3D a vector, whose
/// length is `spin` and whose direction is `spin_axis`). A servo moves a
/// plane along its normal and a box along its `direction`, and changes a
/// cylinder's radius; its load may count the pore water's thrust
/// (`load = "total"`) on a wall that displaces the fluid
/// (`displaces_fluid`).
template <int D>
void read_wall_motion(TableReader& r, WallShape shape, bool displaces_fluid, Vec<D>& velocity,
                      WallMotion& motion, ServoControl& servo, Vec<D>& servo_axis, double& spin,
                      Vec<D>& spin_axis, double& radius_rate, WallOscillation<D>& oscillation) {
  const bool box = shape == WallShape::box || shape == WallShape::mesh;
  r.allow({"velocity", "servo", "fixed", "angular_velocity", "radial_velocity", "oscillation"});
  oscillation = read_oscillation<D>(r);
  // A cylinder's rate of change of radius, whatever its translation; a
  // servo sets its own.
  if (auto v = r.optional_number("radial_velocity")) {
    if (shape != WallShape::cylinder) {
      r.fail(
          "radial_velocity",
          "changes a cylinder wall's radius (a cavity expansion, a strain-controlled cell); a plane or box "
          "wall keeps its shape: give it a 'velocity'");
    }
    if (r.has("servo")) {
      r.fail("radial_velocity",
             "a servo sets the cylinder's radius from its load; give one of 'servo' or 'radial_velocity'");
    }
    radius_rate = r.check(
        "radial_velocity", *v, [](double x) { return std::isfinite(x); },
        "a number, m/s, the radius's rate of change (negative: the cylinder closes)");
  }
  // A cylinder's spin about its axis, a plane's or box's turn about its
  // rotation centre, whatever its translation.
  if (r.has("angular_velocity")) {
    if (shape != WallShape::cylinder && displaces_fluid) {
      r.fail("angular_velocity",
             "a wall that displaces the pore fluid or is impermeable stays along the fluid grid's axes: it "
             "cannot turn (leave 'impermeable' and 'displaces_fluid' out of a turning wall)");
    }
    if (shape != WallShape::cylinder && r.has("servo")) {
      r.fail("angular_velocity",
             "a servo moves a wall along a fixed direction; a wall that turns cannot have one");
    }
    if (D == 3 && shape != WallShape::cylinder) {
      const auto* node = r.raw("angular_velocity");
      if (node != nullptr && !node->is_array()) {
        r.fail("angular_velocity",
               "a plane or box wall turns about the axis of its angular velocity through its "
               "'rotation_centre': give [wx, wy, wz], rad/s, right-handed");
      }
      const Vec<D> w = to_vec<D>(r.numbers("angular_velocity", D));
      if (!w.allFinite()) r.fail("angular_velocity", "must be finite, rad/s");
      spin = w.norm();
      spin_axis = spin > 0.0 ? Vec<D>(w / spin) : Vec<D>::Zero();
    } else {
      spin = r.check(
          "angular_velocity", r.number("angular_velocity"), [](double x) { return std::isfinite(x); },
          D == 3 ? "a number, rad/s, right-handed about the cylinder's axis"
                 : "a number, rad/s, counter-clockwise");
    }
  }
  const int given = int(r.has("velocity")) + int(r.has("servo")) + int(r.has("fixed"));
  if (given > 1) r.fail_table("give only one of 'velocity', 'servo' or 'fixed'");
  if (r.has("velocity")) {
    motion = WallMotion::velocity;
    velocity = to_vec<D>(r.numbers("velocity", D));
  } else if (const toml::table* s = r.optional_table("servo")) {
    TableReader sr(*s, r.where() + " servo", r.file());
    motion = WallMotion::servo;
    servo = ServoControl{};
    if (sr.has("target_force") == sr.has("target_stress")) {
      sr.fail_table(
          "a servo needs one of 'target_force' (N, the load wanted on the wall) or 'target_stress' (Pa, a "
          "plane wall's load over the cross-section the other walls bound: a triaxial or biaxial test)");
    }
    const bool by_stress = sr.has("target_stress");
    if (by_stress && box) {
      sr.fail(
          "target_stress",
          fmt::format("is for a plane wall (its cross-section of the sample) or a cylinder (its lateral "
                      "surface), whose loaded area the other walls bound; give a {} wall a 'target_force'",
                      shape == WallShape::mesh ? "mesh" : "box"));
    }
    read_servo_target(sr, by_stress, shape, servo);
    servo.gain = sr.check("gain", sr.number("gain"), is_positive, "> 0 m/(s N)");
    servo.max_speed = sr.check("max_speed", sr.number("max_speed"), is_positive, "> 0 m/s");
    if (box) {
      if (!sr.has("direction")) {
        sr.fail_table(std::string(shape == WallShape::mesh ? "a mesh" : "a box") +
                      " wall's servo needs 'direction' = [" + std::to_string(D) + " numbers]: the way the " +
                      (shape == WallShape::mesh ? "mesh" : "box") +
                      " moves to load the grains more, e.g. [0, -1] for a lid pushing down in 2D");
      }
      servo_axis = read_direction<D>(sr, "direction", std::nullopt);
    } else if (sr.has("direction")) {
      sr.fail("direction",
              shape == WallShape::cylinder
                  ? "a cylinder's servo changes its radius; 'direction' is for box walls"
                  : "a plane wall's servo moves it along its normal; 'direction' is for box walls");
    }
    servo.with_pore_water = sr.optional_choice("load", {"grains", "total"}) == "total";
    if (servo.with_pore_water && !displaces_fluid) {
      sr.fail("load",
              "\"total\" adds the pore water's thrust, which only a wall with displaces_fluid = true takes "
              "(the water passes through any other wall); give \"grains\", the default");
    }
    sr.finish();
  } else if (r.has("fixed")) {
    if (!r.boolean_or("fixed", true))
      r.fail("fixed", "only 'fixed = true' makes sense; give 'velocity' to move it");
    motion = WallMotion::fixed;
  }
}

/// A stress-controlled servo (read by read_wall_motion from r's 'servo')
/// needs walls[i]'s loaded area: fails at its 'target_stress' otherwise.
template <int D>
void require_loaded_area(TableReader& r, const std::vector<Wall<D>>& walls, std::size_t i,
                         const PeriodicCell<D>& cell) {
  const LoadedArea a = loaded_area(walls, i, cell);
  if (a.why_not.empty()) return;
  TableReader sr(*r.optional_table("servo"), r.where() + " servo", r.file());
  sr.fail(
      "target_stress",
      fmt::format("loads wall \"{}\" over the sample's {}, and {}; give 'target_force' (N) instead",
                  walls[i].name, walls[i].is_cylinder() ? "lateral surface" : "cross-section", a.why_not));
}

template <int D>
std::int64_t axis_component(TableReader& r, std::string_view key, bool allow_norm) {
  std::vector<std::string> allowed =
      D == 2 ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x", "y", "z"};
  if (allow_norm) allowed.emplace_back("norm");
  const std::string c = r.choice(key, allowed);
  if (c == "norm") return -1;
  return c[0] - 'x';
}

/// A tensor's component: "xx", "xy", ... (i, j), or with_mean "mean" (-1, -1).
template <int D>
std::array<int, 2> tensor_component(TableReader& r, std::string_view key, bool with_mean) {
  std::vector<std::string> allowed = D == 2 ? std::vector<std::string>{"xx", "yy", "xy"}
                                            : std::vector<std::string>{"xx", "yy", "zz", "xy", "xz", "yz"};
  if (with_mean) allowed.emplace_back("mean");
  const std::string c = r.choice(key, allowed);
  if (c == "mean") return {-1, -1};
  return {c[0] - 'x', c[1] - 'x'};
}

/// [periodic]: x = [min, max], ... for the axes that repeat.
template <int D>
void read_periodic(TableReader& r, PeriodicCell<D>& cell) {
  for (int k = 0; k < D; ++k) {
    const std::string axis(1, "xyz"[k]);
    if (!r.has(axis)) continue;
    const auto range = r.numbers(axis, 2);
    if (!(std::isfinite(range[0]) && std::isfinite(range[1]) && range[1] > range[0])) {
      r.fail(axis, fmt::format("must be [min, max] with max > min (m), got [{}, {}]",
                               TableReader::format_number(range[0]), TableReader::format_number(range[1])));
    }
    cell.set_axis(k, range[0], range[1]);
  }
  r.finish();
  if (!cell.any()) {
    r.fail_table(fmt::format("names no axis; give {} = [min, max] for each axis that repeats",
                             D == 2 ? "x or y" : "x, y or z"));
  }
}

/// Walls are not repeated across periodic boundaries, and a plane or box
/// that turns would cross them.
template <int D>
void check_turning_wall_in_period(TableReader& r, const PeriodicCell<D>& cell) {
  for (int k = 0; k < D; ++k) {
    if (cell.periodic[k]) {
      r.fail("angular_velocity",
             fmt::format("a plane or box wall cannot turn with periodic boundaries (along {}): walls are not "
                         "repeated across them, and a turning wall would cross them",
                         "xyz"[k]));
    }
  }
}

/// Walls are not repeated: a plane must run along every periodic axis and a
/// box lie within the period, so that no particle meets a wall across a
/// periodic boundary.
template <int D>
void check_wall_in_period(TableReader& r, const Wall<D>& w, const PeriodicCell<D>& cell) {
  if (w.spin != 0.0 && !w.is_cylinder()) check_turning_wall_in_period<D>(r, cell);
  for (int k = 0; k < D; ++k) {
    if (!cell.periodic[k]) continue;
    if (w.is_cylinder() && !(D == 3 && std::abs(w.axis[k]) == 1.0)) {
      r.fail("cylinder",
             fmt::format("a cylinder wall must run along the periodic axis {} (a 3D cylinder with its axis "
                         "along it): walls are not repeated across periodic boundaries",
                         "xyz"[k]));
    }
    if (w.is_plane() && w.normal[k] != 0.0) {
      r.fail("normal", fmt::format("a plane wall must be parallel to the periodic axis {} (normal[{}] = 0): "
                                   "particles leave through the periodic boundaries instead",
                                   "xyz"[k], k));
    }
    if (w.is_solid_body()) {
      double extent = w.axes.row(k).cwiseAbs().dot(w.half);
      if constexpr (D == 3) {
        if (w.is_mesh()) {
          extent = 0.0;
          for (const auto& v : w.mesh->vertex) extent = std::max(extent, std::abs(w.axes.row(k).dot(v)));
        }
      }
      const double lo = cell.lower[k];
      const double hi = lo + cell.length[k];
      if (w.point[k] - extent < lo || w.point[k] + extent > hi) {
        r.fail(
            w.is_mesh() ? "mesh" : "box",
            fmt::format("a {} wall must lie within the periodic range [{}, {}] along {} (walls are "
                        "not repeated across periodic boundaries); it spans [{:.6g}, {:.6g}]",
                        w.is_mesh() ? "mesh" : "box", TableReader::format_number(lo),
                        TableReader::format_number(hi), "xyz"[k], w.point[k] - extent, w.point[k] + extent));
      }
    }
  }
}

/// Every particle starts inside the period, and each period is longer than
/// twice the list's reach (one image of a neighbour within it).
template <int D>
void check_periods(TableReader& r, const Simulation<D>& sim, const std::vector<std::string>& origin) {
  const auto& p = sim.particles;
  const auto& cell = sim.periodic;
  const double shortest = sim.shortest_period();
  for (int k = 0; k < D; ++k) {
    if (!cell.periodic[k]) continue;
    const std::string axis(1, "xyz"[k]);
    const double lo = cell.lower[k];
    const double hi = lo + cell.length[k];
    // A clump's members may stick out of the period (the list builds put
    // them back): its centre of mass starts inside it.
    const auto& clumps = sim.clumps;
    for (std::size_t c = 0; c < clumps.size(); ++c) {
      const double x = clumps.position[c][k];
      if (x < lo || x >= hi) {
        const std::size_t i = clumps.member_index[clumps.first[c]];
        throw SceneError(
            fmt::format("{}: error: the centre of clump {} (of particle {}) starts at {} = {:.6g} m, "
                        "outside the periodic range [periodic] {} = [{}, {}) (allowed: min <= {} < max)",
                        origin[i], c, i, axis, x, axis, TableReader::format_number(lo),
                        TableReader::format_number(hi), axis));
      }
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!clumps.clump_of.empty() && clumps.clump_of[i] >= 0) continue;
      if (p.position[i][k] < lo || p.position[i][k] >= hi) {
        throw SceneError(
            fmt::format("{}: error: particle {} starts at {} = {:.6g} m, outside the periodic range "
                        "[periodic] {} = [{}, {}) (allowed: min <= {} < max)",
                        origin[i], i, axis, p.position[i][k], axis, TableReader::format_number(lo),
                        TableReader::format_number(hi), axis));
      }
    }
    if (!(cell.length[k] > shortest)) {
      r.fail(
          axis,
          sim.clumps.empty()
              ? fmt::format("the period {:.6g} m must exceed 2 x (2 x largest radius + skin) = {:.6g} m, so "
                            "that a particle meets one image of each neighbour",
                            cell.length[k], shortest)
              : fmt::format("the period {:.6g} m must exceed 2 x (the larger of 2 x the largest radius and "
                            "the largest clump's reach, + skin) = {:.6g} m, so that a particle meets one "
                            "image of each neighbour and a clump none of itself",
                            cell.length[k], shortest));
    }
  }
}

/// [domain]: min, max (the box particles are removed outside of). Every
/// particle starts inside it, it holds each period, and it holds the fluid
/// grid with a margin of the largest radius, so that a grain it removes has
/// no volume in the grid's cells (the pore water's balance keeps).
template <int D>
void read_domain(TableReader& r, Simulation<D>& sim, const PoreFluid<D>* fluid,
                 const std::vector<std::string>& origin, std::vector<std::string>& notes) {
  const auto lo = r.numbers("min", D);
  const auto hi = r.numbers("max", D);
  r.finish();
  for (int k = 0; k < D; ++k) {
    if (!(std::isfinite(lo[k]) && std::isfinite(hi[k]) && hi[k] > lo[k])) {
      r.fail("max",
             fmt::format("must be greater than 'min' along every axis (m); along {} min = {} and max = {}",
                         "xyz"[k], TableReader::format_number(lo[k]), TableReader::format_number(hi[k])));
    }
    sim.domain_lower[k] = lo[k];
    sim.domain_upper[k] = hi[k];
  }
  sim.has_domain = true;
  const auto& cell = sim.periodic;
  for (int k = 0; k < D; ++k) {
    if (!cell.periodic[k]) continue;
    const double end = cell.lower[k] + cell.length[k];
    if (lo[k] > cell.lower[k] || hi[k] < end) {
      r.fail(
          lo[k] > cell.lower[k] ? "min" : "max",
          fmt::format("along the periodic axis {} the domain must hold the period [{}, {}] ([periodic] {}): "
                      "particles leave through the period's ends and come back, not out of the domain",
                      "xyz"[k], TableReader::format_number(cell.lower[k]), TableReader::format_number(end),
                      "xyz"[k]));
    }
  }
  const auto& p = sim.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int k = 0; k < D; ++k) {
      if (p.position[i][k] < lo[k] || p.position[i][k] > hi[k]) {
        throw SceneError(fmt::format(
            "{}: error: particle {} starts at {} = {:.6g} m, outside the [domain] (allowed: {} <= {} <= {}, "
            "from {}'s min and max)",
            origin[i], i, "xyz"[k], p.position[i][k], TableReader::format_number(lo[k]), "xyz"[k],
            TableReader::format_number(hi[k]), r.here()));
      }
    }
  }
  std::string box;
  for (int k = 0; k < D; ++k)
    box += fmt::format("{}{} in [{}, {}]", k == 0 ? "" : ", ", "xyz"[k], TableReader::format_number(lo[k]),
                       TableReader::format_number(hi[k]));
  notes.push_back(fmt::format(
      "[domain]: particles whose centres leave {} m are removed from the run{} (the "
      "removed_particles and removed_mass probes and run.json count them)",
      box, sim.clumps.empty() ? "" : "; a clump whose centre of mass leaves it, with all its members"));
  if (fluid == nullptr) return;
  // A clump is removed by its centre of mass: its members reach that far
  // beyond it.
  double r_max = sim.clumps.largest_reach(p);
  for (double radius : p.radius) r_max = std::max(r_max, radius);
  const Vec<D> g_lo = fluid->grid.origin;
  const Vec<D> g_hi = fluid->grid.upper();
  for (int k = 0; k < D; ++k) {
    if (cell.periodic[k]) continue;
    const bool low = g_lo[k] - r_max < lo[k];
    if (low || g_hi[k] + r_max > hi[k]) {
      r.fail(
          low ? "min" : "max",
          fmt::format("must leave the largest grain's radius ({:.6g} m) between the fluid grid, [{:.6g}, "
                      "{:.6g}] along {}, and the domain's side: a grain removed while it overlaps the grid "
                      "would take its volume out of the pore water's balance (allowed: {} {} {:.6g} m)",
                      r_max, g_lo[k], g_hi[k], "xyz"[k], low ? "min <=" : "max >=", "xyz"[k],
                      low ? g_lo[k] - r_max : g_hi[k] + r_max));
    }
  }
}

template <int D>
void check_initial_overlaps(const Simulation<D>& sim, double tolerance,
                            const std::vector<std::string>& origin) {
  const auto& p = sim.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (const auto& w : sim.walls) {
      const double overlap = p.radius[i] - w.gap(p.position[i]);
      if (overlap > tolerance * p.radius[i]) {
        throw SceneError(fmt::format(
            "{}: error: particle {} overlaps wall \"{}\" by {:.3g} m at start ({:.3g} of its radius; "
            "allowed: simulation.initial_overlap_tolerance = {})",
            origin[i], i, w.name, overlap, overlap / p.radius[i], tolerance));
      }
    }
  }
  if (p.size() < 2) return;
  LinkedCells<D> cells;
  double r_max = *std::max_element(p.radius.begin(), p.radius.end());
  cells.build(p.position, 2.0 * r_max, sim.periodic);
  for (std::size_t i = 0; i < p.size(); ++i) {
    cells.for_each_near(cells.cell_of(p.position[i]), [&](std::uint32_t j) {
      if (j <= i) return;
      const auto& clump_of = sim.clumps.clump_of;  // a clump's members may touch
      if (!clump_of.empty() && clump_of[i] >= 0 && clump_of[i] == clump_of[j]) return;
      const double overlap =
          p.radius[i] + p.radius[j] - sim.periodic.shortest(p.position[j] - p.position[i]).norm();
      const double allowed = tolerance * std::min(p.radius[i], p.radius[j]);
      if (overlap > allowed) {
        throw SceneError(
            fmt::format("{}: error: particles {} and {} overlap by {:.3g} m at start (from {}; allowed: "
                        "simulation.initial_overlap_tolerance = {} of the smaller radius)",
                        origin[i], i, j, overlap, origin[j], tolerance));
      }
    });
  }
}

}  // namespace

std::string fnv1a_hex(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return fmt::format("{:016x}", h);
}

int scene_dimension(const toml::table& root, const std::string& file) {
  const toml::table* sim = root["simulation"].as_table();
  if (sim == nullptr) {
    throw SceneError(
        fmt::format("{}:1:1: error: missing required table [simulation] (with 'dimension' = 2 or 3)", file));
  }
  TableReader r(*sim, "[simulation]", file);
  const auto d = r.integer("dimension");
  if (d != 2 && d != 3) r.fail("dimension", fmt::format("must be 2 (discs) or 3 (spheres), got {}", d));
  return static_cast<int>(d);
}

template <int D>
Scene<D> build_scene(const toml::table& root, const std::string& file, const std::string& text) {
  Scene<D> scene;
  scene.file = file;
  scene.text_hash = fnv1a_hex(text);
  auto& sim = scene.simulation;
  const std::filesystem::path base = std::filesystem::path(file).parent_path();
  TableReader top(root, "scene", file);

  // [simulation]
  double overlap_tolerance = 0.01;
  {
    const toml::table* t = top.optional_table("simulation");
    TableReader r(*t, "[simulation]", file);
    r.integer("dimension");
    r.allow({"time_step"});
    if (const toml::node* n = t->get("time_step"); n != nullptr) {
      if (n->is_string()) {
        if (*n->value<std::string>() != "auto")
          r.fail("time_step", "must be \"auto\" or a number of seconds > 0");
      } else if (auto v = n->value<double>(); v && (n->is_floating_point() || n->is_integer())) {
        scene.time_step.automatic = false;
        scene.time_step.value = r.check("time_step", *v, is_positive, "\"auto\" or a number of seconds > 0");
      } else {
        r.fail("time_step", "must be \"auto\" or a number of seconds > 0");
      }
    }
    scene.time_step.safety_factor = r.check(
        "safety_factor", r.number_or("safety_factor", 0.2), [](double v) { return v > 0.0 && v <= 1.0; },
        "in (0, 1]");
    sim.skin = r.check("skin", r.number_or("skin", 0.0), is_non_negative, ">= 0 m (0: automatic)");
    overlap_tolerance = r.check("initial_overlap_tolerance", r.number_or("initial_overlap_tolerance", 0.01),
                                is_non_negative, ">= 0 (a fraction of the radius)");
    r.finish();
  }

  // [periodic]
  std::optional<TableReader> periodic_reader;
  if (const toml::table* t = top.optional_table("periodic")) {
    periodic_reader.emplace(*t, "[periodic]", file);
    read_periodic<D>(*periodic_reader, sim.periodic);
  } else if (top.has("periodic")) {
    top.fail("periodic", "must be a table ([periodic] with x = [min, max], ...)");
  }

  // [[material]]
  MaterialRef materials;
  for_each_table(top, "material", "material", [&](TableReader& r, int) {
    Material m;
    m.name = r.string("name");
    if (materials.index.count(m.name) != 0)
      r.fail("name", fmt::format("material \"{}\" is defined twice", m.name));
    m.density = r.check("density", r.number("density"), is_positive, "> 0 kg/m^3");
    m.youngs_modulus =
        r.check("youngs_modulus", r.number_or("youngs_modulus", 0.0), is_non_negative, ">= 0 Pa");
    m.poisson_ratio = r.check(
        "poisson_ratio", r.number_or("poisson_ratio", 0.0), [](double v) { return v > -1.0 && v < 0.5; },
        "in (-1, 0.5)");
    materials.index[m.name] = static_cast<std::uint16_t>(sim.materials.size());
    materials.names.push_back(m.name);
    sim.materials.push_back(m);
  });
  if (sim.materials.empty()) top.fail_table("needs at least one [[material]]");

  // [[contact]]: one per pair of materials that can touch.
  const std::size_t nm = sim.materials.size();
  sim.contact_table = ContactTable(nm);
  std::vector<bool> defined(nm * nm, false);
  for_each_table(top, "contact", "contact", [&](TableReader& r, int) {
    auto names = r.string_list("materials");
    if (names.size() != 2) r.fail("materials", "must name exactly two materials, e.g. [\"sand\", \"sand\"]");
    const auto a = materials.lookup(r, "materials", names[0]);
    const auto b = materials.lookup(r, "materials", names[1]);
    if (defined[a * nm + b])
      r.fail("materials", fmt::format("the pair {} / {} is defined twice", names[0], names[1]));
    ContactSpec spec;
    const std::string law = r.choice("law", {"linear", "hertz_mindlin"});
    r.allow({"normal_stiffness", "tangential_stiffness_ratio"});
    if (law == "linear") {
      spec.law = NormalLaw::linear;
      spec.normal_stiffness =
          r.check("normal_stiffness", r.number("normal_stiffness"), is_positive, "> 0 N/m");
      spec.tangential_stiffness_ratio =
          r.check("tangential_stiffness_ratio", r.number_or("tangential_stiffness_ratio", 1.0),
                  is_non_negative, ">= 0");
    } else {
      spec.law = NormalLaw::hertz_mindlin;
      if (r.has("normal_stiffness"))
        r.fail("normal_stiffness",
               "does not apply to hertz_mindlin (set youngs_modulus and poisson_ratio on the materials)");
      for (auto idx : {a, b}) {
        if (!(sim.materials[idx].youngs_modulus > 0.0)) {
          r.fail("law", fmt::format("hertz_mindlin needs youngs_modulus > 0 on material \"{}\"",
                                    sim.materials[idx].name));
        }
      }
    }
    spec.restitution = r.check(
        "restitution", r.number("restitution"), [](double v) { return v > 0.0 && v <= 1.0; }, "in (0, 1]");
    spec.friction = r.check("friction", r.number_or("friction", 0.0), is_non_negative, ">= 0");
    spec.rolling_friction =
        r.check("rolling_friction", r.number_or("rolling_friction", 0.0), is_non_negative, ">= 0");
    if (const toml::table* bt = r.optional_table("bond")) {
      // A contact bond (PFC's linear contact bond): made by a stage's
      // make_bonds between the pairs touching then.
      if (spec.law != NormalLaw::linear)
        r.fail("bond", "a contact bond needs law = \"linear\" (its spring also pulls, which Hertz's cannot)");
      TableReader br(*bt, r.where() + " bond", r.file());
      const char* unit = D == 2 ? ">= 0 N per metre of thickness" : ">= 0 N";
      spec.bond_tensile_strength =
          br.check("tensile_strength", br.number("tensile_strength"), is_non_negative, unit);
      spec.bond_shear_strength =
          br.check("shear_strength", br.number("shear_strength"), is_non_negative, unit);
      if (spec.bond_tensile_strength == 0.0 && spec.bond_shear_strength == 0.0)
        br.fail("tensile_strength",
                "a bond with both strengths 0 would break at once: give one > 0, or remove "
                "'bond'");
      // A bond that also carries a moment (YADE's cohesive moment law): a
      // stiffness ratio and its strength, given together.
      const char* moment_unit = D == 2 ? "> 0 N m per metre of thickness" : "> 0 N m";
      auto moment_part = [&](const char* ratio_key, const char* strength_key, double& ratio,
                             double& strength) {
        if (auto v = br.optional_number(ratio_key)) {
          ratio = br.check(
              ratio_key, *v, [](double x) { return x > 0.0; },
              "> 0 (k = ratio x k_n x R*^2, R* = r_i r_j / (r_i + r_j)); leave it out for none");
          if (!br.has(strength_key))
            br.fail(ratio_key, fmt::format("needs '{}' too (the moment at which the bond breaks, {})",
                                           strength_key, moment_unit));
          strength = br.check(
              strength_key, br.number(strength_key), [](double x) { return x > 0.0; }, moment_unit);
        } else if (br.has(strength_key)) {
          br.fail(strength_key, fmt::format("applies with '{}' (> 0), the bond's stiffness in that sense: "
                                            "without it the bond carries no such moment",
                                            ratio_key));
        }
      };
      moment_part("bending_stiffness_ratio", "bending_strength", spec.bond_bending_stiffness_ratio,
                  spec.bond_bending_strength);
      if constexpr (D == 3) {
        moment_part("twisting_stiffness_ratio", "twisting_strength", spec.bond_twisting_stiffness_ratio,
                    spec.bond_twisting_strength);
      } else {
        for (const char* key : {"twisting_stiffness_ratio", "twisting_strength"}) {
          if (br.has(key))
            br.fail(key,
                    "a 2D bond does not twist (discs turn in the plane only): bending_stiffness_ratio "
                    "and bending_strength give its moment");
        }
      }
      // Strengths that vary from bond to bond: Weibull's modulus of a factor
      // of mean 1 on all of a bond's strengths.
      if (auto v = br.optional_number("strength_weibull_modulus")) {
        spec.bond_strength_weibull_modulus = br.check(
            "strength_weibull_modulus", *v, [](double m) { return m >= 0.5 && m <= 1000.0; },
            "in [0.5, 1000] (Weibull's modulus: about 3-10 for cemented sand and rock, larger for less "
            "scatter); leave it out for equal strengths");
        if (auto seed = br.optional_integer("strength_seed")) {
          if (*seed < 0) br.fail("strength_seed", "must be an integer >= 0");
          spec.bond_strength_seed = static_cast<std::uint64_t>(*seed);
        }
      } else if (br.has("strength_seed")) {
        br.fail("strength_seed",
                "applies with 'strength_weibull_modulus' (the scatter of the bonds' strengths), which is "
                "not given");
      }
      br.finish();
    }
    sim.contact_table.set(a, b, make_pair_parameters(sim.materials[a], sim.materials[b], spec));
    defined[a * nm + b] = defined[b * nm + a] = true;
  });

  // [[wall]]
  std::map<std::string, std::size_t> wall_index;
  std::vector<std::string> wall_names;
  std::vector<WallBarrier<D>> wall_barriers;
  std::vector<bool> wall_is_barrier;
  std::vector<std::size_t> solid_walls;        // walls that take up pore volume
  std::vector<std::size_t> impermeable_walls;  // of them, those that close the faces they cover
  std::string solid_wall_prefix;               // where the first was asked for
  std::vector<std::tuple<std::size_t, const toml::table*, std::string>> stress_servos;
  for_each_table(top, "wall", "wall", [&](TableReader& r, int) {
    Wall<D> w;
    w.name = r.string("name");
    if (wall_index.count(w.name) != 0) r.fail("name", fmt::format("wall \"{}\" is defined twice", w.name));
    Vec<D> box_lo = Vec<D>::Zero();  // a box's corners as given (an impermeable plate's extent)
    Vec<D> box_hi = Vec<D>::Zero();
    if (const toml::table* bt = r.optional_table("box")) {
      // A box wall: min and max corners (equal along an axis for a plate).
      for (auto k : {"point", "normal"}) {
        if (r.has(k))
          r.fail(k, fmt::format("a box wall is placed by 'box' alone; remove '{}' (a plane has 'point' and "
                                "'normal', a box 'box = {{ min = [...], max = [...] }}')",
                                k));
      }
      TableReader br(*bt, r.where() + " box", r.file());
      const Vec<D> lo = to_vec<D>(br.numbers("min", D));
      const Vec<D> hi = to_vec<D>(br.numbers("max", D));
      for (int k = 0; k < D; ++k) {
        if (!(lo[k] <= hi[k])) {
          br.fail("max", fmt::format("must be >= min along every axis (a plate has min = max along one); "
                                     "along {} min = {} and max = {}",
                                     "xyz"[k], TableReader::format_number(lo[k]),
                                     TableReader::format_number(hi[k])));
        }
      }
      w.shape = WallShape::box;
      box_lo = lo;
      box_hi = hi;
      w.point = 0.5 * (lo + hi);
      w.half = 0.5 * (hi - lo);
      if (br.has("rotation")) w.axes = read_box_rotation<D>(br);
      br.finish();
    } else if (const toml::table* ct = r.optional_table("cylinder")) {
      read_cylinder<D>(r, *ct, w);
    } else if (const toml::table* mt = r.optional_table("mesh")) {
      scene.notes.push_back(read_mesh<D>(r, *mt, base, w));
    } else {
      if (!r.has("point") && !r.has("normal")) {
        r.fail_table(
            "a wall needs 'point' and 'normal' (an infinite plane), 'box = { min = [...], max = "
            "[...] }' (a box or plate), 'cylinder = { centre = [...], radius = ... }' (a cylinder; 2D: a "
            "circle) or 'mesh = { file = \"...stl\" }' (3D: a surface of triangles)");
      }
      w.point = to_vec<D>(r.numbers("point", D));
      w.normal = read_direction<D>(r, "normal", std::nullopt);
    }
    // A plane or box turns about its rotation centre: by default its point
    // (a box's centre).
    w.pivot = w.point;
    if (r.has("rotation_centre")) {
      if (w.is_cylinder()) {
        r.fail("rotation_centre",
               "a cylinder turns about its own axis (its 'angular_velocity'); a rotation centre is for a "
               "plane or box wall");
      }
      w.pivot = to_vec<D>(r.numbers("rotation_centre", D));
      if (!w.pivot.allFinite()) r.fail("rotation_centre", "must be finite, m");
    }
    w.material = materials.lookup(r, "material", r.string("material"));
    // An impermeable plate is a barrier; an impermeable box with a
    // thickness, or plane, displaces the fluid and closes the faces it
    // covers.
    const bool impermeable = r.boolean_or("impermeable", false);
    const bool plate = w.is_box() && w.half.minCoeff() == 0.0;
    const bool sealed = impermeable && !plate;
    if (sealed && r.has("displaces_fluid") && !r.boolean_or("displaces_fluid", true)) {
      r.fail(
          "displaces_fluid",
          "an impermeable box with a thickness, or plane, displaces the fluid: leave this out, or make the "
          "wall permeable");
    }
    const bool displaces_fluid = r.boolean_or("displaces_fluid", false) || sealed;
    if (w.is_mesh() && (impermeable || displaces_fluid)) {
      r.fail(impermeable ? "impermeable" : "displaces_fluid",
             "a mesh wall lets the pore water through (the fluid's grid is Cartesian and cannot follow its "
             "facets); leave this out, and bound the water with the grid's sides, barriers or impermeable "
             "box walls");
    }
    if (w.is_cylinder() && (impermeable || displaces_fluid)) {
      r.fail(impermeable ? "impermeable" : "displaces_fluid",
             "a cylinder wall lets the pore water through (the fluid's grid is Cartesian and cannot follow "
             "its curve); leave this out, and bound the water with the grid's sides, barriers or impermeable "
             "box walls");
    }
    Vec<D> spin_axis = Vec<D>::Zero();
    read_wall_motion<D>(r, w.shape, displaces_fluid, w.velocity, w.motion, w.servo, w.servo_axis, w.spin,
                        spin_axis, w.radius_rate, w.oscillation);
    if (!w.is_cylinder() && D == 3) w.axis = spin_axis;
    if (impermeable && plate) {
      wall_barriers.push_back(plate_barrier<D>(r, w, box_lo, box_hi));
    }
    wall_is_barrier.push_back(impermeable && plate);
    if (sealed) {
      if (w.is_box() && w.axes != Eigen::Matrix<double, D, D>::Identity()) {
        r.fail(
            "impermeable",
            "an impermeable box closes the fluid grid's faces it covers, so it lies along the grid's axes: "
            "it cannot be rotated");
      }
      if (w.is_plane() && grid_axis_of<D>(w.normal) < 0) {
        r.fail("impermeable",
               "an impermeable plane needs its normal along an axis of the fluid grid (e.g. [0, -1] for a "
               "platen over a 2D sample)");
      }
      impermeable_walls.push_back(sim.walls.size());
    }
    if (displaces_fluid) {
      const std::string key = r.has("displaces_fluid") ? "displaces_fluid" : "impermeable";
      if (w.is_plane() && grid_axis_of<D>(w.normal) < 0) {
        r.fail("displaces_fluid",
               "a plane wall takes up the pore volume behind it only with its normal along an axis of the "
               "fluid grid (e.g. [0, -1] for a platen over a 2D sample); give a box wall for any other "
               "orientation");
      }
      if (w.is_box() && w.half.minCoeff() == 0.0) {
        r.fail("displaces_fluid",
               "a plate (min = max along an axis) has no volume to take up; give it a thickness");
      }
      if (solid_walls.empty()) {
        solid_wall_prefix =
            fmt::format("{}: error: {} key '{}': ", r.location(r.raw(key)->source()), r.where(), key);
      }
      solid_walls.push_back(sim.walls.size());
    }
    check_wall_in_period<D>(r, w, sim.periodic);
    if (w.motion == WallMotion::servo && w.servo.by_stress) {
      stress_servos.emplace_back(sim.walls.size(), &r.table(), r.where());
    }
    wall_index[w.name] = sim.walls.size();
    wall_names.push_back(w.name);
    sim.walls.push_back(w);
  });
  // A stress servo's loaded area is bounded by walls read after it too.
  for (const auto& [i, table, where] : stress_servos) {
    TableReader r(*table, where, file);
    require_loaded_area<D>(r, sim.walls, i, sim.periodic);
  }

  // [[clump_template]]: shapes the generators' `clump` key places.
  std::map<std::string, ClumpShape<D>> clump_shapes;
  std::vector<std::string> clump_names;
  for_each_table(top, "clump_template", "clump_template", [&](TableReader& r, int) {
    auto [name, shape] = read_clump_template<D>(r);
    if (clump_shapes.count(name) != 0)
      r.fail("name", fmt::format("\"{}\" is already a [[clump_template]]", name));
    clump_shapes.emplace(name, std::move(shape));
    clump_names.push_back(name);
  });

  // A table's `clump`: a [[clump_template]]'s shape (none without the key).
  auto lookup_clump = [&](TableReader& r) -> const ClumpShape<D>* {
    const auto name = r.optional_string("clump");
    if (!name) return nullptr;
    auto it = clump_shapes.find(*name);
    if (it == clump_shapes.end()) {
      std::string hint;
      if (auto near = did_you_mean(*name, clump_names); !near.empty())
        hint = fmt::format(" (did you mean \"{}\"?)", near);
      r.fail("clump", fmt::format("\"{}\" is not a [[clump_template]]'s name{}{}", *name, hint,
                                  clump_names.empty() ? ": the scene has none" : ""));
    }
    return &it->second;
  };

  // [[particles]]
  std::vector<std::string> origin;
  for_each_table(top, "particles", "particles", [&](TableReader& r, int index) {
    const std::string gen = r.choice("generator", {"lattice", "column", "random", "csv"});
    const auto mat = materials.lookup(r, "material", r.string("material"));
    const bool fixed = r.boolean_or("fixed", false);
    const ClumpShape<D>* clump = lookup_clump(r);
    Packing<D> pk;
    if (gen == "lattice") {
      const Vec<D> lo = to_vec<D>(r.numbers("min", D));
      const Vec<D> hi = to_vec<D>(r.numbers("max", D));
      const double radius = r.check("radius", r.number("radius"), is_positive, "> 0 m");
      const double spacing = r.check(
          "spacing", r.number_or("spacing", 2.0 * radius), [&](double v) { return v >= 2.0 * radius; },
          ">= 2 x radius (m)");
      const std::string arrangement =
          r.optional_choice("arrangement", D == 2 ? std::vector<std::string>{"square", "hexagonal"}
                                                  : std::vector<std::string>{"cubic", "fcc"})
              .value_or(D == 2 ? "square" : "cubic");
      const bool dense = arrangement == "hexagonal" || arrangement == "fcc";
      // Sites per spacing^D: 1 cubic or square, sqrt 2 fcc, 2/sqrt 3 hexagonal.
      double sites = dense ? 1.5 : 1.0;
      for (int k = 0; k < D; ++k) sites *= std::max(0.0, (hi[k] - lo[k]) / spacing + 1.0);
      check_count_fits(r, "spacing", sites);
      pk = dense ? dense_lattice_packing<D>(lo, hi, spacing, radius)
                 : lattice_packing<D>(lo, hi, spacing, radius);
    } else if (gen == "column") {
      const Vec<D> base = to_vec<D>(r.numbers("base", D));
      Vec<D> up = Vec<D>::Zero();
      up[D - 1] = 1.0;
      const Vec<D> axis = read_direction<D>(r, "axis", up);
      const auto count = r.integer("count");
      if (count < 1) r.fail("count", "must be >= 1");
      check_count_fits(r, "count", static_cast<double>(count));
      if (count > std::numeric_limits<int>::max()) r.fail("count", "must be at most 2^31 - 1");
      const double radius = r.check("radius", r.number("radius"), is_positive, "> 0 m");
      const double gap = r.check("gap", r.number_or("gap", 0.0), is_non_negative, ">= 0 m");
      pk = column_packing<D>(base, axis, static_cast<int>(count), radius, gap);
    } else if (gen == "random") {
      // A box, or a cylinder (its box the one that holds it).
      const std::optional<Cylinder<D>> cylinder = read_cylinder<D>(r);
      const Cylinder<D>* in_cylinder = cylinder ? &*cylinder : nullptr;
      const Vec<D> lo = cylinder ? cylinder->lower() : to_vec<D>(r.numbers("min", D));
      const Vec<D> hi = cylinder ? cylinder->upper() : to_vec<D>(r.numbers("max", D));
      // How many: a count, or as many as make the box's porosity.
      if (r.has("count") && r.has("porosity")) r.fail("porosity", "give 'count' or 'porosity', not both");
      if (!r.has("count") && !r.has("porosity")) {
        r.missing(
            "count",
            "an integer; or instead 'porosity', a number in (0, 1): as many particles as leave that fraction "
            "of the box empty");
      }
      std::int64_t count = 0;
      double porosity = 0.0;
      if (r.has("count")) {
        count = r.integer("count");
        if (count < 1) r.fail("count", "must be >= 1");
        check_count_fits(r, "count", static_cast<double>(count));
      } else {
        porosity = r.check(
            "porosity", r.number("porosity"), [](double v) { return v > 0.0 && v < 1.0; }, "in (0, 1)");
      }
      const RadiusDistribution dist = read_radius(r, D);
      for (int k = 0; k < D; ++k) {
        if (hi[k] - lo[k] < 2.0 * dist.largest())
          r.fail(cylinder ? "cylinder" : "max",
                 fmt::format("the {} must be wider than the largest particle in every direction",
                             cylinder ? "cylinder" : "box"));
      }
      if (r.has("porosity")) {
        // At most this many of the smallest grains.
        double box = 1.0;
        for (int k = 0; k < D; ++k) box *= hi[k] - lo[k];
        if (cylinder) box = cylinder->volume();
        check_count_fits(r, "porosity", (1.0 - porosity) * box / particle_volume<D>(dist.smallest()));
      }
      const auto seed = r.optional_integer("seed").value_or(1);
      const auto attempts = r.optional_integer("max_attempts").value_or(1000);
      // A box that spans a [periodic] axis's whole period fills it: the
      // cloud wraps round, grains straddling its ends.
      std::array<bool, D> wrap{};
      for (int k = 0; k < D; ++k) {
        const auto& cell = sim.periodic;
        const double tol = 1e-9 * cell.length[k];
        wrap[k] = !cylinder && cell.periodic[k] && std::abs(lo[k] - cell.lower[k]) <= tol &&
                  std::abs(hi[k] - (cell.lower[k] + cell.length[k])) <= tol;
      }
      try {
        pk = r.has("count")
                 ? random_packing<D>(lo, hi, count, dist, static_cast<std::uint64_t>(seed), attempts, wrap,
                                     in_cylinder)
                 : random_packing_to_porosity<D>(lo, hi, porosity, dist, static_cast<std::uint64_t>(seed),
                                                 attempts, wrap, in_cylinder);
      } catch (const std::runtime_error& e) {
        r.fail(r.has("count") ? "count" : "porosity", e.what());
      }
      if (dist.kind == RadiusDistribution::Kind::grading) {
        if (auto note = grading_followed_loosely<D>(dist, pk.radius, r.where())) scene.notes.push_back(*note);
      }
      std::string wrapped;
      for (int k = 0; k < D; ++k) {
        if (wrap[k]) wrapped += std::string(wrapped.empty() ? "" : " and ") + "xyz"[k];
      }
      if (!wrapped.empty()) {
        scene.notes.push_back(
            fmt::format("{}: the box spans the period along {}, so the cloud wraps round it: "
                        "grains straddle the period's ends",
                        r.where(), wrapped));
      }
    } else {
      const std::string rel = r.string("file");
      const std::string path = (base / rel).string();
      try {
        pk = read_packing_csv<D>(path);
      } catch (const std::runtime_error& e) {
        r.fail("file", e.what());
      }
    }
    // Sizes and boxes near the end of double precision (radius = 1e308)
    // can place a particle at infinity.
    for (std::size_t i = 0; i < pk.position.size(); ++i) {
      if (!pk.position[i].allFinite() || !std::isfinite(pk.radius[i])) {
        r.fail_table(
            fmt::format("the {} generator places its particle {} at a position that is not finite: "
                        "its sizes or box are beyond double precision",
                        gen, i));
      }
    }
    const Vec<D> velocity =
        to_vec<D>(r.optional_numbers("velocity", D).value_or(std::vector<double>(D, 0.0)));
    if (pk.position.empty()) r.fail_table("made no particles (is the box smaller than one particle?)");
    const double density = sim.materials[mat].density;
    if (std::any_of(pk.clump.begin(), pk.clump.end(), [](std::int64_t c) { return c >= 0; })) {
      if (clump != nullptr)
        r.fail("clump", "the file's clump column gives its clumps already: leave 'clump' out");
      if (r.has("orientation") || r.has("orientation_seed"))
        r.fail(r.has("orientation") ? "orientation" : "orientation_seed",
               "the file's clumps stand as the file has them: leave it out");
      const std::size_t before = sim.particles.size();
      const std::size_t made = add_clumps_from_file<D>(r, sim, pk, mat, fixed, velocity);
      scene.notes.push_back(
          fmt::format("{}: {} clumps from the file's clump column ({} of its {} particles)", r.where(), made,
                      sim.particles.size() - before -
                          static_cast<std::size_t>(std::count(pk.clump.begin(), pk.clump.end(), -1)),
                      pk.position.size()));
      for (std::size_t k = before; k < sim.particles.size(); ++k)
        origin.push_back(fmt::format("{} ([[particles]] #{})", r.here(), index));
      return;
    }
    if (clump != nullptr) {
      const std::size_t added = add_clumps<D>(r, sim, *clump, pk, mat, fixed, velocity);
      scene.notes.push_back(fmt::format(
          "{}: {} clumps \"{}\" of {} {} each ({} particles), each in place of a grain of the generator's "
          "size: its members' sizes are those the grading reports",
          r.where(), pk.position.size(), *r.optional_string("clump"), clump->radius.size(),
          D == 2 ? "discs" : "spheres", added));
      for (std::size_t k = 0; k < added; ++k)
        origin.push_back(fmt::format("{} ([[particles]] #{})", r.here(), index));
      return;
    }
    if (r.has("orientation") || r.has("orientation_seed"))
      r.fail(r.has("orientation") ? "orientation" : "orientation_seed", "orients clumps: give 'clump' too");
    for (std::size_t k = 0; k < pk.position.size(); ++k) {
      sim.particles.add(pk.position[k], pk.radius[k], density, mat, fixed, velocity);
      origin.push_back(fmt::format("{} ([[particles]] #{})", r.here(), index));
    }
  });
  if (!sim.clumps.empty()) sim.clumps.refresh(sim.particles);
  if (sim.particles.size() == 0 && (!top.has("inlet") || top.has("fluid"))) {
    top.fail_table(top.has("inlet")
                       ? "needs at least one [[particles]] generator that makes particles: with a "
                         "[fluid], grains must be there from the start (the permeability's grain "
                         "size comes from them)"
                       : "needs at least one [[particles]] generator that makes particles (or "
                         "an [[inlet]] that adds them during the run)");
  }
  if (periodic_reader && sim.particles.size() > 0) {
    check_periods<D>(*periodic_reader, sim, origin);
    // Members that stick out of the period go back in (as each list build
    // puts them), their clumps' centres inside.
    for (auto& x : sim.particles.position) x = sim.periodic.wrap(x);
  }

  // Every pair of materials that can meet needs a [[contact]].
  {
    std::vector<bool> used(nm, false);
    std::vector<bool> wall_used(nm, false);
    for (auto m : sim.particles.material) used[m] = true;
    for (const auto& w : sim.walls) wall_used[w.material] = true;
    for (std::size_t a = 0; a < nm; ++a) {
      for (std::size_t b = 0; b < nm; ++b) {
        if (used[a] && (used[b] || wall_used[b]) && !defined[a * nm + b]) {
          top.fail_table(fmt::format("no [[contact]] for materials \"{}\" and \"{}\", which can touch",
                                     sim.materials[a].name, sim.materials[b].name));
        }
      }
    }
  }

  // [fluid]
  if (const toml::table* t = top.optional_table("fluid")) {
    scene.fluid = read_fluid<D>(*t, file, sim.particles, wall_barriers, sim.periodic, sim.walls, solid_walls,
                                impermeable_walls);
    sim.force_field = scene.fluid.get();
  } else if (top.has("fluid")) {
    top.fail("fluid", "must be a table ([fluid])");
  }
  if (!scene.fluid && !solid_walls.empty())
    throw SceneError(solid_wall_prefix + "needs a pore fluid to take up: the scene has no [fluid] table");
  if (!scene.fluid && !wall_barriers.empty()) {
    throw SceneError(wall_barriers.front().error_prefix +
                     "needs a pore fluid to keep out: the scene has no [fluid] table");
  }

  // [domain]
  if (const toml::table* t = top.optional_table("domain")) {
    TableReader r(*t, "[domain]", file);
    read_domain<D>(r, sim, scene.fluid.get(), origin, scene.notes);
  } else if (top.has("domain")) {
    top.fail("domain", "must be a table ([domain] with min = [...], max = [...])");
  }

  // [[inlet]]: grains added during the run.
  std::vector<std::string> inlet_names;
  for_each_table(top, "inlet", "inlet", [&](TableReader& r, int) {
    const auto mat = materials.lookup(r, "material", r.string("material"));
    const ClumpShape<D>* clump = lookup_clump(r);
    scene.inlets.push_back(read_inlet<D>(r, mat, sim, scene.fluid.get(), inlet_names, clump));
    inlet_names.push_back(scene.inlets.back().name);
    const auto& in = scene.inlets.back();
    std::string box;
    for (int k = 0; k < D; ++k)
      box += fmt::format("{}{} in [{:.6g}, {:.6g}]", k == 0 ? "" : ", ", "xyz"[k], in.lower[k], in.upper[k]);
    if (in.cylinder) {
      // The cylinder, by its axis and radius (2D: a circle).
      const auto& c = *in.cylinder;
      box = D == 3 ? fmt::format("a cylinder of radius {:.6g} along {} (within {})", c.radius, "xyz"[c.axis],
                                 box)
                   : fmt::format("a circle of radius {:.6g} about ({:.6g}, {:.6g})", c.radius, c.centre[0],
                                 c.centre[1]);
    }
    std::string limit;
    if (in.max_count != std::numeric_limits<std::uint64_t>::max())
      limit += fmt::format(", at most {} {}", in.max_count, in.clump ? "clumps" : "grains");
    if (std::isfinite(in.max_mass))
      limit += fmt::format(", at most {:.6g} kg{}", in.max_mass, D == 2 ? " per metre" : "");
    scene.notes.push_back(fmt::format(
        "[[inlet]] {}: {} every {:.6g} s into {} m{}{}{}", in.name,
        in.rate > 0.0 ? fmt::format("{:.6g} {}/s", in.rate, in.clump ? "clumps" : "grains")
                      : fmt::format("{:.6g} kg/s{}", in.mass_rate, D == 2 ? " per metre" : ""),
        in.interval, box, limit,
        in.clump ? fmt::format("; clumps \"{}\" of {} {}, {}", in.clump_name, in.clump->radius.size(),
                               D == 2 ? "discs" : "spheres", in.aligned ? "aligned" : "turned at random")
                 : "",
        in.active ? "" : "; inactive until a stage sets it active"));
    // The new grains meet the particles, the walls and each other.
    std::vector<bool> meets(nm, false);
    for (auto m : sim.particles.material) meets[m] = true;
    for (const auto& w : sim.walls) meets[w.material] = true;
    for (const auto& other : scene.inlets) meets[other.material] = true;
    for (std::size_t b = 0; b < nm; ++b) {
      if (meets[b] && !defined[mat * nm + b]) {
        r.fail("material", fmt::format("no [[contact]] for materials \"{}\" and \"{}\", which can touch",
                                       sim.materials[mat].name, sim.materials[b].name));
      }
    }
  });
  if (!scene.inlets.empty()) {
    const auto [r_min, r_max] = radius_range(sim.particles, scene.inlets);
    if (sim.skin == 0.0) sim.skin = 0.2 * r_min;  // the automatic skin, over the inlets' grains too
    for (int k = 0; k < D; ++k) {
      if (sim.periodic.periodic[k] &&
          !(sim.periodic.length[k] > 2.0 * (2.0 * r_max + sim.skin_or_default()))) {
        periodic_reader->fail(
            std::string(1, "xyz"[k]),
            fmt::format("the period {:.6g} m must exceed 2 x (2 x largest radius + skin) = {:.6g} m, "
                        "the inlets' grains counted, so that a particle meets one image of each "
                        "neighbour",
                        sim.periodic.length[k], 2.0 * (2.0 * r_max + sim.skin_or_default())));
      }
    }
  }

  // Contact bonds: how far one stretches before it breaks, against the
  // skin (a pair further apart than the skin at a list build is no longer
  // listed, and its bond is lost).
  for (std::size_t a = 0; a < nm; ++a) {
    for (std::size_t b = a; b < nm; ++b) {
      const PairParameters& pp = sim.contact_table(a, b);
      if (!pp.bondable) continue;
      // With strengths that vary, the strongest bond in a thousand: the
      // factor whose Weibull exceedance is 1e-3.
      const double strongest = pp.bond_strength_quantile(1e-3);
      const double stretch = strongest * pp.bond_tensile / pp.normal_stiffness;
      const double skin = sim.skin_or_default();
      scene.notes.push_back(fmt::format(
          "[[contact]] {} / {}: contact bonds (tensile strength {:.6g} N{}, shear {:.6g} N{}{}) stretch by "
          "up "
          "to {:.6g} m before they break{}",
          sim.materials[a].name, sim.materials[b].name, pp.bond_tensile, D == 2 ? "/m" : "", pp.bond_shear,
          D == 2 ? "/m" : "",
          pp.bond_strength_varies()
              ? fmt::format("; the means of strengths scattered with Weibull's modulus {:.6g}, the strongest "
                            "bond in a thousand {:.4g} times as strong",
                            pp.bond_weibull_modulus, strongest)
              : "",
          stretch,
          stretch < 0.5 * skin
              ? ""
              : fmt::format(
                    "; more than half the skin ({:.6g} m): a bond may be stretched so far between list "
                    "builds that a build no longer lists its pair and drops it (counted as broken). "
                    "Set [simulation] skin above {:.6g} m",
                    skin, 2.0 * stretch)));
    }
  }

  // [output] and [[probe]]
  if (const toml::table* t = top.optional_table("output")) {
    TableReader r(*t, "[output]", file);
    scene.output.probe_interval =
        r.check("probe_interval", r.number_or("probe_interval", 0.0), is_non_negative, ">= 0 s");
    scene.output.snapshot_interval =
        r.check("snapshot_interval", r.number_or("snapshot_interval", 0.0), is_non_negative, ">= 0 s");
    scene.output.contacts = r.boolean_or("contacts", true);
    r.finish();
  }
  std::vector<std::string> probe_names;
  // A probe's 'wall', by name.
  const auto probe_wall = [&](TableReader& r) {
    const std::string w = r.string("wall");
    auto it = wall_index.find(w);
    if (it == wall_index.end()) {
      std::string hint;
      if (auto s = did_you_mean(w, wall_names); !s.empty()) hint = fmt::format(" (did you mean \"{}\"?)", s);
      r.fail("wall", fmt::format("no wall named \"{}\"{}", w, hint));
    }
    return it->second;
  };
  for_each_table(top, "probe", "probe", [&](TableReader& r, int) {
    ProbeSpec p;
    p.name = r.string("name");
    if (p.name.empty() || p.name.find_first_of(",\"\n") != std::string::npos || p.name == "time") {
      r.fail("name", "must be a non-empty name without commas or quotes, other than \"time\"");
    }
    if (std::find(probe_names.begin(), probe_names.end(), p.name) != probe_names.end()) {
      r.fail("name", fmt::format("probe \"{}\" is defined twice", p.name));
    }
    probe_names.push_back(p.name);
    const std::string q = r.choice("quantity", {"particle_position",
                                                "particle_velocity",
                                                "wall_position",
                                                "wall_force",
                                                "wall_fluid_force",
                                                "wall_torque",
                                                "wall_radius",
                                                "wall_stress",
                                                "wall_target",
                                                "kinetic_energy",
                                                "elastic_energy",
                                                "gravitational_energy",
                                                "gravity_work",
                                                "fluid_work",
                                                "boundary_work",
                                                "damping_dissipation",
                                                "contact_dissipation",
                                                "contact_count",
                                                "coordination",
                                                "max_overlap",
                                                "unbalanced_force",
                                                "pore_pressure",
                                                "pore_pressure_profile",
                                                "fluid_inflow",
                                                "side_pressure",
                                                "fluid_balance",
                                                "fluid_iterations",
                                                "screen_inflow_profile",
                                                "particles_in_box",
                                                "mean_particle_position",
                                                "stress",
                                                "fabric",
                                                "porosity",
                                                "removed_particles",
                                                "removed_mass",
                                                "particle_fluid_force",
                                                "fluid_force",
                                                "inserted_particles",
                                                "inserted_mass",
                                                "bonds",
                                                "broken_bonds",
                                                "cell_length",
                                                "cell_strain_rate",
                                                "cell_strain",
                                                "cell_stress"});
    r.allow({"particle", "component", "wall", "position", "side", "from", "to", "points", "min", "max"});
    if (q == "inserted_particles" || q == "inserted_mass") {
      if (scene.inlets.empty()) {
        r.fail("quantity",
               fmt::format("\"{}\" counts what an [[inlet]] adds: the scene has no [[inlet]]", q));
      }
      if (auto name = r.optional_string("inlet")) {
        const auto it = std::find(inlet_names.begin(), inlet_names.end(), *name);
        if (it == inlet_names.end()) {
          std::string hint;
          if (auto h = did_you_mean(*name, inlet_names); !h.empty())
            hint = fmt::format(" (did you mean \"{}\"?)", h);
          r.fail("inlet", fmt::format("no [[inlet]] named \"{}\"{}", *name, hint));
        }
        p.inlet = it - inlet_names.begin();
      }
      for (auto k :
           {"particle", "component", "wall", "position", "side", "from", "to", "points", "min", "max"}) {
        if (r.has(k)) r.fail(k, fmt::format("does not apply to quantity \"{}\"", q));
      }
      p.quantity =
          q == "inserted_particles" ? ProbeQuantity::inserted_particles : ProbeQuantity::inserted_mass;
      r.finish();
      scene.output.probes.push_back(p);
      return;
    }
    if (r.has("inlet")) r.fail("inlet", fmt::format("does not apply to quantity \"{}\"", q));
    if (q == "cell_length" || q == "cell_strain_rate" || q == "cell_strain" || q == "cell_stress") {
      for (int k = 0; k < D; ++k) {
        if (!sim.periodic.periodic[k]) {
          r.fail("quantity",
                 fmt::format("\"{}\" reads the periodic cell, which must repeat along every axis: "
                             "[periodic] has no '{}'",
                             q, "xyz"[k]));
        }
      }
      for (auto k : {"particle", "wall", "position", "side", "from", "to", "points", "min", "max"}) {
        if (r.has(k)) r.fail(k, fmt::format("does not apply to quantity \"{}\"", q));
      }
      if (q == "cell_stress") {
        p.quantity = ProbeQuantity::cell_stress;
        p.tensor = tensor_component<D>(r, "component", true);
      } else if (q == "cell_strain") {
        p.quantity = ProbeQuantity::cell_strain;
        const std::string c =
            r.choice("component", D == 2 ? std::vector<std::string>{"x", "y", "volumetric"}
                                         : std::vector<std::string>{"x", "y", "z", "volumetric"});
        p.component = c == "volumetric" ? -1 : c[0] - 'x';
      } else {
        p.quantity = q == "cell_length" ? ProbeQuantity::cell_length : ProbeQuantity::cell_strain_rate;
        p.component = static_cast<int>(axis_component<D>(r, "component", false));
      }
      r.finish();
      scene.output.probes.push_back(p);
      return;
    }
    const bool fluid_probe = q == "pore_pressure" || q == "pore_pressure_profile" || q == "fluid_inflow" ||
                             q == "side_pressure" || q == "fluid_balance" || q == "fluid_iterations" ||
                             q == "screen_inflow_profile" || q == "wall_fluid_force" ||
                             q == "particle_fluid_force" || q == "fluid_force";
    if (fluid_probe && !scene.fluid) {
      r.fail("quantity", fmt::format("\"{}\" needs a pore fluid: the scene has no [fluid] table", q));
    }
    if ((q == "bonds" || q == "broken_bonds") && !sim.contact_table.any_bondable()) {
      r.fail("quantity", fmt::format("\"{}\" counts contact bonds: no [[contact]] of the scene has a 'bond' "
                                     "(bond = {{ tensile_strength = ..., shear_strength = ... }})",
                                     q));
    }
    if ((q == "removed_particles" || q == "removed_mass") && !sim.has_domain) {
      r.fail("quantity",
             fmt::format("\"{}\" counts what leaves the [domain]: the scene has no [domain] table "
                         "(min = [...], max = [...])",
                         q));
    }
    const bool box_probe = q == "particles_in_box" || q == "mean_particle_position" || q == "stress" ||
                           q == "fabric" || q == "porosity" || q == "fluid_force";
    for (std::string k : {"position", "side", "from", "to", "points", "min", "max"}) {
      const bool applies =
          (q == "pore_pressure" && k == "position") ||
          ((q == "fluid_inflow" || q == "side_pressure" || q == "screen_inflow_profile") && k == "side") ||
          (q == "pore_pressure_profile" && (k == "from" || k == "to" || k == "points")) ||
          (box_probe && (k == "min" || k == "max"));
      if (r.has(k) && !applies) r.fail(k, fmt::format("does not apply to quantity \"{}\"", q));
    }
    // The pore pressure's and the flows' probes name no particle, wall or component.
    if (q == "pore_pressure" || q == "pore_pressure_profile" || q == "fluid_inflow" || q == "side_pressure" ||
        q == "fluid_balance" || q == "fluid_iterations" || q == "screen_inflow_profile") {
      for (auto k : {"particle", "component", "wall"}) {
        if (r.has(k)) r.fail(k, fmt::format("does not apply to quantity \"{}\"", q));
      }
    }
    if (q == "pore_pressure_profile") {
      // A line of points: one column per point, named NAME_0 .. NAME_{n-1}.
      const auto from = r.numbers("from", D);
      const auto to = r.numbers("to", D);
      const auto count = r.integer("points");
      if (count < 2 || count > 10000) r.fail("points", "must be 2..10000 points along the line");
      for (std::int64_t k = 0; k < count; ++k) {
        ProbeSpec pt;
        pt.name = fmt::format("{}_{}", p.name, k);
        pt.quantity = ProbeQuantity::pore_pressure;
        const double f = static_cast<double>(k) / static_cast<double>(count - 1);
        for (int a = 0; a < D; ++a) pt.position.push_back(from[a] + f * (to[a] - from[a]));
        scene.output.probes.push_back(pt);
      }
      return;
    }
    if (q == "screen_inflow_profile") {
      // A screened well's cells: one column per cell along its screen,
      // named NAME_0 .. NAME_{n-1}.
      std::vector<std::string> wells;
      for (const auto& source : scene.fluid->sources) {
        if (source.screened()) wells.push_back(source.name);
      }
      if (wells.empty()) {
        r.fail("quantity",
               "\"screen_inflow_profile\" reads a screened well's cells: the scene has no "
               "[[fluid.source]] with a 'screen'");
      }
      const std::string well = r.choice("side", wells);
      std::size_t i = 0;
      while (scene.fluid->sources[i].name != well) ++i;
      const std::size_t cells = source_cells(scene.fluid->grid, scene.fluid->sources[i]).size();
      for (std::size_t k = 0; k < cells; ++k) {
        ProbeSpec pt;
        pt.name = fmt::format("{}_{}", p.name, k);
        pt.quantity = ProbeQuantity::screen_inflow;
        pt.side = static_cast<int>(2 * D + scene.fluid->patches.size() + i);
        pt.screen_cell = k;
        scene.output.probes.push_back(pt);
      }
      return;
    }
    if (box_probe) {
      // The particles whose centres lie in [min, max] at each output time
      // (stress, fabric: their contacts; porosity: the grains' parts in the box).
      p.quantity = q == "particles_in_box"         ? ProbeQuantity::particles_in_box
                   : q == "mean_particle_position" ? ProbeQuantity::mean_particle_position
                   : q == "stress"                 ? ProbeQuantity::stress
                   : q == "fabric"                 ? ProbeQuantity::fabric
                   : q == "fluid_force"            ? ProbeQuantity::fluid_force
                                                   : ProbeQuantity::porosity;
      p.box_min = r.numbers("min", D);
      p.box_max = r.numbers("max", D);
      for (int k = 0; k < D; ++k) {
        if (!(p.box_max[k] > p.box_min[k])) {
          r.fail("max",
                 fmt::format("must be greater than 'min' along every axis; along {} min = {} and max = {}",
                             "xyz"[k], TableReader::format_number(p.box_min[k]),
                             TableReader::format_number(p.box_max[k])));
        }
        // Along a periodic axis each particle counts once, at its image in
        // the box: the box may lie anywhere but be no longer than the period.
        if (sim.periodic.periodic[k] &&
            p.box_max[k] - p.box_min[k] > sim.periodic.length[k] * (1.0 + 1e-12)) {
          r.fail("max",
                 fmt::format("the box is {} m long along {}, longer than the period {} m ([periodic] {}); "
                             "along a periodic axis it may lie anywhere but hold at most one period",
                             TableReader::format_number(p.box_max[k] - p.box_min[k]), "xyz"[k],
                             TableReader::format_number(sim.periodic.length[k]), "xyz"[k]));
        }
      }
      if (q == "mean_particle_position") {
        p.component = static_cast<int>(axis_component<D>(r, "component", false));
      } else if (q == "fluid_force") {
        p.component = static_cast<int>(axis_component<D>(r, "component", true));
      } else if (q == "stress") {
        p.tensor = tensor_component<D>(r, "component", true);
      } else if (q == "fabric") {
        // Its trace is 1: no "mean".
        p.tensor = tensor_component<D>(r, "component", false);
      } else if (r.has("component")) {
        r.fail("component", fmt::format("does not apply to quantity \"{}\"", q));
      }
      for (auto k : {"particle", "wall"}) {
        if (r.has(k)) r.fail(k, fmt::format("does not apply to quantity \"{}\"", q));
      }
    } else if (q == "pore_pressure") {
      p.quantity = ProbeQuantity::pore_pressure;
      p.position = r.numbers("position", D);
    } else if (q == "fluid_inflow" || q == "side_pressure") {
      p.quantity = q == "fluid_inflow" ? ProbeQuantity::fluid_inflow : ProbeQuantity::side_pressure;
      // A side, or a patch of one (index 2 D + its index in the patches),
      // or a source (after the patches).
      auto names = std::vector<std::string>(side_names, side_names + 2 * D);
      for (const auto& patch : scene.fluid->patches) names.push_back(patch.name);
      for (const auto& source : scene.fluid->sources) names.push_back(source.name);
      const std::string side = r.choice("side", names);
      p.side = static_cast<int>(std::find(names.begin(), names.end(), side) - names.begin());
      if (p.side < 2 * D && scene.fluid->grid.periodic[p.side / 2]) {
        r.fail("side",
               fmt::format("the fluid grid is periodic along {}: its side {} is no boundary (allowed: "
                           "a side along a non-periodic axis, a patch or a source)",
                           "xyz"[p.side / 2], side));
      }
    } else if (q == "fluid_balance" || q == "fluid_iterations") {
      p.quantity = q == "fluid_balance" ? ProbeQuantity::fluid_balance : ProbeQuantity::fluid_iterations;
    } else if (q == "particle_position" || q == "particle_velocity" || q == "particle_fluid_force") {
      p.quantity = q == "particle_position"   ? ProbeQuantity::particle_position
                   : q == "particle_velocity" ? ProbeQuantity::particle_velocity
                                              : ProbeQuantity::particle_fluid_force;
      const toml::node* n = r.raw("particle");
      if (n == nullptr) r.fail_table("missing required key 'particle' (an index, or \"top\")");
      if (n->is_string() && *n->value<std::string>() == "top") {
        p.particle = -1;
      } else if (n->is_integer()) {
        const auto idx = *n->value<std::int64_t>();
        // An inlet's grains are numbered on from the scene's; one not made
        // yet reads nan.
        if (!scene.inlets.empty()) {
          if (idx < 0)
            r.fail("particle", "must be a particle index >= 0 (0-based, in creation order) or \"top\"");
        } else if (idx < 0 || static_cast<std::size_t>(idx) >= sim.particles.size()) {
          r.fail("particle", fmt::format("must be in 0..{} (the scene has {} particles)",
                                         sim.particles.size() - 1, sim.particles.size()));
        }
        p.particle = idx;
      } else {
        r.fail("particle", "must be a particle index (0-based, in creation order) or \"top\"");
      }
      p.component = static_cast<int>(axis_component<D>(r, "component", true));
    } else if (q == "wall_position" || q == "wall_force" || q == "wall_fluid_force") {
      p.quantity = q == "wall_position" ? ProbeQuantity::wall_position
                   : q == "wall_force"  ? ProbeQuantity::wall_force
                                        : ProbeQuantity::wall_fluid_force;
      p.wall = probe_wall(r);
      if (p.quantity == ProbeQuantity::wall_fluid_force)
        p.barrier = fluid_thrust_barrier(r, *scene.fluid, sim.walls, p.wall, wall_is_barrier[p.wall]);
      p.component = static_cast<int>(axis_component<D>(r, "component", true));
    } else if (q == "wall_stress") {
      p.quantity = ProbeQuantity::wall_stress;
      p.wall = probe_wall(r);
      if (const LoadedArea a = loaded_area(sim.walls, p.wall, sim.periodic); !a.why_not.empty()) {
        r.fail("wall",
               fmt::format("wall \"{}\" has no loaded area to divide its load by: {} (allowed: a plane "
                           "wall normal to an axis, its cross-section bounded by a pair of plane walls "
                           "or a period along each other axis, or in 3D by a cylinder along its normal; "
                           "a cylinder, in 3D along an axis whose walls or period bound its height)",
                           sim.walls[p.wall].name, a.why_not));
      }
      if (r.has("component")) r.fail("component", "does not apply: the stress is normal to the wall");
    } else if (q == "wall_target") {
      p.quantity = ProbeQuantity::wall_target;
      p.wall = probe_wall(r);
      if (r.has("component"))
        r.fail("component",
               "does not apply: a servo's target is its load normal to the wall (N) or its stress (Pa)");
    } else if (q == "wall_torque" || q == "wall_radius") {
      const bool torque = q == "wall_torque";
      p.quantity = torque ? ProbeQuantity::wall_torque : ProbeQuantity::wall_radius;
      const std::string w = r.string("wall");
      auto it = wall_index.find(w);
      // The moment is about an axis: a cylinder's, a 3D plane's or box's
      // turn's (through its rotation centre), or in 2D the normal to the
      // plane of the discs through the wall's centre of rotation.
      auto fits = [&](const Wall<D>& wall) { return wall.is_cylinder() || (torque && wall.has_axis()); };
      if (it == wall_index.end() || !fits(sim.walls[it->second])) {
        std::vector<std::string> names;
        for (const auto& wall : sim.walls) {
          if (fits(wall)) names.push_back("\"" + wall.name + "\"");
        }
        r.fail("wall",
               fmt::format("must name {}; the scene's: {}",
                           !torque  ? "a cylinder wall (its radius)"
                           : D == 2 ? "a wall (the moment about its centre of rotation)"
                                    : "a cylinder (the moment about its axis) or a plane or box wall "
                                      "given an angular_velocity in its [[wall]] (about that axis through "
                                      "its rotation_centre)",
                           names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", "))));
      }
      p.wall = it->second;
      if (r.has("component"))
        r.fail("component", torque ? "does not apply: the moment is about the wall's axis"
                                   : "does not apply: the radius is a length");
    } else {
      for (auto k : {"particle", "component", "wall"}) {
        if (r.has(k)) r.fail(k, fmt::format("does not apply to quantity \"{}\"", q));
      }
      p.quantity = q == "kinetic_energy"         ? ProbeQuantity::kinetic_energy
                   : q == "elastic_energy"       ? ProbeQuantity::elastic_energy
                   : q == "gravitational_energy" ? ProbeQuantity::gravitational_energy
                   : q == "gravity_work"         ? ProbeQuantity::gravity_work
                   : q == "fluid_work"           ? ProbeQuantity::fluid_work
                   : q == "boundary_work"        ? ProbeQuantity::boundary_work
                   : q == "damping_dissipation"  ? ProbeQuantity::damping_dissipation
                   : q == "contact_dissipation"  ? ProbeQuantity::contact_dissipation
                   : q == "contact_count"        ? ProbeQuantity::contact_count
                   : q == "coordination"         ? ProbeQuantity::coordination
                   : q == "max_overlap"          ? ProbeQuantity::max_overlap
                   : q == "removed_particles"    ? ProbeQuantity::removed_particles
                   : q == "removed_mass"         ? ProbeQuantity::removed_mass
                   : q == "bonds"                ? ProbeQuantity::bonds
                   : q == "broken_bonds"         ? ProbeQuantity::broken_bonds
                                                 : ProbeQuantity::unbalanced_force;
    }
    // The budget's works accumulate step by step from the start (a slower
    // serial sweep per half kick): only when a probe asks for them.
    if (p.quantity == ProbeQuantity::gravity_work || p.quantity == ProbeQuantity::fluid_work ||
        p.quantity == ProbeQuantity::boundary_work || p.quantity == ProbeQuantity::damping_dissipation ||
        p.quantity == ProbeQuantity::contact_dissipation) {
      sim.track_energy = true;
    }
    scene.output.probes.push_back(p);
  });

  // [[stage]]
  CellMotion<D> planned_cell;  // the periodic cell's motion as the stages read so far leave it
  for_each_table(top, "stage", "stage", [&](TableReader& r, int index) {
    Stage<D> s;
    s.name = r.optional_string("name").value_or(fmt::format("stage{}", index));
    s.duration = r.check("duration", r.number("duration"), is_positive, "> 0 s (the longest the stage runs)");
    if (auto g = r.optional_numbers("gravity", D)) s.gravity = to_vec<D>(*g);
    if (auto a = r.optional_number("local_damping")) {
      s.local_damping = r.check(
          "local_damping", *a, [](double v) { return v >= 0.0 && v < 1.0; }, "in [0, 1)");
    }
    if (auto b = r.optional_number("viscous_damping")) {
      s.viscous_damping = r.check("viscous_damping", *b, is_non_negative, ">= 0 1/s");
    }
    if (const toml::table* st = r.optional_table("stop_when")) {
      TableReader sr(*st, r.where() + " stop_when", file);
      if (auto v = sr.optional_number("kinetic_energy_below")) {
        s.kinetic_energy_below = sr.check("kinetic_energy_below", *v, is_positive, "> 0 J");
      }
      if (auto v = sr.optional_number("unbalanced_force_below")) {
        s.unbalanced_force_below = sr.check("unbalanced_force_below", *v, is_positive, "> 0");
      }
      if (auto name = sr.optional_string("probe")) {
        // A [[probe]] by name (a profile's points are NAME_0, NAME_1, ...).
        std::vector<std::string> names;
        for (const auto& p : scene.output.probes) names.push_back(p.name);
        const auto it = std::find(names.begin(), names.end(), *name);
        if (it == names.end()) {
          std::string hint;
          if (auto h = did_you_mean(*name, names); !h.empty())
            hint = fmt::format(" (did you mean \"{}\"?)", h);
          sr.fail("probe", names.empty()
                               ? fmt::format("no probe named \"{}\": the scene has no [[probe]]", *name)
                               : fmt::format("no probe named \"{}\"{}", *name, hint));
        }
        s.stop_probe = static_cast<std::size_t>(it - names.begin());
        auto finite = [](double v) { return std::isfinite(v); };
        if (auto v = sr.optional_number("above"))
          s.probe_above = sr.check("above", *v, finite, "a finite number");
        if (auto v = sr.optional_number("below"))
          s.probe_below = sr.check("below", *v, finite, "a finite number");
        if (!s.probe_above && !s.probe_below) {
          sr.fail("probe", "needs 'above' or 'below' (or both): the probe's value at which the stage ends");
        }
      } else {
        for (auto k : {"above", "below"}) {
          if (sr.has(k)) sr.fail(k, "applies to a probe: give 'probe' = the name of a [[probe]]");
        }
      }
      s.check_interval = sr.optional_integer("check_interval").value_or(100);
      if (s.check_interval < 1) sr.fail("check_interval", "must be >= 1 step");
      if (!s.kinetic_energy_below && !s.unbalanced_force_below && !s.stop_probe) {
        sr.fail_table(
            "needs 'kinetic_energy_below', 'unbalanced_force_below' or 'probe' with 'above' or 'below'");
      }
      sr.finish();
    }
    if (const toml::table* wt = r.optional_table("walls")) {
      for (const auto& [name, node] : *wt) {
        auto it = wall_index.find(std::string(name.str()));
        if (it == wall_index.end()) {
          std::string hint;
          if (auto h = did_you_mean(name.str(), wall_names); !h.empty())
            hint = fmt::format(" (did you mean \"{}\"?)", h);
          throw SceneError(fmt::format("{}: error: {} walls: no wall named \"{}\"{}",
                                       r.location(node.source()), r.where(), name.str(), hint));
        }
        const toml::table* ct = node.as_table();
        if (ct == nullptr)
          r.fail("walls", "each wall entry must be a table, e.g. walls.top = { velocity = [0, -0.01] }");
        TableReader cr(*ct, fmt::format("{} walls.{}", r.where(), name.str()), file);
        WallChange<D> c;
        c.wall = it->second;
        const bool displaces = std::find(solid_walls.begin(), solid_walls.end(), c.wall) != solid_walls.end();
        read_wall_motion<D>(cr, sim.walls[c.wall].shape, displaces, c.velocity, c.motion, c.servo,
                            c.servo_axis, c.spin, c.spin_axis, c.radius_rate, c.oscillation);
        if (c.spin != 0.0 && !sim.walls[c.wall].is_cylinder()) {
          check_turning_wall_in_period<D>(cr, sim.periodic);
        }
        if (c.motion == WallMotion::servo && c.servo.by_stress) {
          require_loaded_area<D>(cr, sim.walls, c.wall, sim.periodic);
        }
        if (wall_is_barrier[c.wall] &&
            (c.motion != WallMotion::fixed || c.spin != 0.0 || c.oscillation.active())) {
          cr.fail(c.motion == WallMotion::velocity ? "velocity"
                  : c.motion == WallMotion::servo  ? "servo"
                  : c.spin != 0.0                  ? "angular_velocity"
                                                   : "oscillation",
                  "an impermeable wall cannot move: its barrier is fixed in the fluid grid");
        }
        cr.finish();
        s.walls.push_back(c);
      }
    }
    if (const toml::array* contacts = r.optional_array("contacts")) {
      // New friction for pairs of materials: [{ materials = [...], friction = ... }].
      for (std::size_t k = 0; k < contacts->size(); ++k) {
        const toml::table* ct = contacts->get(k)->as_table();
        if (ct == nullptr) {
          r.fail(
              "contacts",
              "must be an array of tables, e.g. contacts = [{ materials = [\"sand\", \"sand\"], friction = "
              "0.0 }]");
        }
        TableReader cr(*ct, fmt::format("{} contacts #{}", r.where(), k + 1), file);
        auto names = cr.string_list("materials");
        if (names.size() != 2)
          cr.fail("materials", "must name exactly two materials, e.g. [\"sand\", \"sand\"]");
        const auto a = materials.lookup(cr, "materials", names[0]);
        const auto b = materials.lookup(cr, "materials", names[1]);
        if (!defined[a * nm + b]) {
          cr.fail("materials",
                  fmt::format("the pair {} / {} has no [[contact]] whose friction a stage could change",
                              names[0], names[1]));
        }
        const double mu = cr.check("friction", cr.number("friction"), is_non_negative, ">= 0");
        // The automatic time step counts the turning that the tangential
        // spring gives a grain only where the [[contact]] has friction.
        if (mu > 0.0 && sim.contact_table(a, b).friction == 0.0 && !sim.contact_table(a, b).bondable) {
          cr.fail(
              "friction",
              fmt::format("the [[contact]] of {} / {} has no friction, so the time step does not allow for "
                          "the grains its tangential spring turns; give the [[contact]] the friction of the "
                          "stage that has the most, and lower it in the others",
                          names[0], names[1]));
        }
        cr.finish();
        s.frictions.push_back({a, b, mu});
      }
    }
    if (r.has("make_bonds")) {
      s.make_bonds = r.boolean_or("make_bonds", false);
      if (s.make_bonds && !sim.contact_table.any_bondable()) {
        r.fail("make_bonds",
               "bonds pairs whose [[contact]] has a 'bond' (bond = { tensile_strength = ..., "
               "shear_strength = ... }), and no [[contact]] of the scene has one");
      }
    }
    if (auto gap = r.optional_number("bond_gap")) {
      if (!s.make_bonds) r.fail("bond_gap", "applies with make_bonds = true");
      const double skin = sim.skin_or_default();
      s.bond_gap = r.check(
          "bond_gap", *gap, [skin](double v) { return v >= 0.0 && v < skin; },
          fmt::format(">= 0 m and below the neighbour lists' skin ({} m; [simulation] skin)",
                      TableReader::format_number(skin)));
    }
    if (r.has("periodic_cell")) {
      s.cell = read_cell_change<D>(r, sim, cell_neighbours(scene), planned_cell);
    }
    if (const toml::table* it = r.optional_table("inlets")) {
      for (const auto& [name, node] : *it) {
        const auto found = std::find(inlet_names.begin(), inlet_names.end(), std::string(name.str()));
        if (found == inlet_names.end()) {
          std::string hint;
          if (auto h = did_you_mean(name.str(), inlet_names); !h.empty())
            hint = fmt::format(" (did you mean \"{}\"?)", h);
          throw SceneError(fmt::format("{}: error: {} inlets: no [[inlet]] named \"{}\"{}",
                                       r.location(node.source()), r.where(), name.str(), hint));
        }
        const toml::table* ct = node.as_table();
        if (ct == nullptr)
          r.fail("inlets", "each inlet entry must be a table, e.g. inlets.rain = { active = false }");
        TableReader cr(*ct, fmt::format("{} inlets.{}", r.where(), name.str()), file);
        if (!cr.has("active"))
          cr.fail_table("needs 'active' (true: the inlet adds grains from this stage on; false: it stops)");
        s.inlets.emplace_back(static_cast<std::size_t>(found - inlet_names.begin()),
                              cr.boolean_or("active", true));
        cr.finish();
      }
    }
    if (const toml::table* ft = r.optional_table("fluid")) {
      if (!scene.fluid) r.fail("fluid", "changes the pore fluid, but the scene has no [fluid] table");
      TableReader fr(*ft, r.where() + " fluid", file);
      if (const toml::table* bt = fr.optional_table("boundary")) {
        auto changes =
            read_fluid_boundary_changes<D>(*bt, r.where() + " fluid.boundary", file, scene.fluid.get());
        s.fluid_sides = std::move(changes.sides);
        s.fluid_patches = std::move(changes.patches);
      }
      if (const toml::table* st = fr.optional_table("sources"))
        s.fluid_sources = read_source_changes<D>(*st, r.where() + " fluid.sources", file, *scene.fluid);
      if (fr.has("freeze_permeability")) s.freeze_permeability = fr.boolean_or("freeze_permeability", false);
      if (fr.has("steps_per_update")) s.fluid_steps_per_update = read_steps_per_update(fr);
      if (fr.has("hold_forces")) s.fluid_hold_forces = fr.boolean_or("hold_forces", false);
      if (fr.has("drained")) s.fluid_drained = fr.boolean_or("drained", false);
      fr.finish();
    }
    scene.stages.push_back(s);
  });
  if (scene.stages.empty()) top.fail_table("needs at least one [[stage]] (with a 'duration')");

  // [analysis]
  if (const toml::table* t = top.optional_table("analysis")) {
    TableReader r(*t, "[analysis]", file);
    r.choice("kind", {"seepage_column"});
    if (!scene.fluid) r.fail("kind", "\"seepage_column\" needs a pore fluid: the scene has no [fluid] table");
    if (!scene.fluid->patches.empty()) {
      r.fail("kind",
             fmt::format("\"seepage_column\" compares with a one-dimensional solution and takes whole "
                         "sides; the scene's [fluid.boundary] has patches (\"{}\")",
                         scene.fluid->patches.front().name));
    }
    SeepageColumnSpec a;
    std::vector<std::string> stage_names;
    for (const auto& st : scene.stages) stage_names.push_back(st.name);
    auto stage_name = [&](std::string_view key) {
      const std::string n = r.string(key);
      if (std::find(stage_names.begin(), stage_names.end(), n) == stage_names.end()) {
        std::string hint;
        if (auto h = did_you_mean(n, stage_names); !h.empty())
          hint = fmt::format(" (did you mean \"{}\"?)", h);
        r.fail(key, fmt::format("no stage named \"{}\"{}", n, hint));
      }
      return n;
    };
    a.settle_stage = stage_name("settle_stage");
    a.inflow_stage = stage_name("inflow_stage");
    a.pressure_times = r.number_list("pressure_times");
    for (double x : a.pressure_times)
      r.check("pressure_times", x, is_positive, "> 0 s after the inflow starts");
    a.uplift_interval =
        r.check("uplift_interval", r.number_or("uplift_interval", 1e-3), is_positive, "> 0 s");
    a.uplift_tolerance =
        r.check("uplift_tolerance", r.number_or("uplift_tolerance", 0.02), is_positive, "> 0");
    a.pressure_tolerance =
        r.check("pressure_tolerance", r.number_or("pressure_tolerance", 0.03), is_positive, "> 0");
    a.plots = r.boolean_or("plots", true);
    const auto& inflow = *std::find_if(scene.stages.begin(), scene.stages.end(),
                                       [&](const Stage<D>& st) { return st.name == a.inflow_stage; });
    const bool has_flux = std::any_of(
        inflow.fluid_sides.begin(), inflow.fluid_sides.end(),
        [](const auto& fs) { return fs.first == 2 * (D - 1) && fs.second.type == FluidBoundaryType::flux; });
    if (!has_flux) {
      r.fail("inflow_stage", fmt::format("stage \"{}\" must set a flux on the bottom side ({}) in its "
                                         "fluid.boundary",
                                         a.inflow_stage, side_names[2 * (D - 1)]));
    }
    r.finish();
    scene.seepage_column = a;
  }

  for (const auto& key : kTopLevel) top.allow({key});
  top.finish();

  check_initial_overlaps(sim, overlap_tolerance, origin);

  // Time step: the first stage's gravity does not matter for the critical
  // step; the pore fluid's undrained stiffness and drag do.
  // An inlet's smallest grain counts too (a clump: its members against its
  // mass and inertia): added for this only (at its box's centre, outside
  // any fluid grid), then taken out again.
  const std::size_t scene_particles = sim.particles.size();
  const std::size_t scene_clumps = sim.clumps.size();
  for (const auto& in : scene.inlets) {
    const double density = sim.materials[in.material].density;
    const Vec<D> centre = 0.5 * (in.lower + in.upper);
    if (in.clump) {
      sim.clumps.add(sim.particles, *in.clump, in.radii.smallest(), centre,
                     ClumpShape<D>::identity_orientation(), density, in.material, false, Vec<D>::Zero());
    } else {
      sim.particles.add(centre, in.radii.smallest(), density, in.material, false);
    }
  }
  // One cell never drained keeps a uniform pressure: no grain feels the
  // water's stiffness, so the critical step leaves it out.
  if (scene.fluid) {
    auto drains = [](const auto& change) { return change.second.type == FluidBoundaryType::drained; };
    scene.fluid->uniform_pressure =
        scene.fluid->sealed_single_cell() &&
        std::none_of(scene.stages.begin(), scene.stages.end(), [&](const auto& st) {
          return std::any_of(st.fluid_sides.begin(), st.fluid_sides.end(), drains) ||
                 std::any_of(st.fluid_patches.begin(), st.fluid_patches.end(), drains);
        });
    if (scene.fluid->uniform_pressure) {
      const double stiff = scene.fluid->critical_time_step(sim.particles, sim.critical_time_step(), true);
      scene.notes.push_back(fmt::format(
          "[fluid]: one cell whose sides no stage drains: its pressure stays uniform and its gradient pushes "
          "no grain, so the critical step leaves the water's undrained stiffness out ({:.4g} s with it); the "
          "walls that displace the water feel it",
          stiff));
    }
  }
  const double critical = scene.fluid
                              ? scene.fluid->critical_time_step(sim.particles, sim.critical_time_step())
                              : sim.critical_time_step();
  scene.critical_time_step = critical;
  if (sim.particles.size() > scene_particles) {
    std::vector<std::uint32_t> keep(scene_particles);
    for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = static_cast<std::uint32_t>(i);
    sim.particles.permute(keep);
  }
  if (sim.clumps.size() > scene_clumps) {
    std::vector<std::uint8_t> kept(sim.clumps.size(), 0);
    std::fill(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(scene_clumps), 1);
    sim.clumps.keep(kept);
    sim.clumps.refresh(sim.particles);
  }
  // Refusals of [simulation] time_step, at the key.
  auto refuse_time_step = [&](const std::string& message) {
    TableReader(*root["simulation"].as_table(), "[simulation]", file).fail("time_step", message);
  };
  if (scene.time_step.automatic) {
    sim.time_step = scene.time_step.safety_factor * critical;
    if (!(std::isfinite(sim.time_step) && sim.time_step > 0.0)) {
      refuse_time_step(
          std::isinf(critical)
              ? std::string("\"auto\" needs a particle free to move (the critical time step comes from the "
                            "free particles' masses and contacts); give a number of seconds")
              : fmt::format("\"auto\" gives {:.4g} s, from a critical time step of {:.4g} s: a density, "
                            "contact stiffness or pore-fluid value is out of range",
                            sim.time_step, critical));
    }
  } else {
    if (scene.time_step.value > critical) {
      refuse_time_step(
          fmt::format("{:.4g} s is larger than the critical time step {:.4g} s "
                      "(1/omega of the fastest contact mode of the lightest grain, normal or with "
                      "friction turning it, or the Rayleigh step; with the pore fluid's K_f/n and "
                      "drag if any); use a smaller value or \"auto\"",
                      scene.time_step.value, critical));
    }
    sim.time_step = scene.time_step.value;
  }
  // An inlet inserts at most once a step: a shorter interval would only
  // pile insertions onto one step (and one below round-off never advance).
  for (std::size_t i = 0; i < scene.inlets.size(); ++i) {
    if (scene.inlets[i].interval < sim.time_step) {
      TableReader r(*(*root["inlet"].as_array())[i].as_table(), fmt::format("[[inlet]] #{}", i + 1), file);
      r.fail("interval", fmt::format("must be at least the time step, {:.4g} s, got {:.4g} s", sim.time_step,
                                     scene.inlets[i].interval));
    }
  }
  // Viscous damping is explicit: each half kick scales a velocity by
  // 1 - c dt/2, which reverses it from c dt = 2 on (and grows it beyond 4).
  if (const toml::array* stages = root["stage"].as_array()) {
    for (std::size_t i = 0; i < scene.stages.size() && i < stages->size(); ++i) {
      const auto& c = scene.stages[i].viscous_damping;
      if (c && *c * sim.time_step >= 2.0) {
        TableReader r(*(*stages)[i].as_table(), fmt::format("[[stage]] #{}", i + 1), file);
        r.fail("viscous_damping", fmt::format("must be below 2 / time step = {:.4g} 1/s (explicit damping "
                                              "reverses the velocities beyond it), got {:.4g}",
                                              2.0 / sim.time_step, *c));
      }
    }
  }
  if (const toml::array* stages = root["stage"].as_array())
    check_cell_rates<D>(*stages, scene.stages, sim.time_step, file);
  return scene;
}

template Scene<2> build_scene<2>(const toml::table&, const std::string&, const std::string&);
template Scene<3> build_scene<3>(const toml::table&, const std::string&, const std::string&);

}  // namespace darcydem
