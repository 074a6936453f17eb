#include "darcydem/scene/scene_fluid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "darcydem/fluid/well_index.hpp"

namespace darcydem {
namespace {

template <int D>
std::vector<std::string> side_list() {
  return std::vector<std::string>(side_names, side_names + 2 * D);
}

/// type = "drained" | "flux" | "no_flow" with its value; `what` is "side"
/// or "patch", for the messages.
FluidBoundary read_condition(TableReader& r, const char* what) {
  FluidBoundary b;
  const std::string type = r.choice("type", {"drained", "flux", "no_flow"});
  r.allow({"pressure", "inflow"});
  if (type == "drained") {
    if (r.has("inflow"))
      r.fail("inflow", fmt::format("does not apply to a drained {} (give 'pressure')", what));
    b.type = FluidBoundaryType::drained;
    b.value = read_time_series(r, "pressure", "excess pore pressure, Pa");
  } else if (type == "flux") {
    if (r.has("pressure"))
      r.fail("pressure", fmt::format("does not apply to a flux {} (give 'inflow')", what));
    b.type = FluidBoundaryType::flux;
    b.value = read_time_series(r, "inflow", "Darcy velocity into the grid, m/s");
  } else {
    for (auto k : {"pressure", "inflow"}) {
      if (r.has(k)) r.fail(k, fmt::format("does not apply to a no_flow {}", what));
    }
    b.type = FluidBoundaryType::no_flow;
  }
  return b;
}

/// The names a [fluid.boundary] table may hold besides the patches'.
template <int D>
std::string side_choices() {
  std::string list;
  for (const auto& n : side_list<D>()) list += (list.empty() ? "" : ", ") + n;
  return list;
}

/// A patch's place: 'side', and 'from' and 'to' along the side's other
/// axes. Checked against the grid: inside the side, from < to, holding at
/// least one face centre and none of an earlier patch's faces.
/// Why a side of a periodic axis takes no condition.
std::string periodic_side_message(const std::string& side) {
  return fmt::format(
      "the scene is periodic along {} ([periodic]): the fluid grid spans the period and its two {} sides "
      "are one face between its last and first cells, which takes no condition",
      side.substr(0, 1), side.substr(0, 1));
}

template <int D>
FluidPatch<D> read_patch_place(TableReader& r, const std::string& name, const FluidGrid<D>& grid,
                               const std::vector<FluidPatch<D>>& earlier) {
  const auto names = side_list<D>();
  FluidPatch<D> patch;
  patch.name = name;
  const std::string side = r.choice("side", names);
  patch.side = static_cast<int>(std::find(names.begin(), names.end(), side) - names.begin());
  const int axis = patch.side / 2;
  if (grid.periodic[axis]) r.fail("side", periodic_side_message(side));
  std::string along;  // the side's other axes, e.g. "x, y"
  for (int k = 0; k < D; ++k) {
    if (k != axis) along += std::string(along.empty() ? "" : ", ") + "xyz"[k];
  }
  const auto from = r.numbers("from", D - 1);
  const auto to = r.numbers("to", D - 1);
  int j = 0;
  for (int k = 0; k < D; ++k) {
    if (k == axis) continue;
    const double lo = grid.origin[k];
    const double hi = grid.face_at(k, grid.cells[k]);
    if (!(to[j] > from[j]))
      r.fail("to", fmt::format("must be greater than 'from' along {} (the patch's extent along {}, m)",
                               "xyz"[k], along));
    // (A patch's edge on the grid's edge may differ from it by round-off.)
    const double slack = 1e-9 * grid.min_width(k);
    if (!(from[j] >= lo - slack && to[j] <= hi + slack)) {
      r.fail(from[j] >= lo ? "to" : "from",
             fmt::format("the patch must lie on side {}: along {} the grid spans [{}, {}] m", side, "xyz"[k],
                         TableReader::format_number(lo), TableReader::format_number(hi)));
    }
    patch.lo[k] = from[j];
    patch.hi[k] = to[j];
    ++j;
  }
  // The side's faces, by their centres.
  std::array<int, D> c{};
  std::size_t faces = 0;
  std::size_t total = 1;
  for (int k = 0; k < D; ++k) total *= k == axis ? 1U : static_cast<std::size_t>(grid.cells[k]);
  for (std::size_t f = 0; f < total; ++f) {
    std::size_t rest = f;
    for (int k = 0; k < D; ++k) {
      if (k == axis) continue;
      c[k] = static_cast<int>(rest % static_cast<std::size_t>(grid.cells[k]));
      rest /= static_cast<std::size_t>(grid.cells[k]);
    }
    const Vec<D> centre = grid.centre(c);  // of the cell beside the face
    if (!patch.holds(centre)) continue;
    ++faces;
    for (const auto& e : earlier) {
      if (e.side == patch.side && e.holds(centre)) {
        r.fail("from", fmt::format("patch \"{}\" shares faces of side {} with patch \"{}\": a face can be in "
                                   "one patch only",
                                   name, side, e.name));
      }
    }
  }
  if (faces == 0) {
    std::string width;  // e.g. "0.001 x 0.002"
    for (int k = 0; k < D; ++k) {
      if (k != axis)
        width += std::string(width.empty() ? "" : " x ") + TableReader::format_number(grid.min_width(k));
    }
    r.fail("from",
           fmt::format("the patch holds no face of side {}: a face is in it when its centre is, and the "
                       "faces are {}{} m wide along {}",
                       side, grid.any_graded() ? "at least " : "", width, along));
  }
  return patch;
}

/// Checks a barrier against the grid: a plane of faces between cells, and
/// at least one face in it; `fail(key, message)` (which does not return)
/// otherwise, with 'axis', 'at' or 'from' as the key at fault.
template <int D, class Fail>
void check_barrier(const FluidBarrier<D>& barrier, const FluidGrid<D>& grid, Fail&& fail) {
  const int k = barrier.axis;
  const std::string axis(1, "xyz"[k]);
  if (grid.cells[k] < 2) {
    fail("axis",
         fmt::format("the grid has one cell along {}: there is no face between cells to close", axis));
  }
  if (grid.graded(k)) {
    // The interior face nearest `at`, within 1e-6 of the narrower cell beside it.
    const int nearest = std::clamp(grid.nearest_face(k, barrier.at), 1, grid.cells[k] - 1);
    const double tolerance = 1e-6 * std::min(grid.width(k, nearest - 1), grid.width(k, nearest));
    if (!(std::abs(grid.face_at(k, nearest) - barrier.at) <= tolerance)) {
      fail("at",
           fmt::format("must be on a plane of faces between two cells inside the grid: along {} (graded) "
                       "the nearest is at {} m",
                       axis, TableReader::format_number(grid.face_at(k, nearest))));
    }
  } else {
    const double plane = (barrier.at - grid.origin[k]) / grid.spacing[k];
    const double nearest = std::round(plane);
    if (!(std::abs(plane - nearest) <= 1e-6 && nearest >= 1.0 && nearest <= grid.cells[k] - 1.0)) {
      const double below =
          grid.origin[k] + grid.spacing[k] * std::clamp(std::round(plane), 1.0, grid.cells[k] - 1.0);
      fail("at",
           fmt::format("must be on a plane of faces between two cells inside the grid: along {} they are at "
                       "{} + n x {} m, n = 1 .. {} (the nearest: {} m)",
                       axis, TableReader::format_number(grid.origin[k]),
                       TableReader::format_number(grid.spacing[k]), grid.cells[k] - 1,
                       TableReader::format_number(below)));
    }
  }
  std::size_t faces = 1;
  for (int a = 0; a < D; ++a) {
    if (a == k) continue;
    // Cell centres along a inside [lo, hi].
    std::size_t in = 0;
    for (int c = 0; c < grid.cells[a]; ++c) {
      const double x = grid.centre_at(a, c);
      in += x >= barrier.lo[a] && x <= barrier.hi[a] ? 1U : 0U;
    }
    faces *= in;
  }
  if (faces == 0) {
    fail("from",
         "the barrier holds no face: a face is in it when its centre lies within the barrier's extent along "
         "the other axes");
  }
}

/// [fluid.grid] as origin, cells and size: cells of one size, at least
/// `2 r_max` wide.
template <int D>
void read_uniform_grid(TableReader& g, FluidGrid<D>& grid, double r_max) {
  const auto origin = g.numbers("origin", D);
  const auto cells = g.numbers("cells", D);
  const auto size = g.numbers("size", D);
  for (int k = 0; k < D; ++k) {
    grid.origin[k] = origin[k];
    if (!(cells[k] >= 1.0) || cells[k] != std::floor(cells[k]) || cells[k] > 1e6)
      g.fail("cells", "must be whole numbers of cells >= 1 along each axis");
    grid.cells[k] = static_cast<int>(cells[k]);
    g.check("size", size[k], is_positive, "> 0 m along each axis (the size of one cell)");
    if (size[k] < 2.0 * r_max * (1.0 - 1e-12)) {
      g.fail("size", fmt::format("cells must be at least one grain diameter wide: {:.4g} m along {} is less "
                                 "than the largest diameter {:.4g} m",
                                 size[k], "xyz"[k], 2.0 * r_max));
    }
    grid.spacing[k] = size[k];
  }
}

/// [fluid.grid] given axis by axis: a table per axis (`x`, `y`[, `z`]),
/// each either `faces` (the face coordinates, increasing) or `from`, `to`,
/// `cells` and `ratio` (the last cell's width over the first's, default 1:
/// cells of one size; else widths in geometric progression). Cells at
/// least `2 r_max` wide; a periodic axis uniform.
template <int D>
void read_grid_axes(TableReader& g, FluidGrid<D>& grid, double r_max,
                    const std::array<bool, static_cast<std::size_t>(D)>& periodic) {
  for (auto key : {"origin", "cells", "size"}) {
    if (g.has(key))
      g.fail(key, "the grid is given axis by axis (x, y, z tables): leave out origin, cells and size");
  }
  for (int k = 0; k < D; ++k) {
    const std::string name(1, "xyz"[k]);
    const toml::table* t = g.optional_table(name);
    if (t == nullptr) {
      g.fail_table(
          fmt::format("the {} axis has no table: given axis by axis, the grid needs a table for every "
                      "axis, {{ from, to, cells[, ratio] }} or {{ faces = [...] }}",
                      name));
    }
    TableReader a(*t, "[fluid.grid] " + name, g.file());
    std::vector<double> faces;
    const char* key = "faces";
    if (a.has("faces")) {
      for (auto other : {"from", "to", "cells", "ratio"}) {
        if (a.has(other)) a.fail(other, "give either faces or from, to, cells (and ratio), not both");
      }
      faces = a.number_list("faces");
      if (faces.size() < 2) a.fail("faces", "must hold at least two face coordinates (one cell), m");
      for (std::size_t i = 0; i < faces.size(); ++i) {
        if (!std::isfinite(faces[i]) || (i > 0 && !(faces[i] > faces[i - 1])))
          a.fail("faces", "must be finite face coordinates in increasing order, m");
      }
    } else {
      const double from = a.number("from");
      const double to = a.number("to");
      if (!std::isfinite(from) || !std::isfinite(to) || !(to > from))
        a.fail("to", "must be finite and greater than 'from' (the grid's extent along the axis, m)");
      const double n = a.check(
          "cells", static_cast<double>(a.integer("cells")), [](double v) { return v >= 1.0 && v <= 1e6; },
          "a whole number of cells >= 1");
      const double ratio = a.check("ratio", a.number_or("ratio", 1.0), is_positive,
                                   "> 0 (the last cell's width over the first's)");
      key = "cells";
      const int cells = static_cast<int>(n);
      if (ratio == 1.0) {
        // Cells of one size: a uniform axis, as origin, cells and size give it.
        grid.origin[k] = from;
        grid.cells[k] = cells;
        grid.spacing[k] = (to - from) / n;
      } else {
        if (cells < 2) a.fail("ratio", "grades cells: it needs at least two cells");
        if (periodic[k])
          a.fail("ratio",
                 fmt::format("the scene is periodic along {}: the grid's cells along it must be of one "
                             "size (ratio = 1)",
                             name));
        faces = graded_faces(from, to, cells, ratio);
      }
    }
    if (!faces.empty()) {
      if (periodic[k])
        a.fail(key,
               fmt::format("the scene is periodic along {}: the grid's cells along it must be of one size "
                           "(from, to, cells)",
                           name));
      grid.set_faces(k, std::move(faces));
    }
    if (grid.min_width(k) < 2.0 * r_max * (1.0 - 1e-12)) {
      a.fail(key, fmt::format(
                      "cells must be at least one grain diameter wide: the narrowest along {} is {:.4g} m, "
                      "less than the largest diameter {:.4g} m",
                      name, grid.min_width(k), 2.0 * r_max));
    }
    a.finish();
  }
}

/// One [[fluid.barrier]]: 'axis' (its normal), 'at' (a plane of faces
/// between cells), 'from' and 'to' along the other axes; checked against
/// the grid.
template <int D>
FluidBarrier<D> read_barrier(const toml::table& table, const std::string& where, const std::string& file,
                             const FluidGrid<D>& grid) {
  TableReader r(table, where, file);
  FluidBarrier<D> barrier;
  barrier.name = r.optional_string("name").value_or(where);
  const std::vector<std::string> axes =
      D == 2 ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x", "y", "z"};
  const std::string axis = r.choice("axis", axes);
  barrier.axis = static_cast<int>(std::find(axes.begin(), axes.end(), axis) - axes.begin());
  barrier.at = r.number("at");
  const auto from = r.numbers("from", D - 1);
  const auto to = r.numbers("to", D - 1);
  int j = 0;
  for (int a = 0; a < D; ++a) {
    if (a == barrier.axis) continue;
    if (!(to[j] > from[j])) r.fail("to", fmt::format("must be greater than 'from' along {}", "xyz"[a]));
    barrier.lo[a] = from[j];
    barrier.hi[a] = to[j];
    ++j;
  }
  check_barrier(barrier, grid, [&](const char* key, const std::string& message) { r.fail(key, message); });
  r.finish();
  return barrier;
}

/// A source's condition: one of 'inflow' (m^3/s; 2D: per metre) and
/// 'pressure' (Pa held in its cell), each a number or a series.
template <int D>
void read_source_condition(TableReader& r, FluidSourceType& type, TimeSeries& value) {
  const bool inflow = r.has("inflow");
  if (inflow == r.has("pressure")) {
    r.fail_table(
        fmt::format("give one of 'inflow' ({} into the pore water, negative out; a number or a series) "
                    "and 'pressure' (Pa, the excess pore pressure it holds in its cell)",
                    D == 2 ? "m^2/s per metre" : "m^3/s"));
  }
  type = inflow ? FluidSourceType::inflow : FluidSourceType::pressure;
  value = inflow ? read_time_series(r, "inflow",
                                    D == 2 ? "m^2/s per metre into the grid, negative out"
                                           : "m^3/s into the grid, negative out")
                 : read_time_series(r, "pressure", "excess pore pressure held in its cell, Pa");
}

/// One [[fluid.source]]: 'name', 'position' (in the grid), 'inflow' or
/// 'pressure', and a well's 'radius'. `taken` holds the names the sides,
/// patches and earlier sources already use.
template <int D>
FluidSource<D> read_source(const toml::table& table, const std::string& where, const std::string& file,
                           const FluidGrid<D>& grid, const PermeabilitySpec<D>& permeability,
                           const std::vector<std::string>& taken) {
  TableReader r(table, where, file);
  FluidSource<D> source;
  source.name = r.string("name");
  if (source.name.empty()) r.fail("name", "must not be empty (probes and stages find the source by it)");
  if (std::find(taken.begin(), taken.end(), source.name) != taken.end()) {
    r.fail("name",
           fmt::format("\"{}\" is already a side, a patch or a source of the fluid: names must differ "
                       "(the fluid_inflow probe and the stages find a source by its name)",
                       source.name));
  }
  const bool screened = r.has("screen");
  if (screened && D == 2) {
    r.fail("screen",
           "is for 3D grids: in 2D a source is already a well through the whole thickness (give its "
           "'position' and 'radius')");
  }
  if (screened && !r.has("radius")) {
    r.fail("screen",
           "needs the well's 'radius' (m): each cell of the screen is joined to the bore by a well "
           "index, which needs it");
  }
  if (!screened && r.has("axis")) r.fail("axis", "is a screened well's: give it a 'screen' = [from, to] too");
  // A screened well's position is across its axis; along it, the screen's.
  if (screened) {
    const std::string axis = r.optional_choice("axis", {"x", "y", "z"}).value_or("z");
    source.screen_axis = axis == "x" ? 0 : axis == "y" ? 1 : 2;
  }
  const int along = source.screen_axis;
  const std::string others = along == 0 ? "y, z" : along == 1 ? "x, z" : "x, y";
  const std::size_t given = screened ? D - 1 : D;
  if (const toml::array* p = table["position"].as_array(); screened && p != nullptr && p->size() != given) {
    r.fail("position", fmt::format("with a 'screen' along {} is the well's line, [{}]: the screen gives its "
                                   "extent along {}",
                                   "xyz"[along], others, "xyz"[along]));
  }
  const auto given_x = r.numbers("position", given);
  std::vector<double> x;
  if (screened) {
    const auto z = r.numbers("screen", 2);
    const double lo = grid.face_at(along, 0);
    const double hi = grid.face_at(along, grid.cells[along]);
    if (!(z[0] >= lo && z[1] <= hi && z[0] < z[1])) {
      r.fail("screen",
             fmt::format(
                 "must be [from, to] along {}, from < to, in the fluid grid's [{}, {}] m; got [{}, {}] m",
                 "xyz"[along], TableReader::format_number(lo), TableReader::format_number(hi),
                 TableReader::format_number(z[0]), TableReader::format_number(z[1])));
    }
    source.screen = {z[0], z[1]};
    for (int k = 0, j = 0; k < D; ++k) x.push_back(k == along ? 0.5 * (z[0] + z[1]) : given_x[j++]);
  } else {
    x = given_x;
  }
  for (int k = 0; k < D; ++k) {
    const double lo = grid.face_at(k, 0);
    const double hi = grid.face_at(k, grid.cells[k]);
    if (!(x[k] >= lo && x[k] <= hi)) {
      r.fail("position", fmt::format("must lie in the fluid grid: {} = {} m is outside [{}, {}] m", "xyz"[k],
                                     TableReader::format_number(x[k]), TableReader::format_number(lo),
                                     TableReader::format_number(hi)));
    }
    source.position[k] = x[k];
  }
  read_source_condition<D>(r, source.type, source.value);
  source.drain = r.boolean_or("drain", false);
  if (source.drain && source.type != FluidSourceType::pressure) {
    r.fail("drain",
           "a drain holds a 'pressure' and takes water out only while the water around it stands "
           "above it: give it 'pressure' (Pa), not 'inflow'");
  }
  if constexpr (D == 3) {
    if (screened) {
      // Each cell of the screen takes Peaceman's 2D index across the well:
      // the cells' widths across its axis and the permeability's
      // proportions there, alike along the screen's row of cells.
      const Vec<D> widths = cell_widths_at(grid, source.position);
      const Vec<D> shape = permeability_shape(permeability);
      source.radius = r.check("radius", r.number("radius"), is_positive, "> 0 m, the well's radius");
      const double r_e = equivalent_radius<2>(across(along, widths), across(along, shape));
      if (!(source.radius < r_e)) {
        r.fail("radius",
               fmt::format(
                   "must be less than the equivalent radius of the cells the screen passes through, {} "
                   "m (Peaceman's across the well, 0.1985 h for square cells), got {} m: a well that "
                   "wide is wider than the cells can tell; model it with coarser cells, or as a box wall",
                   TableReader::format_number(r_e), TableReader::format_number(source.radius)));
      }
    }
  }
  if (!screened && r.has("radius")) {
    source.radius = r.check("radius", r.number("radius"), is_positive, "> 0 m, the well's radius");
    // The equivalent radius depends on its cell's widths and the
    // permeability's proportions only.
    const Vec<D> widths = cell_widths_at(grid, source.position);
    const Vec<D> shape = permeability_shape(permeability);
    if constexpr (D == 3) {
      const bool cubic = std::abs(widths[1] - widths[0]) <= 1e-9 * widths[0] &&
                         std::abs(widths[2] - widths[0]) <= 1e-9 * widths[0];
      const bool isotropic = std::abs(shape[1] - shape[0]) <= 1e-12 * shape[0] &&
                             std::abs(shape[2] - shape[0]) <= 1e-12 * shape[0];
      if (!cubic || !isotropic) {
        r.fail("radius",
               fmt::format("in 3D a well's radius needs its cell to be a cube ({} x {} x {} m here) and the "
                           "permeability the same along x, y and z (the equivalent radius of its cell, "
                           "0.3149 h, is known for those only); leave the radius out to read the cell's "
                           "pressure",
                           TableReader::format_number(widths[0]), TableReader::format_number(widths[1]),
                           TableReader::format_number(widths[2])));
      }
    }
    const double r_e = equivalent_radius<D>(widths, shape);
    if (!(source.radius < r_e)) {
      r.fail(
          "radius",
          fmt::format("must be less than its cell's equivalent radius, {} m (Peaceman's: the cell's pressure "
                      "is the well's at that distance; {}), got {} m: a well that wide is wider than the "
                      "cells can tell; model it with coarser cells, or as a box wall",
                      TableReader::format_number(r_e), D == 2 ? "0.1985 h for a square cell" : "0.3149 h",
                      TableReader::format_number(source.radius)));
    }
  }
  r.finish();
  return source;
}

}  // namespace

template <int D>
std::vector<FluidSourceChange> read_source_changes(const toml::table& table, const std::string& where,
                                                   const std::string& file, const PoreFluid<D>& fluid) {
  std::vector<std::string> names;
  for (const auto& s : fluid.sources) names.push_back(s.name);
  TableReader r(table, where, file);
  std::vector<FluidSourceChange> out;
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    r.allow({name});
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end()) {
      std::string hint;
      if (auto h = did_you_mean(name, names); !h.empty()) hint = fmt::format(" (did you mean \"{}\"?)", h);
      r.fail(name, names.empty() ? std::string("the scene has no [[fluid.source]]")
                                 : fmt::format("is not a [[fluid.source]] of the scene{}", hint));
    }
    const toml::table* t = node.as_table();
    if (t == nullptr)
      r.fail(
          name,
          "must be a table, e.g. { inflow = 0.0 } (m^3/s) or { pressure = 0.0 } (Pa); a number or a series");
    TableReader sr(*t, fmt::format("{}.{}", where, name), file);
    for (auto k : {"name", "position"}) {
      if (sr.has(k))
        sr.fail(k,
                "a stage changes a source's inflow or pressure only; its name and position are set in "
                "[[fluid.source]]");
    }
    FluidSourceChange change;
    change.source = static_cast<std::size_t>(at - names.begin());
    read_source_condition<D>(sr, change.type, change.value);
    sr.finish();
    out.push_back(change);
  }
  r.finish();
  return out;
}

