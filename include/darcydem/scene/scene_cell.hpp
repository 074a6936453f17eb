#pragma once
// Reading a stage's `periodic_cell`: the periodic cell's deformation from
// that stage on, axis by axis a strain rate or a target stress held by a
// servo (cell_motion.hpp). Documented in docs/SCENE.md.
#include <string>
#include <vector>

#include "darcydem/core/cell_motion.hpp"
#include "darcydem/scene/scene.hpp"
#include "darcydem/scene/toml_reader.hpp"
#include "darcydem/simulation/simulation.hpp"

namespace darcydem {

/// What the scene around the cell has that a deforming cell cannot take.
struct CellNeighbours {
  bool fluid = false;           ///< [fluid]: its pressure can add to the servo's stress
  bool fluid_sources = false;   ///< [[fluid.source]]: fixed places in the grid
  bool fluid_barriers = false;  ///< [[fluid.barrier]]: fixed planes in the grid
  bool inlets = false;
};

/// The scene's CellNeighbours (its fluid and inlets as built so far).
template <int D>
CellNeighbours cell_neighbours(const Scene<D>& scene);

/// What CellMotion::rate_allowed allows with time step `time_step`, for
/// messages: "below 1e-3 / time step = ... 1/s in magnitude (...)".
std::string cell_rate_rule(double time_step);

/// For `darcydem check`: one line per stage with a `periodic_cell`, the
/// cell's whole motion from that stage on ("stage NAME: periodic cell x
/// held at 100000 Pa, z strained at -1 1/s (ln strains over the stage's
/// 0.2 s if it runs to its end: z -0.2); servo gain ..., at most ... 1/s");
/// "" for a scene whose cell never deforms.
template <int D>
std::string describe_cell_motions(const Scene<D>& scene);

/// Why the cell of `sim` cannot deform ("which must repeat along every
/// axis; ..."), or "" if it can.
template <int D>
std::string cell_deformation_obstacle(const Simulation<D>& sim, const CellNeighbours& around);

/// The stage's `periodic_cell` table (read through `stage`, the stage's
/// reader), refused with the file, line and key if it is malformed or the
/// scene cannot deform its cell. `planned` is the cell's motion as the
/// stages before this one leave it; the change is applied to it.
template <int D>
CellChange<D> read_cell_change(TableReader& stage, const Simulation<D>& sim, const CellNeighbours& around,
                               CellMotion<D>& planned);

/// Refuses, at the stage's key, a strain rate or a servo's largest rate
/// that stretches the cell by a thousandth or more in one time step
/// (checked once the time step is known). `stages` is the scene's
/// [[stage]] array, `read` what was read from it.
template <int D>
void check_cell_rates(const toml::array& stages, const std::vector<Stage<D>>& read, double time_step,
                      const std::string& file);

}  // namespace darcydem
