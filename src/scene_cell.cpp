#include "darcydem/scene/scene_cell.hpp"

#include <cmath>

#include <fmt/format.h>

namespace darcydem {
namespace {

/// Refuses a cell that cannot deform, at the stage's key.
template <int D>
void check_deformable(TableReader& r, const Simulation<D>& sim, const CellNeighbours& around) {
  const std::string why = cell_deformation_obstacle(sim, around);
  if (!why.empty()) r.fail("periodic_cell", "deforms the periodic cell, " + why);
}

}  // namespace

std::string cell_rate_rule(double time_step) {
  static_assert(CellMotion<3>::largest_stretch == 1e-3, "the rule's text gives the limit");
  return fmt::format(
      "below 1e-3 / time step = {} 1/s in magnitude (each step stretches the cell by 1 + rate x time step)",
      TableReader::format_number(CellMotion<3>::largest_stretch / time_step));
}

template <int D>
std::string describe_cell_motions(const Scene<D>& scene) {
  std::string out;
  CellMotion<D> motion;
  for (const auto& stage : scene.stages) {
    if (!stage.cell) continue;
    stage.cell->apply(motion);
    std::string axes;
    std::string strains;
    for (int k = 0; k < D; ++k) {
      const std::string sep = axes.empty() ? "" : ", ";
      if (motion.by_stress[k]) {
        axes += fmt::format("{}{} held at {:.6g} Pa", sep, "xyz"[k], motion.target_stress[k]);
      } else if (motion.strain_rate[k] != 0.0) {
        axes += fmt::format("{}{} strained at {:.6g} 1/s", sep, "xyz"[k], motion.strain_rate[k]);
        strains += fmt::format("{}{} {:.4g}", strains.empty() ? "" : ", ", "xyz"[k],
                               motion.strain_rate[k] * stage.duration);
      }
    }
    if (axes.empty()) axes = "fixed";
    // Every axis at a set rate: the volume's strain too (0: an undrained
    // test at constant volume).
    if (!motion.any_by_stress() && !strains.empty()) {
      strains += fmt::format(", volumetric {:.4g}", motion.strain_rate.sum() * stage.duration);
    }
    if (!strains.empty()) {
      axes += fmt::format(" (ln strains over the stage's {:.6g} s if it runs to its end: {})", stage.duration,
                          strains);
    }
    if (motion.any_by_stress()) {
      axes += fmt::format("; servo gain {:.6g} 1/(Pa s), at most {:.6g} 1/s, holding the {}", motion.gain,
                          motion.max_strain_rate,
                          motion.total_stress ? "total stress (contacts + pore water)" : "contacts' stress");
    }
    out += fmt::format("stage {}: periodic cell {}\n", stage.name, axes);
  }
  return out;
}

template <int D>
CellNeighbours cell_neighbours(const Scene<D>& scene) {
  CellNeighbours around;
  around.fluid = scene.fluid != nullptr;
  around.fluid_sources = scene.fluid != nullptr && !scene.fluid->sources.empty();
  around.fluid_barriers = scene.fluid != nullptr && !scene.fluid->barriers.empty();
  around.inlets = !scene.inlets.empty();
  return around;
}

template <int D>
std::string cell_deformation_obstacle(const Simulation<D>& sim, const CellNeighbours& around) {
  for (int k = 0; k < D; ++k) {
    if (!sim.periodic.periodic[k]) {
      return fmt::format(
          "which must repeat along every axis; [periodic] has no '{}' (allowed: a [periodic] "
          "table with {})",
          "xyz"[k], D == 2 ? "x and y" : "x, y and z");
    }
  }
  auto obstacle = [](const char* what) {
    return fmt::format(
        "which cannot be combined with {} (yet): the cell's stretch would carry the grains "
        "past them",
        what);
  };
  if (!sim.walls.empty()) return obstacle("walls ([[wall]])");
  if (around.fluid_sources) return obstacle("the pore fluid's sources ([[fluid.source]])");
  if (around.fluid_barriers) return obstacle("the pore fluid's barriers ([[fluid.barrier]])");
  if (around.inlets) return obstacle("inlets ([[inlet]])");
  if (!sim.clumps.empty()) return obstacle("clumps");
  if (sim.has_domain) return obstacle("a [domain]");
  return "";
}

template <int D>
CellChange<D> read_cell_change(TableReader& stage, const Simulation<D>& sim, const CellNeighbours& around,
                               CellMotion<D>& planned) {
  const toml::table* t = stage.optional_table("periodic_cell");
  if (t == nullptr) {
    stage.fail("periodic_cell",
               "must be a table, e.g. periodic_cell = { x = { stress = 1e5 }, y = { strain_rate = -0.01 }, "
               "gain = 1e-6, max_strain_rate = 0.1 }");
  }
  check_deformable<D>(stage, sim, around);
  TableReader r(*t, stage.where() + " periodic_cell", stage.file());
  CellChange<D> change;
  bool any = false;
  for (int k = 0; k < D; ++k) {
    const std::string axis(1, "xyz"[k]);
    const toml::table* at = r.optional_table(axis);
    if (at == nullptr) {
      if (r.has(axis)) r.fail(axis, "must be a table: { strain_rate = 1/s } or { stress = Pa }");
      continue;
    }
    TableReader ar(*at, fmt::format("{}.{}", r.where(), axis), r.file());
    const bool rate = ar.has("strain_rate");
    const bool stress = ar.has("stress");
    if (rate == stress) {
      ar.fail_table(
          "needs either 'strain_rate' (1/s, negative: the cell shrinks along the axis) or 'stress' (Pa, "
          "compression positive, held by the servo), not both");
    }
    auto finite = [](double v) { return std::isfinite(v); };
    typename CellChange<D>::Axis a;
    a.by_stress = stress;
    a.value = stress ? ar.check("stress", ar.number("stress"), finite, "a finite number (Pa)")
                     : ar.check("strain_rate", ar.number("strain_rate"), finite, "a finite number (1/s)");
    ar.finish();
    change.axes[k] = a;
    any = true;
  }
  if (auto g = r.optional_number("gain"))
    change.gain = r.check(
        "gain", *g, [](double v) { return v > 0.0 && std::isfinite(v); }, "> 0 1/(Pa s)");
  if (auto m = r.optional_number("max_strain_rate")) {
    change.max_strain_rate = r.check(
        "max_strain_rate", *m, [](double v) { return v > 0.0 && std::isfinite(v); }, "> 0 1/s");
  }
  if (r.has("load")) {
    change.total_stress = r.optional_choice("load", {"grains", "total"}) == "total";
    if (*change.total_stress && !around.fluid) {
      r.fail("load",
             "\"total\" adds the pore water's mean pressure to the contacts' stress, which needs a [fluid]; "
             "give \"grains\", the default");
    }
  }
  r.finish();
  if (!any && !change.gain && !change.max_strain_rate && !change.total_stress) {
    r.fail_table("needs an axis ('x', 'y'" + std::string(D == 3 ? ", 'z'" : "") +
                 ") = { strain_rate = 1/s } or { stress = Pa }, or the servo's 'gain', 'max_strain_rate' or "
                 "'load'");
  }
  change.apply(planned);
  if (planned.servo_incomplete()) {
    if (planned.gain == 0.0) r.missing("gain", "the servo's gain, 1/(Pa s): rate = gain x (stress - target)");
    if (planned.max_strain_rate == 0.0) r.missing("max_strain_rate", "the servo's largest strain rate, 1/s");
  }
  return change;
}

template <int D>
void check_cell_rates(const toml::array& stages, const std::vector<Stage<D>>& read, double time_step,
                      const std::string& file) {
  auto too_fast = [&](double rate) { return !CellMotion<D>::rate_allowed(rate, time_step); };
  const std::string allowed = cell_rate_rule(time_step);
  for (std::size_t i = 0; i < read.size() && i < stages.size(); ++i) {
    const auto& change = read[i].cell;
    if (!change) continue;
    TableReader stage(*stages[i].as_table(), fmt::format("[[stage]] #{}", i + 1), file);
    TableReader r(*stage.optional_table("periodic_cell"), stage.where() + " periodic_cell", file);
    if (change->max_strain_rate && too_fast(*change->max_strain_rate)) {
      r.fail("max_strain_rate", fmt::format("must be {}, got {}", allowed,
                                            TableReader::format_number(*change->max_strain_rate)));
    }
    for (int k = 0; k < D; ++k) {
      const auto& a = change->axes[k];
      if (!a || a->by_stress || !too_fast(a->value)) continue;
      const std::string axis(1, "xyz"[k]);
      TableReader ar(*r.optional_table(axis), fmt::format("{}.{}", r.where(), axis), file);
      ar.fail("strain_rate",
              fmt::format("must be {}, got {}", allowed, TableReader::format_number(a->value)));
    }
  }
}

template void check_cell_rates<2>(const toml::array&, const std::vector<Stage<2>>&, double,
                                  const std::string&);
template void check_cell_rates<3>(const toml::array&, const std::vector<Stage<3>>&, double,
                                  const std::string&);
template std::string describe_cell_motions<2>(const Scene<2>&);
template std::string describe_cell_motions<3>(const Scene<3>&);
template CellNeighbours cell_neighbours<2>(const Scene<2>&);
template CellNeighbours cell_neighbours<3>(const Scene<3>&);
template std::string cell_deformation_obstacle<2>(const Simulation<2>&, const CellNeighbours&);
template std::string cell_deformation_obstacle<3>(const Simulation<3>&, const CellNeighbours&);
template CellChange<2> read_cell_change<2>(TableReader&, const Simulation<2>&, const CellNeighbours&,
                                           CellMotion<2>&);
template CellChange<3> read_cell_change<3>(TableReader&, const Simulation<3>&, const CellNeighbours&,
                                           CellMotion<3>&);

}  // namespace darcydem