template <int D>
FluidBoundaryChanges read_fluid_boundary_changes(const toml::table& table, const std::string& where,
                                                 const std::string& file, const PoreFluid<D>* defined,
                                                 std::vector<FluidPatch<D>>* define) {
  FluidBoundaryChanges out;
  const auto names = side_list<D>();
  std::vector<std::string> patch_names;
  if (defined != nullptr) {
    for (const auto& p : defined->patches) patch_names.push_back(p.name);
  }
  TableReader r(table, where, file);
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    const auto side_at = std::find(names.begin(), names.end(), name);
    const bool is_side = side_at != names.end();
    r.allow({name});
    const toml::table* t = node.as_table();
    if (t == nullptr) {
      r.fail(name, is_side
                       ? "must be a table, e.g. { type = \"drained\", pressure = 0.0 }"
                       : "must be a table: a side's condition, or a patch { side = ..., from = [...], to = "
                         "[...], type = ... }");
    }
    TableReader sr(*t, fmt::format("{}.{}", where, name), file);
    if (is_side && defined != nullptr && defined->grid.periodic[(side_at - names.begin()) / 2]) {
      r.fail(name, periodic_side_message(name));
    }
    if (is_side) {
      const FluidBoundary b = read_condition(sr, "side");
      sr.finish();
      out.sides.emplace_back(static_cast<int>(side_at - names.begin()), b);
      continue;
    }
    if (define != nullptr) {
      // [fluid.boundary]: any other name is a patch, which says where it is.
      if (!sr.has("side")) {
        std::string hint;
        if (auto h = did_you_mean(name, names); !h.empty()) hint = fmt::format(" (did you mean \"{}\"?)", h);
        r.fail(name, fmt::format("is not a side ({}){}; a patch of a side needs 'side', 'from' and 'to'",
                                 side_choices<D>(), hint));
      }
      FluidPatch<D> patch = read_patch_place<D>(sr, name, defined->grid, *define);
      patch.condition = read_condition(sr, "patch");
      sr.finish();
      out.patches.emplace_back(static_cast<int>(define->size()), patch.condition);
      define->push_back(patch);
      continue;
    }
    // A stage: the patches of [fluid.boundary], by name.
    const auto at = std::find(patch_names.begin(), patch_names.end(), name);
    if (at == patch_names.end()) {
      std::vector<std::string> all = names;
      all.insert(all.end(), patch_names.begin(), patch_names.end());
      std::string hint;
      if (auto h = did_you_mean(name, all); !h.empty()) hint = fmt::format(" (did you mean \"{}\"?)", h);
      r.fail(name, fmt::format("is neither a side ({}) nor a patch of [fluid.boundary]{}", side_choices<D>(),
                               hint));
    }
    for (auto k : {"side", "from", "to"}) {
      if (sr.has(k))
        sr.fail(k, "a stage changes a patch's condition only; where it lies is set in [fluid.boundary]");
    }
    const FluidBoundary b = read_condition(sr, "patch");
    sr.finish();
    out.patches.emplace_back(static_cast<int>(at - patch_names.begin()), b);
  }
  r.finish();
  return out;
}

