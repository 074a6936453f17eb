// Sources of water inside the grid (pore_fluid.hpp, [[fluid.source]]):
// their part of each fluid step's system, what they give after the solve,
// wells' bores (fluid/well_index.hpp), screened wells' bore pressures for a
// given inflow, and which drains stand open.
#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/fluid/well_index.hpp"

namespace darcydem {

template <int D>
typename PoreFluid<D>::SourcePass PoreFluid<D>::assemble_sources(double dt, double time) {
  // A source's water goes into its cell's right-hand side; one that holds
  // a pressure takes its cell out of the system (hold_pressure); what
  // water that takes is found after the solve. A well with a radius holds
  // its pressure at its bore instead, joined to its cell by its well
  // index, as a drained side's face is to its cell; a screened well joins
  // each of its cells to its bore so, each by its own index: held at a
  // pressure, that pressure is known; given an inflow, it is found after
  // the solve (superpose_given_screens). A shut drain gives nothing (a
  // screened one's bore still joins its cells, giving none).
  Eigen::VectorXd& diagonal = operator_.diagonal;
  SourcePass out;
  held_sources_.clear();
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const std::size_t c = source_cells_[i];
    const bool shut = sources[i].drains() && drain_open_[i] == 0;
    if (sources[i].screened()) {
      const bool held = sources[i].type == FluidSourceType::pressure && !shut;
      const double bore = held ? sources[i].value.at(time) : 0.0;
      for (const auto& [cell, index] : screen_well_indices(i)) {
        diagonal[static_cast<Eigen::Index>(cell)] += dt * index;
        rhs_[cell] += dt * index * bore;
      }
      if (held)
        out.bore_held.emplace_back(i, 0.0);
      else
        out.given_screens.emplace_back(i, shut ? 0.0 : sources[i].value.at(time));
      continue;
    }
    if (shut) {
      source_inflow_[i] = 0.0;
    } else if (sources[i].type == FluidSourceType::inflow) {
      source_inflow_[i] = sources[i].value.at(time);
      rhs_[c] += dt * source_inflow_[i];
    } else if (sources[i].radius > 0.0) {
      const double index = well_index(i);
      diagonal[static_cast<Eigen::Index>(c)] += dt * index;
      rhs_[c] += dt * index * sources[i].value.at(time);
      out.bore_held.emplace_back(i, index);
    } else {
      hold_pressure(i, sources[i].value.at(time));
    }
  }
  return out;
}

template <int D>
void PoreFluid<D>::take_source_inflows(const SourcePass& placed, double dt, double time) {
  // A source that holds a pressure gives the water its cell's own balance
  // lacks, with the cell at that pressure: its diagonal times it, less what
  // its neighbours draw, less its right-hand side.
  for (const HeldSource& h : held_sources_) {
    double lacking = h.diagonal * h.pressure - h.rhs;
    for (const auto& [neighbour, conductance] : h.couplings)
      lacking -= conductance * solution_[static_cast<Eigen::Index>(neighbour)];
    source_inflow_[h.source] = lacking / dt;
  }
  for (const auto& [i, index] : placed.bore_held) {
    const double bore = sources[i].value.at(time);
    if (!sources[i].screened()) {
      source_inflow_[i] = index * (bore - pressure_[source_cells_[i]]);
      continue;
    }
    source_inflow_[i] = 0.0;
    for (const auto& [cell, cell_index] : screen_well_indices(i))
      source_inflow_[i] += cell_index * (bore - pressure_[cell]);
  }
  for (const auto& [i, q] : placed.given_screens) source_inflow_[i] = q;
}

template <int D>
bool PoreFluid<D>::settle_drains(double time) {
  bool changed = false;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    if (!sources[i].drains()) continue;
    // Open, it shuts if it gives water; shut, it opens if the water around
    // it (at its bore, or in its cell) stands above its pressure.
    const bool open =
        drain_open_[i] != 0 ? source_inflow_[i] <= 0.0 : well_pressure(i) > sources[i].value.at(time);
    changed = changed || open != (drain_open_[i] != 0);
    drain_open_[i] = open ? 1 : 0;
  }
  return changed;
}

