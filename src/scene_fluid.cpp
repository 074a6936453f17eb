#include "darcydem/scene/scene_fluid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

namespace darcydem {
namespace {

template <int D>
std::vector<std::string> side_list() {
  return std::vector<std::string>(side_names, side_names + 2 * D);
}

/// A number, or a table { times = [...], values = [...] } (s from the start
/// of the stage, piecewise linear).
TimeSeries read_series(TableReader& r, std::string_view key, const std::string& unit) {
  const toml::node* n = r.raw(key);
  if (n == nullptr) r.fail_table(fmt::format("missing required key '{}' ({})", key, unit));
  if (auto v = n->value<double>(); v && (n->is_floating_point() || n->is_integer())) {
    if (!std::isfinite(*v)) r.fail(key, "must be a finite number");
    return TimeSeries::constant(*v);
  }
  const toml::table* t = n->as_table();
  if (t == nullptr) {
    r.fail(key, fmt::format("must be a number ({}) or a table {{ times = [...], values = [...] }}", unit));
  }
  TableReader tr(*t, fmt::format("{} {}", r.where(), key), r.file());
  TimeSeries s;
  s.times = tr.number_list("times");
  s.values = tr.number_list("values");
  if (s.values.size() != s.times.size()) tr.fail("values", "must have as many entries as 'times'");
  for (std::size_t i = 0; i < s.times.size(); ++i) {
    if (!(s.times[i] >= 0.0)) tr.fail("times", "must be >= 0 s (counted from the start of the stage)");
    if (i > 0 && !(s.times[i] > s.times[i - 1])) tr.fail("times", "must increase strictly");
  }
  tr.finish();
  return s;
}

}  // namespace

template <int D>
std::vector<std::pair<int, FluidBoundary>> read_fluid_sides(const toml::table& table,
                                                            const std::string& where,
                                                            const std::string& file) {
  std::vector<std::pair<int, FluidBoundary>> out;
  const auto names = side_list<D>();
  TableReader r(table, where, file);
  for (int s = 0; s < 2 * D; ++s) {
    const toml::table* t = r.optional_table(names[s]);
    if (t == nullptr) {
      if (r.has(names[s])) r.fail(names[s], "must be a table, e.g. { type = \"drained\", pressure = 0.0 }");
      continue;
    }
    TableReader sr(*t, fmt::format("{}.{}", where, names[s]), file);
    FluidBoundary b;
    const std::string type = sr.choice("type", {"drained", "flux", "no_flow"});
    sr.allow({"pressure", "inflow"});
    if (type == "drained") {
      if (sr.has("inflow")) sr.fail("inflow", "does not apply to a drained side (give 'pressure')");
      b.type = FluidBoundaryType::drained;
      b.value = read_series(sr, "pressure", "excess pore pressure, Pa");
    } else if (type == "flux") {
      if (sr.has("pressure")) sr.fail("pressure", "does not apply to a flux side (give 'inflow')");
      b.type = FluidBoundaryType::flux;
      b.value = read_series(sr, "inflow", "Darcy velocity into the grid, m/s");
    } else {
      for (auto k : {"pressure", "inflow"}) {
        if (sr.has(k)) sr.fail(k, "does not apply to a no_flow side");
      }
      b.type = FluidBoundaryType::no_flow;
    }
    sr.finish();
    out.emplace_back(s, b);
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
                                         const ParticleData<D>& particles) {
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
  if (r.has("steps_per_update")) fluid->steps_per_update = read_steps_per_update(r);
  fluid->hold_forces = r.boolean_or("hold_forces", false);

  double r_max = 0.0;
  double d_sum = 0.0;
  for (double x : particles.radius) {
    r_max = std::max(r_max, x);
    d_sum += 2.0 * x;
  }
  const double d_mean = particles.size() > 0 ? d_sum / static_cast<double>(particles.size()) : 0.0;

  // [fluid.grid]
  {
    const toml::table* t = r.optional_table("grid");
    if (t == nullptr) r.fail_table("missing required table [fluid.grid] (origin, cells, size)");
    TableReader g(*t, "[fluid.grid]", file);
    const auto origin = g.numbers("origin", D);
    const auto cells = g.numbers("cells", D);
    const auto size = g.numbers("size", D);
    for (int k = 0; k < D; ++k) {
      fluid->grid.origin[k] = origin[k];
      if (!(cells[k] >= 1.0) || cells[k] != std::floor(cells[k]) || cells[k] > 1e6)
        g.fail("cells", "must be whole numbers of cells >= 1 along each axis");
      fluid->grid.cells[k] = static_cast<int>(cells[k]);
      g.check("size", size[k], is_positive, "> 0 m along each axis (the size of one cell)");
      if (size[k] < 2.0 * r_max * (1.0 - 1e-12)) {
        g.fail("size",
               fmt::format("cells must be at least one grain diameter wide: {:.4g} m along {} is less "
                           "than the largest diameter {:.4g} m",
                           size[k], "xyz"[k], 2.0 * r_max));
      }
      fluid->grid.spacing[k] = size[k];
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
      spec.diameter = p.check("diameter", p.number_or("diameter", d_mean), is_positive, "> 0 m");
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

  // [fluid.boundary]: sides not given are no-flow.
  if (const toml::table* t = r.optional_table("boundary")) {
    for (auto& [side, b] : read_fluid_sides<D>(*t, "[fluid.boundary]", file)) fluid->sides[side] = b;
  }
  r.finish();
  fluid->initialize(particles);
  return fluid;
}

template std::vector<std::pair<int, FluidBoundary>> read_fluid_sides<2>(const toml::table&,
                                                                        const std::string&,
                                                                        const std::string&);
template std::vector<std::pair<int, FluidBoundary>> read_fluid_sides<3>(const toml::table&,
                                                                        const std::string&,
                                                                        const std::string&);
template std::unique_ptr<PoreFluid<2>> read_fluid<2>(const toml::table&, const std::string&,
                                                     const ParticleData<2>&);
template std::unique_ptr<PoreFluid<3>> read_fluid<3>(const toml::table&, const std::string&,
                                                     const ParticleData<3>&);

}  // namespace darcydem