int read_steps_per_update(TableReader& r) {
  const auto m = r.optional_integer("steps_per_update");
  if (!m || *m < 1 || *m > std::numeric_limits<int>::max()) {
    r.fail("steps_per_update", "must be an integer from 1 to 2147483647 (DEM steps per fluid step)");
  }
  return static_cast<int>(*m);
}

template <int D>
std::unique_ptr<PoreFluid<D>> read_fluid(const toml::table& table, const std::string& file,
                                         const ParticleData<D>& particles,
                                         const std::vector<WallBarrier<D>>& wall_barriers,
                                         const PeriodicCell<D>& periodic, const std::vector<Wall<D>>& walls,
                                         const std::vector<std::size_t>& solid_walls,
                                         const std::vector<std::size_t>& impermeable_walls) {
  TableReader r(table, "[fluid]", file);
  const std::string solver = r.optional_choice("solver", {"cholesky", "cg"}).value_or("cg");
  const double tolerance =
      r.check("tolerance", r.number_or("tolerance", 1e-10), is_positive, "> 0 (CG, relative)");
  const std::string preconditioner =
      r.optional_choice("preconditioner", {"auto", "jacobi", "multigrid"}).value_or("auto");
  if (solver != "cg" && r.has("preconditioner")) r.fail("preconditioner", "applies to solver = \"cg\" only");
  auto fluid = std::make_unique<PoreFluid<D>>(
      solver == "cg" ? PressureSolverKind::cg : PressureSolverKind::cholesky, tolerance,
      preconditioner == "jacobi"      ? CgPreconditioner::jacobi
      : preconditioner == "multigrid" ? CgPreconditioner::multigrid
                                      : CgPreconditioner::automatic);
  fluid->fluid.density = r.check("density", r.number("density"), is_positive, "> 0 kg/m^3");
  fluid->fluid.viscosity = r.check("viscosity", r.number("viscosity"), is_positive, "> 0 Pa s");
  fluid->fluid.bulk_modulus = r.check("bulk_modulus", r.number("bulk_modulus"), is_positive, "> 0 Pa");
  const std::string drag = r.choice("drag", {"darcy", "ergun"});
  fluid->drag = drag == "ergun" ? DragLaw::ergun : DragLaw::darcy;
  if (r.optional_choice("drag_cells", {"centre", "overlaps"}) == "overlaps")
    fluid->drag_cells = DragCells::overlaps;
  if (r.has("steps_per_update")) fluid->steps_per_update = read_steps_per_update(r);
  fluid->hold_forces = r.boolean_or("hold_forces", false);
  // Any finite height (the reader refuses nan and inf).
  if (const auto level = r.optional_number("water_level")) fluid->water_level = *level;

  double r_max = 0.0;
  for (double x : particles.radius) r_max = std::max(r_max, x);

  // [fluid.grid]
  {
    const toml::table* t = r.optional_table("grid");
    if (t == nullptr) r.fail_table("missing required table [fluid.grid] (origin, cells, size)");
    TableReader g(*t, "[fluid.grid]", file);
    // Either origin, cells and size (cells of one size), or a table per
    // axis (x, y[, z]), each uniform or graded.
    bool per_axis = false;
    for (int k = 0; k < D; ++k) per_axis = per_axis || g.has(std::string(1, "xyz"[k]));
    if (per_axis) {
      read_grid_axes<D>(g, fluid->grid, r_max, periodic.periodic);
    } else {
      read_uniform_grid<D>(g, fluid->grid, r_max);
    }
    // Along a periodic axis the grid spans the period: its ends meet.
    for (int k = 0; k < D; ++k) {
      if (!periodic.periodic[k]) continue;
      const double lo = periodic.lower[k];
      const double length = periodic.length[k];
      const auto& grid = fluid->grid;
      const double end = grid.face_at(k, grid.cells[k]);
      if (std::abs(grid.origin[k] - lo) > 1e-9 * length || std::abs(end - (lo + length)) > 1e-9 * length) {
        g.fail(
            per_axis                                        ? std::string(1, "xyz"[k])
            : std::abs(grid.origin[k] - lo) > 1e-9 * length ? "origin"
                                                            : "size",
            fmt::format("the scene is periodic along {} ([periodic] {} = [{}, {}]): the grid must span the "
                        "period, from {} m over cells x size = {} m along {}; it spans [{}, {}] m",
                        "xyz"[k], "xyz"[k], TableReader::format_number(lo),
                        TableReader::format_number(lo + length), TableReader::format_number(lo),
                        TableReader::format_number(length), "xyz"[k],
                        TableReader::format_number(grid.origin[k]), TableReader::format_number(end)));
      }
      fluid->grid.periodic[k] = true;
    }
    if (fluid->grid.size() > 50'000'000) g.fail("cells", "more than 5e7 cells");
    g.finish();
  }

  // [fluid.permeability]
  {
    const toml::table* t = r.optional_table("permeability");
    if (t == nullptr)
      r.fail_table("missing required table [fluid.permeability] (model = \"kozeny_carman\" or \"constant\")");
    TableReader p(*t, "[fluid.permeability]", file);
    auto& spec = fluid->permeability;
    const std::string model = p.choice("model", {"kozeny_carman", "constant"});
    p.allow({"diameter", "anisotropy", "hydraulic_conductivity", "intrinsic"});
    if (model == "kozeny_carman") {
      spec.model = PermeabilityModel::kozeny_carman;
      spec.diameter = p.check(
          "diameter", p.number_or("diameter", specific_surface_diameter<D>(particles.radius)),
          // d^2 enters kappa: it must neither underflow to 0 nor overflow.
          [](double d) { return d > 0.0 && std::isnormal(d * d); },
          "> 0 m, with d^2 neither 0 nor infinite in double precision");
      if (auto a = p.optional_numbers("anisotropy", D)) {
        for (int k = 0; k < D; ++k)
          spec.anisotropy[k] = p.check("anisotropy", (*a)[k], is_positive, "> 0 on every axis");
      }
      for (auto k : {"hydraulic_conductivity", "intrinsic"}) {
        if (p.has(k))
          p.fail(k, "does not apply to model \"kozeny_carman\" (it computes k from the porosity)");
      }
    } else {
      spec.model = PermeabilityModel::constant;
      for (auto k : {"diameter", "anisotropy"}) {
        if (p.has(k)) p.fail(k, "does not apply to model \"constant\"");
      }
      if (p.has("hydraulic_conductivity") == p.has("intrinsic")) {
        p.fail_table(
            "give exactly one of 'hydraulic_conductivity' (k, m/s, per axis) or 'intrinsic' (m^2, per axis)");
      }
      if (p.has("hydraulic_conductivity")) {
        const auto k = p.numbers("hydraulic_conductivity", D);
        for (int a = 0; a < D; ++a) {
          p.check("hydraulic_conductivity", k[a], is_positive, "> 0 m/s on every axis");
          spec.intrinsic[a] = k[a] * fluid->fluid.viscosity / fluid->fluid.unit_weight();
        }
      } else {
        const auto k = p.numbers("intrinsic", D);
        for (int a = 0; a < D; ++a)
          spec.intrinsic[a] = p.check("intrinsic", k[a], is_positive, "> 0 m^2 on every axis");
      }
    }
    spec.max_porosity = p.check(
        "max_porosity", p.number_or("max_porosity", 0.9), [](double v) { return v > 0.0 && v < 1.0; },
        "in (0, 1)");
    spec.min_porosity = p.check(
        "min_porosity", p.number_or("min_porosity", 0.05),
        [&](double v) { return v > 0.0 && v < spec.max_porosity; }, "in (0, max_porosity)");
    p.finish();
  }

  // [fluid.boundary]: sides not given are no-flow; patches.
  if (const toml::table* t = r.optional_table("boundary")) {
    std::vector<FluidPatch<D>> patches;
    for (auto& [side, b] :
         read_fluid_boundary_changes<D>(*t, "[fluid.boundary]", file, fluid.get(), &patches).sides)
      fluid->sides[side] = b;
    fluid->patches = patches;
  }
  // [[fluid.barrier]]: impermeable walls inside the grid.
  if (const toml::array* a = r.optional_array("barrier")) {
    int index = 0;
    for (const toml::node& node : *a) {
      ++index;
      const toml::table* t = node.as_table();
      if (t == nullptr) r.fail("barrier", "must be an array of tables: [[fluid.barrier]]");
      fluid->barriers.push_back(
          read_barrier<D>(*t, fmt::format("[[fluid.barrier]] #{}", index), file, fluid->grid));
    }
  }
  // [[fluid.source]]: wells and injection points inside the grid.
  if (const toml::array* a = r.optional_array("source")) {
    std::vector<std::string> taken = side_list<D>();
    for (const auto& p : fluid->patches) taken.push_back(p.name);
    int index = 0;
    for (const toml::node& node : *a) {
      ++index;
      const toml::table* t = node.as_table();
      if (t == nullptr) r.fail("source", "must be an array of tables: [[fluid.source]]");
      const std::string where = fmt::format("[[fluid.source]] #{}", index);
      fluid->sources.push_back(read_source<D>(*t, where, file, fluid->grid, fluid->permeability, taken));
      taken.push_back(fluid->sources.back().name);
      // Each in cells of its own: two pressures held in one cell would fight.
      const auto mine = source_cells(fluid->grid, fluid->sources.back());
      for (std::size_t j = 0; j + 1 < fluid->sources.size(); ++j) {
        for (const SourceCell& other : source_cells(fluid->grid, fluid->sources[j])) {
          const bool shared = std::any_of(mine.begin(), mine.end(),
                                          [&](const SourceCell& c) { return c.cell == other.cell; });
          if (!shared) continue;
          TableReader(*t, where, file)
              .fail(
                  fluid->sources.back().screened() ? "screen" : "position",
                  fmt::format("{} of source \"{}\": each source needs a cell of its "
                              "own (a source gives its water to, or holds its pressure in, its "
                              "whole cell; a screened well, to each cell it passes through)",
                              fluid->sources.back().screened() ? "passes through a cell" : "lies in the cell",
                              fluid->sources[j].name));
        }
      }
    }
  }
  // Impermeable box walls: barriers on their planes, checked like the
  // others but reported at the wall's 'impermeable' key.
  for (const auto& w : wall_barriers) {
    check_barrier(w.barrier, fluid->grid, [&](const char*, const std::string& message) {
      throw SceneError(fmt::format("{}the plate at {} = {} m: {}", w.error_prefix, "xyz"[w.barrier.axis],
                                   TableReader::format_number(w.barrier.at), message));
    });
    fluid->barriers.push_back(w.barrier);
  }
  r.finish();
  fluid->solid_walls = solid_walls;
  fluid->impermeable_walls = impermeable_walls;
  fluid->initialize(particles, walls);
  return fluid;
}

