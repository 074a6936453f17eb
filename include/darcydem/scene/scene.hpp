#pragma once
// A scene: the simulation set up from a TOML file, with what to output and
// the list of stages to run. Documented key by key in docs/SCENE.md.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "darcydem/core/vec.hpp"
#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/generation/inlet.hpp"
#include "darcydem/simulation/simulation.hpp"

namespace darcydem {

enum class ProbeQuantity {
  particle_position,
  particle_velocity,
  wall_position,
  wall_force,
  wall_fluid_force,  ///< the excess pore water's thrust on a wall, N (PoreFluid::wall_thrust, barrier_thrust)
  wall_torque,       ///< the particles' moment on a cylinder about its axis, N m (Wall::torque)
  wall_radius,       ///< a cylinder's radius, m (a servo changes it)
  wall_stress,       ///< the particles' load on a plane over its loaded area, Pa (walls/loaded_area.hpp)
  wall_target,       ///< a servo's target as the last step took it, N or Pa (NaN: not a servo)
  kinetic_energy,
  elastic_energy,        ///< J, stored in the contacts' and bonds' springs (Simulation::elastic_energy)
  gravitational_energy,  ///< J, -sum m g.x (zero at the origin)
  // The energy budget since the run began (Simulation::energy; the scene
  // turns on Simulation::track_energy when a probe asks for one of these), J.
  gravity_work,         ///< by gravity on the free grains
  fluid_work,           ///< by the pore fluid's forces (the force field) on the grains
  boundary_work,        ///< by moving walls and moving fixed grains on the free grains
  damping_dissipation,  ///< taken by local and viscous damping
  contact_dissipation,  ///< taken by the contacts and not stored in their springs
  contact_count,
  coordination,
  max_overlap,
  unbalanced_force,
  pore_pressure,           ///< excess pore pressure at a point, Pa
  fluid_inflow,            ///< flow into the grid through one side, m^3/s
  side_pressure,           ///< excess pressure on one side (or patch) of the grid, Pa
  fluid_balance,           ///< inflow - stored - pore change since the start, m^3
  fluid_iterations,        ///< iterations of the last pressure solve
  screen_inflow,           ///< what one cell of a screened well took from its bore, m^3/s
  particles_in_box,        ///< how many particle centres lie in a box
  mean_particle_position,  ///< one component of their mean centre, m (NaN with none)
  stress,             ///< a component of the contacts' mean stress in a box, Pa (Simulation::contact_stress)
  fabric,             ///< a component of the contacts' fabric tensor in a box (Simulation::contact_fabric)
  porosity,           ///< 1 - the grains' volume in a box (exact overlaps) / its volume
  removed_particles,  ///< how many particles have left the [domain] so far
  removed_mass,       ///< their mass, kg (2D: per metre)
  particle_fluid_force,  ///< the pore fluid's force on one particle, N (Simulation::field_forces)
  fluid_force,           ///< the pore fluid's force on the particles whose centres lie in a box, N
  inserted_particles,    ///< how many particles an inlet (or all) has added so far (a clump: its members)
  inserted_mass,         ///< their mass, kg (2D: per metre)
  bonds,                 ///< contact bonds intact now
  broken_bonds,          ///< contact bonds broken so far
  cell_length,           ///< the periodic cell's length along an axis, m
  cell_strain_rate,      ///< its strain rate along an axis, 1/s (CellMotion)
  cell_strain,           ///< ln(L / L at the stage's start) along an axis, or the volumetric sum
  cell_stress,           ///< a component of the contacts' mean stress over it, Pa (Simulation::cell_stress)
};

struct ProbeSpec {
  std::string name;
  ProbeQuantity quantity = ProbeQuantity::kinetic_energy;
  std::int64_t particle = -1;  ///< creation index; -1: the topmost particle
  int component = 0;           ///< 0..D-1, or -1 for the norm
  std::size_t wall = 0;
  /// wall_fluid_force: the wall's barrier in PoreFluid::barriers (an
  /// impermeable plate), or -1 (a wall that displaces the fluid)
  std::int64_t barrier = -1;
  std::int64_t inlet = -1;       ///< inserted_particles, inserted_mass: the inlet's index, -1: all
  std::vector<double> position;  ///< pore_pressure: the point, m
  int side = 0;                  ///< fluid_inflow, side_pressure: x_min, x_max, y_min, ...
  std::size_t screen_cell = 0;   ///< screen_inflow: the cell's place along the screen, from 0
  /// particles_in_box, mean_particle_position, stress, porosity, fluid_force: the box, m
  std::vector<double> box_min, box_max;
  std::array<int, 2> tensor{0, 0};  ///< stress, fabric: the component (i, j); (-1, -1) the mean, trace / D
};

struct OutputSpec {
  double probe_interval = 0.0;     ///< s (0: every step)
  double snapshot_interval = 0.0;  ///< s (0: only at the end of each stage)
  bool contacts = true;            ///< the contact network with every snapshot (contacts_NNNNN.vtu)
  std::vector<ProbeSpec> probes;
};

struct TimeStepSpec {
  bool automatic = true;
  double value = 0.0;          ///< s, when not automatic
  double safety_factor = 0.2;  ///< fraction of the critical step
};

template <int D>
struct WallChange {
  std::size_t wall = 0;
  WallMotion motion = WallMotion::fixed;
  Vec<D> velocity = Vec<D>::Zero();
  ServoControl servo;
  Vec<D> servo_axis = Vec<D>::Zero();  ///< a box's (Wall::servo_axis)
  double spin = 0.0;                   ///< rad/s (Wall::spin)
  Vec<D> spin_axis = Vec<D>::Zero();   ///< a 3D plane's or box's axis of turn (Wall::axis), unit or zero
  double radius_rate = 0.0;            ///< m/s, a cylinder's (Wall::radius_rate)
  WallOscillation<D> oscillation;      ///< none unless the entry gives one; it starts with the stage
};

template <int D>
struct Stage {
  std::string name;
  double duration = 0.0;  ///< s; the longest the stage runs
  std::optional<Vec<D>> gravity;
  std::optional<double> local_damping;
  std::optional<double> viscous_damping;
  std::optional<double> kinetic_energy_below;    ///< J: stop once below
  std::optional<double> unbalanced_force_below;  ///< -: stop once below
  /// A probe's value: stop once above `probe_above` or below `probe_below`
  /// (either or both; a NaN reading stops nothing).
  std::optional<std::size_t> stop_probe;  ///< index in OutputSpec::probes
  std::optional<double> probe_above;
  std::optional<double> probe_below;
  std::int64_t check_interval = 100;  ///< steps between stop checks
  std::vector<WallChange<D>> walls;
  std::vector<std::pair<int, FluidBoundary>> fluid_sides;    ///< changes of the fluid's sides
  std::vector<std::pair<int, FluidBoundary>> fluid_patches;  ///< and of its patches (index in patches)
  std::vector<FluidSourceChange> fluid_sources;              ///< and of its sources
  std::optional<bool> fluid_drained;                 ///< every cell at zero excess pressure (true) or not
  std::optional<bool> freeze_permeability;           ///< hold (true) or resume updating k
  std::optional<int> fluid_steps_per_update;         ///< a new coupling interval M
  std::optional<bool> fluid_hold_forces;             ///< hold the grains' fluid forces, or not
  std::vector<std::pair<std::size_t, bool>> inlets;  ///< inlets (index) switched on or off
  /// New Coulomb coefficients: the two materials (indices) and mu, e.g.
  /// none while a sample is compacted and the sand's for the test (YADE's
  /// compaction friction, PFC's contact property changes).
  struct FrictionChange {
    std::uint16_t first = 0;
    std::uint16_t second = 0;
    double friction = 0.0;
  };
  std::vector<FrictionChange> frictions;
  std::optional<CellChange<D>> cell;  ///< the periodic cell's deformation from this stage on
  bool make_bonds = false;            ///< bond the pairs that can be bonded at the stage's start
  double bond_gap = 0.0;              ///< m: and those less than this apart
};

/// [analysis] kind = "seepage_column": the paper's 1D upward seepage check.
struct SeepageColumnSpec {
  std::string settle_stage;            ///< stage that settles the column (m_v, n measured there)
  std::string inflow_stage;            ///< stage with the inflow at the bottom
  std::vector<double> pressure_times;  ///< s after the inflow starts
  double uplift_interval = 1e-3;       ///< s between uplift samples
  double uplift_tolerance = 0.02;      ///< RMS uplift error / final uplift
  double pressure_tolerance = 0.03;    ///< max pressure error / steady bottom pressure
  bool plots = true;                   ///< write PNG plots with matplotlib
};

template <int D>
struct Scene {
  std::string file;
  std::string text_hash;  ///< FNV-1a 64 of the scene file's bytes, hex
  Simulation<D> simulation;
  TimeStepSpec time_step;
  OutputSpec output;
  std::vector<Stage<D>> stages;
  std::unique_ptr<PoreFluid<D>> fluid;  ///< optional pore fluid ([fluid])
  std::optional<SeepageColumnSpec> seepage_column;
  std::vector<Inlet<D>> inlets;  ///< [[inlet]]: grains added during the run
  /// s: the critical time step the scene's time step was set against, the
  /// inlets' smallest grains counted.
  double critical_time_step = 0.0;
  /// What the reader found worth saying about a scene it accepts (e.g. a
  /// grading the few grains drawn follow loosely): `darcydem check` and the
  /// run log print them.
  std::vector<std::string> notes;
  /// The `--set PATH=VALUE` changes the scene was built with
  /// (apply_scene_overrides), for the run log and run.json.
  std::vector<std::string> overrides;
};

/// Reads `simulation.dimension` (2 or 3) from a parsed scene.
int scene_dimension(const toml::table& root, const std::string& file);

/// Builds a scene from a parsed file; throws SceneError on bad input. Sets
/// the time step (checked against the critical step).
template <int D>
Scene<D> build_scene(const toml::table& root, const std::string& file, const std::string& text);

std::string fnv1a_hex(const std::string& bytes);

}  // namespace darcydem