template <int D>
void PoreFluid<D>::superpose_given_screens(const std::vector<std::pair<std::size_t, double>>& wells,
                                           double dt) {
  // The system is linear in the bores' pressures p_m, which the solve took
  // as zero: u = u0 + sum_m p_m g_m, g_m the response to well m's bore at
  // unit pressure (the same matrix, right-hand side dt WI_c on m's cells).
  // Each well gives its inflow Q_l = sum_c WI_lc (p_l - u_c), which with
  // u so written is a small linear system for the p_m:
  //   p_l sum_c WI_lc - sum_m p_m sum_c WI_lc g_m[c] = Q_l + sum_c WI_lc u0_c.
  // Exact to the solver's tolerance; each such well costs one more solve
  // with the factorisation (or preconditioner) already made.
  const auto m = static_cast<Eigen::Index>(wells.size());
  const auto n = static_cast<Eigen::Index>(grid.size());
  std::vector<std::vector<std::pair<std::size_t, double>>> nodes;
  std::vector<Eigen::VectorXd> response;
  for (const auto& [w, q] : wells) {
    nodes.push_back(screen_well_indices(w));
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    for (const auto& [cell, index] : nodes.back()) b[static_cast<Eigen::Index>(cell)] = dt * index;
    Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
    const SolveStats stats = solver_.kind() == PressureSolverKind::cholesky
                                 ? solver_.solve(matrix_, b, g, true)
                                 : solver_.solve(operator_, b, g, true);
    last_solve_.iterations += stats.iterations;
    last_solve_.residual = std::max(last_solve_.residual, stats.residual);
    response.push_back(std::move(g));
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd r(m);
  for (Eigen::Index l = 0; l < m; ++l) {
    r[l] = wells[static_cast<std::size_t>(l)].second;
    for (const auto& [cell, index] : nodes[static_cast<std::size_t>(l)]) {
      const auto c = static_cast<Eigen::Index>(cell);
      a(l, l) += index;
      r[l] += index * solution_[c];
      for (Eigen::Index k = 0; k < m; ++k) a(l, k) -= index * response[static_cast<std::size_t>(k)][c];
    }
  }
  const Eigen::VectorXd bore = a.partialPivLu().solve(r);
  for (Eigen::Index k = 0; k < m; ++k) solution_ += bore[k] * response[static_cast<std::size_t>(k)];
}

template <int D>
std::vector<std::pair<std::size_t, double>> PoreFluid<D>::screen_well_indices(std::size_t source) const {
  std::vector<std::pair<std::size_t, double>> out;
  if constexpr (D == 3) {
    const FluidSource<D>& s = sources.at(source);
    for (const SourceCell& sc : screens_.at(source)) {
      const auto at = grid.coords(sc.cell);
      const Vec<3> widths(grid.width(0, at[0]), grid.width(1, at[1]), grid.width(2, at[2]));
      out.emplace_back(sc.cell, screen_well_index(s.screen_axis, widths, kappa_[sc.cell], fluid.viscosity,
                                                  s.radius, sc.length));
    }
  }
  return out;
}

template <int D>
std::vector<double> PoreFluid<D>::screen_inflows(std::size_t source) const {
  const double bore = well_pressure(source);
  std::vector<double> out;
  for (const auto& [cell, index] : screen_well_indices(source))
    out.push_back(index * (bore - pressure_[cell]));
  return out;
}

template <int D>
double PoreFluid<D>::equivalent_radius(std::size_t source) const {
  if constexpr (D == 3) {
    if (sources.at(source).screened()) {
      const Vec<3> widths = cell_widths_at(grid, sources[source].position);
      const Vec<3> shape = permeability_shape(permeability);
      const int axis = sources[source].screen_axis;
      return darcydem::equivalent_radius<2>(across(axis, widths), across(axis, shape));
    }
  }
  return darcydem::equivalent_radius<D>(cell_widths_at(grid, sources.at(source).position),
                                        permeability_shape(permeability));
}

template <int D>
double PoreFluid<D>::well_index(std::size_t source) const {
  const double radius = sources.at(source).radius;
  if (radius <= 0.0) return 0.0;
  if (sources[source].screened()) {
    double sum = 0.0;
    for (const auto& node : screen_well_indices(source)) sum += node.second;
    return sum;
  }
  return darcydem::well_index<D>(cell_widths_at(grid, sources.at(source).position),
                                 kappa_[source_cells_.at(source)], fluid.viscosity, radius);
}

template <int D>
double PoreFluid<D>::well_pressure(std::size_t source) const {
  if (sources.at(source).screened()) {
    double weighted = source_inflow_.at(source);
    double sum = 0.0;
    for (const auto& [cell, index] : screen_well_indices(source)) {
      weighted += index * pressure_[cell];
      sum += index;
    }
    return weighted / sum;
  }
  const double cell = pressure_[source_cells_.at(source)];
  const double index = well_index(source);
  return index > 0.0 ? cell + source_inflow_.at(source) / index : cell;
}

template <int D>
void PoreFluid<D>::hold_pressure(std::size_t source, double pressure) {
  // The cell is taken out of the system: its couplings to its neighbours
  // move to their right-hand sides at the held pressure (their diagonals
  // keep them), and its own row becomes diagonal * u = diagonal * p, its
  // scale kept. Exact: the cell is at p to the solver's tolerance, and the
  // matrix stays symmetric and positive definite.
  const std::size_t c = source_cells_[source];
  const auto ci = static_cast<Eigen::Index>(c);
  HeldSource h;
  h.source = source;
  h.pressure = pressure;
  h.diagonal = operator_.diagonal[ci];
  h.rhs = rhs_[c];
  const auto at = grid.coords(c);
  auto decouple = [&](std::size_t neighbour, double& conductance) {
    if (conductance == 0.0) return;
    h.couplings.emplace_back(neighbour, conductance);
    rhs_[neighbour] += conductance * pressure;
    conductance = 0.0;
  };
  for (int k = 0; k < D; ++k) {
    const std::size_t s = grid.stride(k);
    auto& upper = operator_.upper[static_cast<std::size_t>(k)];
    if (at[k] + 1 < grid.cells[k]) decouple(c + s, upper[ci]);
    if (at[k] > 0) decouple(c - s, upper[static_cast<Eigen::Index>(c - s)]);
  }
  for (auto& coupling : operator_.extra) {
    if (static_cast<std::size_t>(coupling.a) == c) decouple(static_cast<std::size_t>(coupling.b), coupling.g);
    if (static_cast<std::size_t>(coupling.b) == c) decouple(static_cast<std::size_t>(coupling.a), coupling.g);
  }
  rhs_[c] = h.diagonal * pressure;
  held_sources_.push_back(std::move(h));
}

#define DARCYDEM_SOURCES_INSTANTIATE(D)                                                                      \
  template PoreFluid<D>::SourcePass PoreFluid<D>::assemble_sources(double, double);                          \
  template void PoreFluid<D>::take_source_inflows(const SourcePass&, double, double);                        \
  template bool PoreFluid<D>::settle_drains(double);                                                         \
  template void PoreFluid<D>::superpose_given_screens(const std::vector<std::pair<std::size_t, double>>&,    \
                                                      double);                                               \
  template std::vector<std::pair<std::size_t, double>> PoreFluid<D>::screen_well_indices(std::size_t) const; \
  template std::vector<double> PoreFluid<D>::screen_inflows(std::size_t) const;                              \
  template double PoreFluid<D>::equivalent_radius(std::size_t) const;                                        \
  template double PoreFluid<D>::well_index(std::size_t) const;                                               \
  template double PoreFluid<D>::well_pressure(std::size_t) const;                                            \
  template void PoreFluid<D>::hold_pressure(std::size_t, double);
DARCYDEM_SOURCES_INSTANTIATE(2)
DARCYDEM_SOURCES_INSTANTIATE(3)
#undef DARCYDEM_SOURCES_INSTANTIATE

}  // namespace darcydem