template std::vector<FluidSourceChange> read_source_changes<2>(const toml::table&, const std::string&,
                                                               const std::string&, const PoreFluid<2>&);
template std::vector<FluidSourceChange> read_source_changes<3>(const toml::table&, const std::string&,
                                                               const std::string&, const PoreFluid<3>&);
template FluidBoundaryChanges read_fluid_boundary_changes<2>(const toml::table&, const std::string&,
                                                             const std::string&, const PoreFluid<2>*,
                                                             std::vector<FluidPatch<2>>*);
template FluidBoundaryChanges read_fluid_boundary_changes<3>(const toml::table&, const std::string&,
                                                             const std::string&, const PoreFluid<3>*,
                                                             std::vector<FluidPatch<3>>*);
template std::unique_ptr<PoreFluid<2>> read_fluid<2>(const toml::table&, const std::string&,
                                                     const ParticleData<2>&,
                                                     const std::vector<WallBarrier<2>>&,
                                                     const PeriodicCell<2>&, const std::vector<Wall<2>>&,
                                                     const std::vector<std::size_t>&,
                                                     const std::vector<std::size_t>&);
template std::unique_ptr<PoreFluid<3>> read_fluid<3>(const toml::table&, const std::string&,
                                                     const ParticleData<3>&,
                                                     const std::vector<WallBarrier<3>>&,
                                                     const PeriodicCell<3>&, const std::vector<Wall<3>>&,
                                                     const std::vector<std::size_t>&,
                                                     const std::vector<std::size_t>&);

}  // namespace darcydem
