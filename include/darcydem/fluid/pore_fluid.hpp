#pragma once
// The pore fluid: excess pore pressure on a fixed grid, coupled both ways
// with the grains (the paper's algorithm, docs/ARCHITECTURE.md).
//
// One fluid step (every `steps_per_update` DEM steps), per cell c:
//   1. solid volume Vs_c from the exact overlap of every grain with the cell;
//      porosity n = 1 - Vs/V; mean solid velocity; permeability.
//   2. Biot + Darcy, backward Euler, one SPD system for the grid:
//        S_c (u_c - u_c_old) = dVs_c                       (Biot: (K_f/n) eps_v)
//                            + dt sum_faces T_f (u_nb - u_c) (Darcy, implicit)
//                            + dt (fluid carried across faces by the moving skeleton)
//                            + dt (boundary inflow)
//      with S_c = n V / K_f and T_f = (kappa_f / mu) A / h, kappa_f the
//      harmonic mean of the two cells.
//   3. face pressure gradients and Darcy fluxes q = -(kappa/mu) grad u.
// Forces on each grain (every DEM step): -V_p grad u + drag + buoyancy.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Sparse>

#include "darcydem/core/lanes.hpp"
#include "darcydem/core/vec.hpp"
#include "darcydem/fluid/box_cell_overlap.hpp"
#include "darcydem/fluid/fluid_boundary.hpp"
#include "darcydem/fluid/fluid_grid.hpp"
#include "darcydem/fluid/fluid_laws.hpp"
#include "darcydem/fluid/pressure_solver.hpp"
#include "darcydem/fluid/well_index.hpp"
#include "darcydem/particles/particle_data.hpp"
#include "darcydem/simulation/force_field.hpp"
#include "darcydem/walls/wall.hpp"

namespace darcydem {

/// Fluid volumes of one fluid step and of the run so far (m^3).
struct FluidBalance {
  double inflow = 0.0;       ///< across the grid's sides and from its sources, into the grid
  double stored = 0.0;       ///< sum S (u - u_old): compression of the pore fluid
  double pore_change = 0.0;  ///< increase of pore volume, -(change of solid volume)
  double gross = 0.0;        ///< sum of the magnitudes of all the terms (each side's flow too)
  [[nodiscard]] double imbalance() const { return inflow - stored - pore_change; }
};

/// Wall-clock seconds of the parts of the last fluid update.
struct FluidUpdateTimes {
  double overlaps = 0.0;    ///< grain/cell overlaps, solid volumes and fluxes
  double properties = 0.0;  ///< porosity, permeability, drag coefficients per cell
  double assembly = 0.0;    ///< the matrix and right-hand side
  double solve = 0.0;       ///< the linear solve
  double fields = 0.0;      ///< face gradients and fluxes, the balance
};

template <int D>
class PoreFluid final : public ParticleForceField<D> {
 public:
  FluidGrid<D> grid;
  FluidProperties fluid;
  PermeabilitySpec<D> permeability;
  DragLaw drag = DragLaw::darcy;
  /// centre: each grain's drag from the cell holding its centre; overlaps:
  /// from every cell it overlaps, weighted by the overlap volumes, so that
  /// the drag summed over a cell's grains is what its porosity and
  /// permeability give (exact force balance with few grains per cell), at
  /// the cost of an overlap computation in every force evaluation.
  DragCells drag_cells = DragCells::centre;
  int steps_per_update = 1;  ///< DEM steps per fluid step
  /// Hold each grain's fluid force from the first DEM step after a fluid
  /// step until the next fluid step (the coupling interval of PFC's and
  /// CFDEM's fluid coupling); false: recompute it every DEM step from the
  /// last fluid step's pressure and flux, at the grain's current position
  /// and velocity. The same when steps_per_update is 1.
  bool hold_forces = false;
  /// True when the pore pressure stays uniform for the whole run, so that
  /// no grain feels a gradient of it: a grid of one cell whose sides and
  /// patches are never drained (the scene reader sets it from every
  /// stage's conditions: sealed_single_cell). The water's undrained
  /// stiffness then acts on the walls that displace it, not on a grain,
  /// and critical_time_step leaves it out: a lumped sample, as a CU test's
  /// single cell.
  bool uniform_pressure = false;
  std::array<FluidBoundary, 2 * D> sides{};  ///< x_min, x_max, y_min, ...
  /// Parts of sides with their own condition, each boundary face in at
  /// most one (the scene reader checks it; the first that holds a face
  /// takes it). Set before initialize(), which finds their faces.
  std::vector<FluidPatch<D>> patches;
  /// Sources of water inside the grid, each into the cell holding its
  /// position (a position outside the grid is a logic error; the scene
  /// reader checks it), giving an inflow or holding a pressure there (at
  /// most one that holds a pressure in a cell). Set before initialize(),
  /// which finds their cells.
  std::vector<FluidSource<D>> sources;
  /// Impermeable walls inside the grid. Set before initialize(), which
  /// finds their faces.
  std::vector<FluidBarrier<D>> barriers;
  /// Walls that take up pore volume, as indices into the walls given to
  /// initialize() and update(): boxes, and planes normal to a grid axis
  /// (the half-space behind one, behind_plane). In each cell the wall's
  /// exact volume there (box_cell_overlap.hpp) is solid, like the grains' (porosity,
  /// storage, permeability); a moving one changes it, which the Biot term
  /// turns into pressure and flow, so it pushes the pore water ahead of it.
  /// Where the planes' solids overlap (a cell's platens meet at its edges
  /// and corners), their union counts once, and a box counts only its part
  /// outside them; boxes overlapping each other add up.
  std::vector<std::size_t> solid_walls;
  /// Of solid_walls, those the pore water cannot cross either (a wall's
  /// `impermeable`): boxes along the grid's axes and planes. Every face
  /// they cover (where the wall lies on either side of it, on the face
  /// itself included), at this fluid step and the last, is closed to flow
  /// in proportion to the area covered:
  /// its conductance, the fluid the skeleton carries through it and, on a
  /// side of the grid, the side's inflow are scaled by the open part. The
  /// cells a wall fills are cut off. Their thrust (wall_thrust) is the
  /// pressure on their faces in the water.
  std::vector<std::size_t> impermeable_walls;
  /// Whether wall w (an index as in solid_walls) is one of impermeable_walls.
  [[nodiscard]] bool is_impermeable(std::size_t w) const {
    return std::find(impermeable_walls.begin(), impermeable_walls.end(), w) != impermeable_walls.end();
  }
  /// Count the pore fluid carried across faces by the moving skeleton, so
  /// that Darcy's flux is relative to the grains (false: the paper's scheme).
  bool carry_with_solid = true;
  /// Every cell open to water at zero excess pressure: the pore volume's
  /// change flows in or out where it happens, and no pressure builds (a
  /// drained stage of a sample whose drainage the grid does not hold, as a
  /// periodic cell's: the consolidation before an undrained shear). The
  /// balance counts that flow as inflow.
  bool drained = false;
  /// Keep each cell's permeability as it is (a stage can freeze it, e.g. to
  /// compare with a closed form that assumes a constant k).
  bool permeability_frozen = false;
  /// The height of a free water surface (along y in 2D, z in 3D), m: a
  /// grain whose centre is outside the grid and below it is in free water,
  /// with its buoyancy, -rho_f g V_p, and a grain's drag alone in water
  /// (lone_grain_drag), e.g. a grain lifted above a heaving bed. Above the
  /// grid's top the water rises at the Darcy flux through the top face
  /// below; beside or below the grid it is still. NaN (the default): no
  /// fluid outside the grid, as above the water.
  double water_level = std::numeric_limits<double>::quiet_NaN();

  PoreFluid(PressureSolverKind solver = PressureSolverKind::cg, double tolerance = 1e-10,
            CgPreconditioner preconditioner = CgPreconditioner::automatic);

  /// Solid volumes, porosity and permeability from the particles; pressure
  /// zero. Call once before the first update.
  void initialize(const ParticleData<D>& particles, const std::vector<Wall<D>>& walls = {});
  /// Sets the excess pressure of every cell (Pa), e.g. an initial field
  /// or a restart, after initialize(); gradients and fluxes follow, and the
  /// next update starts from it. Throws std::invalid_argument if the size
  /// is not the number of cells.
  void set_pressure(const std::vector<double>& u);
  /// One fluid step of length dt ending at `time`; `walls` holds the
  /// solid_walls where they are now.
  void update(const ParticleData<D>& particles, double dt, double time,
              const std::vector<Wall<D>>& walls = {});

  void particle_forces(const ParticleData<D>& particles, const Vec<D>& gravity,
                       std::vector<Vec<D>>& force) const override;
  /// A grid periodic along every axis, without graded axes, stretched to
  /// span the deforming cell as it is now: its cells keep their count and
  /// take the period's share. The next update counts the cells' change of
  /// volume, as a change of their pore volume, into the Biot term and the
  /// balance. Throws std::logic_error on any other grid.
  void follow_cell(const PeriodicCell<D>& cell) override;
  /// The excess pressure's mean over the grid, by cell volume, Pa: what a
  /// periodic cell's total-stress servo adds to the contacts' stress.
  [[nodiscard]] double mean_pressure() const override;
  /// With hold_forces: true if `force` is what the last particle_forces
  /// call wrote, for as many particles under the same gravity, and no fluid
  /// step (or new pressure) has come since.
  [[nodiscard]] bool forces_current(const ParticleData<D>& particles, const Vec<D>& gravity,
                                    const std::vector<Vec<D>>& force) const override {
    return hold_forces && held_.force == &force && held_.count == particles.size() &&
           held_.gravity == gravity;
  }

  /// The fluid's state for a checkpoint: the settings stages change, every
  /// cell and face field the next update or force evaluation reads, the
  /// balance and the counters. `held_output` is the vector the simulation
  /// gets its field forces in (Simulation::field_forces()): with
  /// hold_forces, whether the forces it holds are current is stored, not
  /// the address. Load it into a fluid built from the same scene and
  /// initialized.
  /// The items' count, which must match the scene's on loading, then each
  /// item's checkpoint; `what` names them in the message.
  template <class Archive, class Item>
  static void checkpoint_each(Archive& ar, std::vector<Item>& items, const char* what) {
    std::size_t count = items.size();
    ar(count);
    if constexpr (Archive::loading) {
      if (count != items.size())
        throw std::runtime_error(std::string("checkpoint: the pore fluid has another number of ") + what);
    }
    for (auto& item : items) ar(item);
  }
  template <class Archive>
  void checkpoint(Archive& ar, const std::vector<Vec<D>>* held_output) {
    ar(steps_per_update, hold_forces, sides, permeability_frozen, drained, pressure_, pressure_old_,
       pressure_older_, porosity_, solid_, solid_old_, wall_solid_, wall_solid_old_, porosity_used_,
       solid_flux_, solid_velocity_, kappa_, cell_drag_, blend_atan_, n_power_, face_lambda_, carried_,
       face_gq_, solid_face_flux_, face_open_, face_covered_, side_inflow_, last_solve_, last_, total_,
       updates_, time_, initialized_, wrap_lambda_, wrap_carried_, boundary_carried_, grid.origin,
       grid.spacing, volume_old_);
    if constexpr (Archive::loading) {
      if (!grid.any_graded()) take_spacing();
    }
    checkpoint_each(ar, patches, "boundary patches");
    ar(patch_inflow_);
    checkpoint_each(ar, sources, "sources");
    ar(source_inflow_, drain_open_);
    bool held = held_.force != nullptr;
    if constexpr (!Archive::loading) {
      if (held && held_.force != held_output)
        throw std::logic_error("checkpoint: the held fluid forces belong to another vector");
    }
    ar(held, held_.count, held_.gravity);
    if constexpr (Archive::loading) held_.force = held ? held_output : nullptr;
  }

  /// Critical step of the coupled system: the DEM step with the undrained
  /// stiffness K_f/n of the pore fluid added (none with uniform_pressure),
  /// and the drag relaxation time.
  [[nodiscard]] double critical_time_step(const ParticleData<D>& particles, double dem_step) const {
    return critical_time_step(particles, dem_step, !uniform_pressure);
  }
  /// The same with the water's stiffness counted or not, whatever
  /// uniform_pressure says: what the step would be were the one sealed
  /// cell drained.
  [[nodiscard]] double critical_time_step(const ParticleData<D>& particles, double dem_step,
                                          bool water_stiffness) const;

  /// Whether the grid is one cell with no side or patch drained now: its
  /// pressure is uniform, every face's gradient zero or a flux's own.
  [[nodiscard]] bool sealed_single_cell() const {
    if (grid.size() != 1) return false;
    for (int k = 0; k < 2 * D; ++k)
      if (!grid.periodic[k / 2] && sides[k].type == FluidBoundaryType::drained) return false;
    for (const auto& patch : patches)
      if (patch.condition.type == FluidBoundaryType::drained) return false;
    return true;
  }

  // Fields, one value per cell.
  [[nodiscard]] const std::vector<double>& pressure() const { return pressure_; }       ///< Pa (excess)
  [[nodiscard]] const std::vector<double>& porosity() const { return porosity_; }       ///< -
  [[nodiscard]] const std::vector<double>& solid_volume() const { return solid_; }      ///< m^3, grains
  [[nodiscard]] const std::vector<double>& wall_volume() const { return wall_solid_; }  ///< m^3, solid walls
  [[nodiscard]] const std::vector<Vec<D>>& permeability_field() const { return kappa_; }       ///< m^2
  [[nodiscard]] const std::vector<Vec<D>>& solid_velocity() const { return solid_velocity_; }  ///< m/s
  /// Darcy velocity at each cell centre (mean of the two faces), m/s.
  [[nodiscard]] std::vector<Vec<D>> darcy_velocity() const;
  /// Excess pressure at a point, interpolated between cell centres, Pa.
  [[nodiscard]] double pressure_at(const Vec<D>& x) const;
  /// Pressure gradient at a point (staggered interpolation), Pa/m.
  [[nodiscard]] Vec<D> gradient_at(const Vec<D>& x) const;
  /// Grains whose centres are outside the grid: the fluid exerts no force
  /// (and no buoyancy) on them, as on grains above the water.
  [[nodiscard]] std::size_t grains_outside(const ParticleData<D>& particles) const;
  /// Of those, the grains below water_level: in free water.
  [[nodiscard]] std::size_t grains_in_free_water(const ParticleData<D>& particles) const;
  /// The excess pore pressure's thrust on a wall that displaces the fluid
  /// (one of solid_walls), -(integral of u n dA) over the part of its
  /// surface in the grid, N (2D: per metre). A box: by the divergence
  /// theorem, -(sum over cells of the box's volume there times the cell's
  /// gradient, the mean of its two faces') plus, where the box crosses a
  /// side of the grid, its section there times the side's pressure along
  /// the side's outward normal, and where it crosses a barrier, its section
  /// times the jump. A plane normal to a grid axis: the same for the
  /// half-space behind it (behind_plane), along its normal; on or beyond
  /// the grid's side it faces, it takes that side's pressure. Across its
  /// normal, only as far as the other planes leave water (planes_wet_region):
  /// a platen between others takes the water's thrust over the section
  /// they bound. Exact for a pressure linear in space. An impermeable wall (impermeable_walls)
  /// instead takes the pressure on each of its faces from the cells on the
  /// wet side (sealed_box_thrust). The hydrostatic part (buoyancy) is not
  /// in it: u is the excess pressure.
  [[nodiscard]] Vec<D> wall_thrust(const std::vector<Wall<D>>& walls, std::size_t w) const;
  /// The excess pore pressure's thrust on barrier b (an impermeable
  /// plate's), N (2D: per metre): over the faces it closes, the pressure
  /// of the cell below minus that of the cell above times the face's
  /// area, along its axis.
  [[nodiscard]] Vec<D> barrier_thrust(std::size_t barrier) const;
  /// Flow into the grid through one side in the last step, m^3/s.
  [[nodiscard]] double side_inflow(int side) const { return side_inflow_[side]; }
  /// Flow into the grid through one patch (index in `patches`) in the last
  /// step, m^3/s; part of its side's side_inflow.
  [[nodiscard]] double patch_inflow(std::size_t patch) const { return patch_inflow_.at(patch); }
  /// What source i gave in the last fluid step, m^3/s (2D: per metre).
  [[nodiscard]] double source_inflow(std::size_t source) const { return source_inflow_.at(source); }
  /// Whether source i, a drain, stood open in the last fluid step.
  [[nodiscard]] bool drain_open(std::size_t source) const { return drain_open_.at(source) != 0; }
  /// The cell that source i feeds.
  [[nodiscard]] std::size_t source_cell(std::size_t source) const { return source_cells_.at(source); }
  /// Source i's well index now, m^3/(s Pa) (2D: per metre), from its
  /// radius and its cell's widths and permeability (fluid/well_index.hpp);
  /// a screened well's, its cells' summed; 0 for a source without a radius.
  [[nodiscard]] double well_index(std::size_t source) const;
  /// A screened well's cells, from the bottom up, each with its well index
  /// now, m^3/(s Pa) (screen_well_index: Peaceman's across the well times
  /// the screen's length in the cell); what cell c takes from the bore is
  /// its index times (well_pressure - its pressure). Empty for a point
  /// source.
  [[nodiscard]] std::vector<std::pair<std::size_t, double>> screen_well_indices(std::size_t source) const;
  /// What each cell of a screened well took from its bore in the last
  /// fluid step, m^3/s, in the order of screen_well_indices: its index
  /// times (well_pressure - its pressure). They add up to source_inflow.
  [[nodiscard]] std::vector<double> screen_inflows(std::size_t source) const;
  /// Source i's cell's equivalent radius, m (fluid/well_index.hpp): from
  /// its widths and the permeability's proportions along the axes; a
  /// screened well's, across it (Peaceman's 2D, from the widths and
  /// permeabilities along x and y).
  [[nodiscard]] double equivalent_radius(std::size_t source) const;
  /// The pressure at source i, Pa: with a radius, at its bore, its cell's
  /// plus its last inflow over its well index (a held pressure's, that
  /// pressure; a screened well's, (inflow + sum of WI_c u_c) / sum of WI_c
  /// over its cells); without, its cell's.
  [[nodiscard]] double well_pressure(std::size_t source) const;
  /// The excess pressure on a side of the grid (`side` 0 .. 2D-1, as
  /// side_inflow) or on a patch (`side` = 2D + its index in `patches`),
  /// Pa: the mean over its faces, weighted by their areas, of each face's
  /// pressure, its cell's carried to the face by the face's gradient (on a
  /// drained face the imposed value; on a flux face the cell's plus the
  /// drop of the inflow through the half cell; on a no-flow face the
  /// cell's). What a piezometer at an inlet reads: the pressure drop of a
  /// permeameter or a fluidization curve. NaN for a side without faces
  /// (a periodic axis).
  [[nodiscard]] double side_pressure(int side) const;
  /// Boundary faces of a patch (as found by initialize()).
  [[nodiscard]] std::size_t patch_faces(std::size_t patch) const { return patch_faces_.at(patch); }
  /// Area of a patch's faces, m^2 (2D: per metre).
  [[nodiscard]] double patch_area(std::size_t patch) const { return patch_area_.at(patch); }
  /// Interior faces a barrier closes (as found by initialize()).
  [[nodiscard]] std::size_t barrier_faces(std::size_t barrier) const { return barrier_faces_.at(barrier); }

  [[nodiscard]] const FluidBalance& last_balance() const { return last_; }
  [[nodiscard]] const FluidBalance& total_balance() const { return total_; }
  [[nodiscard]] const SolveStats& last_solve() const { return last_solve_; }
  [[nodiscard]] const FluidUpdateTimes& last_times() const { return last_times_; }
  /// Wall-clock seconds of all particle_forces calls so far.
  [[nodiscard]] double force_time() const { return force_seconds_; }
  [[nodiscard]] std::uint64_t updates() const { return updates_; }
  [[nodiscard]] const PressureSolver& solver() const { return solver_; }

  /// Solid volume of every particle in every cell it overlaps: calls
  /// f(cell, particle, volume); with `sections`, also
  /// section(axis, face index (FluidGrid::face_index), particle, area) for
  /// its cross-section on every face it crosses. Exposed for tests and
  /// diagnostics.
  template <class F, class G>
  void for_each_overlap(const ParticleData<D>& particles, F&& f, G&& section, bool sections) const {
    for_each_overlap(particles, 0, particles.size(), f, section, sections);
  }
  /// The same for the particles [begin, end).
  template <class F, class G>
  void for_each_overlap(const ParticleData<D>& particles, std::size_t begin, std::size_t end, F&& f,
                        G&& section, bool sections) const;
  template <class F>
  void for_each_overlap(const ParticleData<D>& particles, F&& f) const {
    for_each_overlap(
        particles, f, [](int, std::size_t, std::size_t, double) {}, false);
  }

 private:
  /// Whether a grain's centre at x is in the grid (as the forces count it).
  [[nodiscard]] bool in_grid(const Vec<D>& x) const;
  void compute_solid(const ParticleData<D>& particles);
  /// wall_thrust of a solid box (a box wall's, or the part behind a plane).
  [[nodiscard]] Vec<D> box_thrust(const SolidBox<D>& box) const;
  /// wall_thrust of an impermeable box along the grid's axes: over each of
  /// its faces in the grid, the area in each cell on its wet side times
  /// that cell's pressure (no water crosses the face, so the pressure is
  /// flat towards it: the face's to second order in the cell's width).
  [[nodiscard]] Vec<D> sealed_box_thrust(const SolidBox<D>& box) const;
  /// The solid of a wall that displaces the fluid, as a box: its own, or
  /// for a plane behind_plane, its face kept 1e-5 of a cell inside the
  /// grid. None if it misses the grid.
  [[nodiscard]] std::optional<SolidBox<D>> displaced_box(const Wall<D>& wall) const;
  /// The region the planes among solid_walls (but `skip`, an index into
  /// `walls`) leave to the water, an axis-aligned box [lo, hi]: along each
  /// axis between the faces of their solids (displaced_box), +-infinity
  /// where no plane bounds it. Their solids' union is all else.
  [[nodiscard]] std::pair<Vec<D>, Vec<D>> planes_wet_region(const std::vector<Wall<D>>& walls,
                                                            std::size_t skip = std::size_t(-1)) const;
  /// face_open_ from the impermeable_walls among `walls` (empty if none).
  void compute_open_faces(const std::vector<Wall<D>>& walls);
  /// Holds `pressure` in source `source`'s cell in this step's system
  /// (held_sources_).
  void hold_pressure(std::size_t source, double pressure);
  /// wall_solid_ from the solid_walls among `walls`.
  void compute_wall_solid(const std::vector<Wall<D>>& walls);
  void compute_cell_properties();
  void build_pattern();
  /// Each boundary face's patch (BoundaryFace::patch), and the patches'
  /// face counts.
  void assign_patches();
  /// The interior faces the barriers close (blocked_), and their counts.
  void assign_barriers();
  /// Zero on the blocked faces: conductances, carried fluid, or the face
  /// fields.
  void close_barrier_faces(std::array<std::vector<double>, D>& per_cell_below);
  void close_barrier_fields();
  void compute_face_fields(double time);
  /// The fluid step of a drained grid: the pressure back to zero, the
  /// pore volume's change and the water released as inflow.
  void drain_freely(double time);
  /// The last fluid step's balance into the run's, and the step counted.
  void close_step(const FluidBalance& b, double time);
  [[nodiscard]] double side_lambda(int axis, std::size_t cell) const;
  /// grad u and the Darcy flux at x together (the per-grain hot path):
  /// for the component along an axis, linear between the two faces of the
  /// cell holding x along that axis, and between cell centres along the
  /// others (held beyond the outer ones), as on a staggered (MAC) grid.
  /// Where a point lies for the staggered interpolation, per axis: the cell
  /// holding it and its fraction across that cell (for the axis's own
  /// faces), and the lower of the two cell centres around it and the
  /// fraction between them (for the other axes).
  struct Stencil {
    std::array<int, D> face_cell{};
    std::array<double, D> face_frac{};
    std::array<int, D> centre_cell{};
    std::array<double, D> centre_frac{};
  };
  /// The Stencil's values along axis k at s (cell units), without branches
  /// (inline: called in a loop the compiler vectorises).
  void stencil_axis(int k, double s, int& face_cell, double& face_frac, int& centre_cell,
                    double& centre_frac) const {
    // Beyond the outer centres the fraction is clamped to 0 or 1, which
    // holds the outer value; with one cell along an axis there is no pair.
    const int last = grid.cells[k] - 1;
    s = s == s ? s : 0.0;  // a NaN position (never inside the grid) reads cell 0, not a NaN index
    const double fb = std::clamp(std::floor(s), 0.0, static_cast<double>(last));
    face_cell = static_cast<int>(fb);
    face_frac = std::clamp(s - fb, 0.0, 1.0);
    const double t = s - 0.5;
    const double cb = std::clamp(std::floor(t), 0.0, static_cast<double>(std::max(last - 1, 0)));
    centre_cell = static_cast<int>(cb);
    centre_frac = last > 0 ? std::clamp(t - cb, 0.0, 1.0) : 0.0;
  }
  /// stencil_axis on any axis: on a graded one, the fraction between the
  /// two cell centres is taken along x (linear in x between them), not in
  /// cell units, whose scale changes at the face between them.
  void stencil_axis_any(int k, double s, int& face_cell, double& face_frac, int& centre_cell,
                        double& centre_frac) const {
    stencil_axis(k, s, face_cell, face_frac, centre_cell, centre_frac);
    if (!grid.graded(k) || grid.cells[k] < 2 || !(s == s)) return;
    // x back from its cell units (FluidGrid::cell_units).
    const int i = std::clamp(static_cast<int>(std::floor(std::clamp(s, -1.0, grid.cells[k] + 1.0))), 0,
                             grid.cells[k] - 1);
    centre_frac = graded_centre_frac(k, grid.face_at(k, i) + (s - i) * grid.width(k, i), centre_cell);
  }
  /// On graded axis k, the fraction of x from the centre of layer
  /// `centre_cell` to the next one's, clamped to [0, 1] (build_geometry's
  /// layer centres and inverse gaps).
  [[nodiscard]] double graded_centre_frac(int k, double x, int centre_cell) const {
    const auto c = static_cast<std::size_t>(centre_cell);
    return std::clamp((x - layer_centre_[k][c]) * layer_inv_gap_[k][c], 0.0, 1.0);
  }
  /// stencil_axis_any for coordinate x on graded axis k, from the layers'
  /// centres, inverse widths and inverse gaps between centres
  /// (build_geometry); returns x in cell units (FluidGrid::cell_units).
  double stencil_graded(int k, double x, int& face_cell, double& face_frac, int& centre_cell,
                        double& centre_frac) const {
    const int last = grid.cells[k] - 1;
    const auto i = static_cast<std::size_t>(std::clamp(grid.cell_along(k, x), 0, last));
    const double s = static_cast<double>(i) + (x - grid.faces[k][i]) * layer_inv_width_[k][i];
    stencil_axis(k, s, face_cell, face_frac, centre_cell, centre_frac);
    if (last > 0 && s == s) centre_frac = graded_centre_frac(k, x, centre_cell);
    return s;
  }
  /// Index in the face arrays of axis A of the stencil's lower corner for
  /// component A: the face below the holding cell along A, the lower cell
  /// centre along the others.
  template <int A>
  [[nodiscard]] std::size_t stencil_base(const std::array<int, D>& face_cell,
                                         const std::array<int, D>& centre_cell) const {
    std::size_t base = 0;
    for (int k = 0; k < D; ++k)
      base += static_cast<std::size_t>(k == A ? face_cell[k] : centre_cell[k]) * face_stride_[A][k];
    return base;
  }
  /// (grad u, Darcy flux) of component A, multilinear between the 2^D
  /// faces of axis A from `base` (stencil_base) with fractions fr along
  /// each axis, the pair as one vector (GCC/Clang vector extension): one
  /// load and one multiply-add per lerp for both.
  template <int A>
  [[nodiscard, gnu::always_inline]] std::array<double, 2> interpolate_component(
      std::size_t base, const std::array<double, D>& fr) const {
    using Pair = double __attribute__((vector_size(16)));
    const std::array<double, 2>* g = face_gq_[A].data() + base;
    auto load = [&](std::size_t at) {
      Pair p;
      std::memcpy(&p, g[at].data(), sizeof p);
      return p;
    };
    auto lerp = [](Pair lo, Pair hi, double t) -> Pair { return lo + t * (hi - lo); };
    const auto& step = corner_step_[A];
    const std::size_t s0 = step[0];
    const std::size_t s1 = step[1];
    if (s0 == 1) {
      // The two corners along x are side by side in memory (always, unless
      // the grid is one cell wide along x): one 4-lane load holds
      // (grad, flux) of both, the lerps along y (and z) act on both at
      // once, and the one along x comes last.
      auto load_both = [&](std::size_t at) {
        Lanes p;
        std::memcpy(&p, g[at].data(), sizeof p);
        return p;
      };
      auto lerp4 = [](Lanes lo, Lanes hi, double t) -> Lanes { return lo + t * (hi - lo); };
      Lanes z = lerp4(load_both(0), load_both(s1), fr[1]);
      if constexpr (D == 3) {
        const std::size_t s2 = step[2];
        z = lerp4(z, lerp4(load_both(s2), load_both(s2 + s1), fr[1]), fr[2]);
      }
      return {z[0] + fr[0] * (z[2] - z[0]), z[1] + fr[0] * (z[3] - z[1])};
    }
    Pair v{};
    if constexpr (D == 2) {
      v = lerp(lerp(load(0), load(s0), fr[0]), lerp(load(s1), load(s1 + s0), fr[0]), fr[1]);
    } else {
      const std::size_t s2 = step[2];
      const Pair v00 = lerp(load(0), load(s0), fr[0]);
      const Pair v10 = lerp(load(s1), load(s1 + s0), fr[0]);
      const Pair v01 = lerp(load(s2), load(s2 + s0), fr[0]);
      const Pair v11 = lerp(load(s2 + s1), load(s2 + s1 + s0), fr[0]);
      v = lerp(lerp(v00, v10, fr[1]), lerp(v01, v11, fr[1]), fr[2]);
    }
    return {v[0], v[1]};
  }
  /// s is x in cell units, (x - origin) / spacing.
  void interpolate(const std::array<double, D>& s, std::array<double, D>& grad,
                   std::array<double, D>& flux) const;
  /// The same interpolation corner by corner, where the pair of cell
  /// centres around s along a periodic axis may be the grid's last layer
  /// and its first (s wrapped into [0, cells) along periodic axes first):
  /// for grains within half a cell of a periodic end.
  void interpolate_wrapped(std::array<double, D> s, std::array<double, D>& grad,
                           std::array<double, D>& flux) const;
  /// The two cell layers along axis k whose centres the stencil
  /// interpolates between at s (cell units, wrapped), and the fraction
  /// towards the second: across a periodic end, the last layer and the first.
  void centre_pair(int k, double s, std::array<int, 2>& layer, double& frac) const;
  /// s along periodic axes wrapped into [0, cells).
  [[nodiscard]] std::array<double, D> wrap_cell_units(std::array<double, D> s) const {
    for (int k = 0; k < D; ++k) {
      if (!grid.periodic[k]) continue;
      const double n = grid.cells[k];
      s[k] -= n * std::floor(s[k] / n);
      if (s[k] >= n) s[k] -= n;  // rounding
    }
    return s;
  }
  /// Whether the staggered stencil at s (wrapped) reaches across a periodic
  /// end: within half a cell of it.
  [[nodiscard]] bool near_periodic_end(const std::array<double, D>& s) const {
    bool near = false;
    for (int k = 0; k < D; ++k)
      near = near || (grid.periodic[k] && (s[k] < 0.5 || s[k] > grid.cells[k] - 0.5));
    return near;
  }
  void interpolate(const Stencil& stencil, std::array<double, D>& grad, std::array<double, D>& flux) const;
  /// x in cell units along each axis (FluidGrid::cell_units).
  [[nodiscard]] std::array<double, D> cell_units(const Vec<D>& x) const {
    std::array<double, D> s{};
    for (int k = 0; k < D; ++k)
      s[k] = grid.graded(k) ? grid.cell_units(k, x[k]) : (x[k] - grid.origin[k]) * inv_spacing_[k];
    return s;
  }
  /// Volume of cell c, m^3.
  [[nodiscard]] double volume_of(std::size_t c) const {
    return volume_.empty() ? uniform_volume_ : volume_[c];
  }
  /// Storage n V / K_f of cell c, m^3/Pa (porosity floored at 1e-3).
  [[nodiscard]] double storage_of(std::size_t c) const {
    return std::max(porosity_[c], 1e-3) * volume_of(c) / fluid.bulk_modulus;
  }
  /// The geometry of a grid with graded axes (empty without): per cell its
  /// volume, and per interior face, [axis][a] for the face between a and a
  /// + stride(axis), its area, 1 / the distance between the two centres
  /// and the weight of cell a in the harmonic mean of the permeabilities,
  /// h_a / (h_a + h_b).
  void build_geometry();
  /// The uniform grid's spacing into what follows from it: the inverse
  /// spacing, the cells' volume, the periodic ends' face areas.
  void take_spacing();

  /// An interior face in the stored matrix (Cholesky solver only; the hot
  /// loops go over FluidGrid::face_run).
  struct Face {
    std::uint32_t a, b;  ///< cells below and above along `axis`
    int axis;
    std::size_t pos_ab, pos_ba;  ///< positions in the matrix values
  };
  struct BoundaryFace {
    std::uint32_t cell;
    int side;
    std::size_t index;  ///< in the face arrays of the side's axis
    int patch = -1;     ///< in `patches`; -1: the side's own condition
    double area = 0.0;  ///< m^2
    double half = 0.0;  ///< half the cell's width along the side's axis, m
  };
  [[nodiscard]] const FluidBoundary& condition_of(const BoundaryFace& bf) const {
    return bf.patch >= 0 ? patches[static_cast<std::size_t>(bf.patch)].condition : sides[bf.side];
  }
  /// The open part of a boundary face (1 without impermeable walls).
  [[nodiscard]] double open_of(const BoundaryFace& bf) const {
    return face_open_[bf.side / 2].empty() ? 1.0 : face_open_[bf.side / 2][bf.index];
  }

  /// Sums over one block of grains (compute_solid): per cell, the solid
  /// volume and the solid volume flux side by side (one vector add per
  /// grain and cell), and the solid flux through each face.
  /// The sums are kept zero outside the range of cells (faces) that the
  /// block touched, and only that range is added and cleared: with the
  /// grains in spatial order (Simulation sorts them), a block covers a slab
  /// of the grid, not all of it.
  struct SolidSums {
    std::vector<Lanes> cell;  ///< (V_s, V_s v_x, V_s v_y[, V_s v_z])
    std::array<std::vector<double>, D> face_flux;
    std::size_t cell_lo = 0, cell_hi = 0;  ///< touched: [lo, hi)
    std::array<std::size_t, D> face_lo{}, face_hi{};
  };
  std::vector<SolidSums> block_solid_;
  std::vector<Lanes> block_total_;  ///< the blocks' cell sums added
  std::vector<double> pressure_, pressure_old_, porosity_, solid_, solid_old_;
  std::vector<double> wall_solid_, wall_solid_old_;  ///< volume of the solid walls per cell
  std::vector<double> pressure_older_;               ///< the pressure one fluid step before pressure_old_
  std::vector<double> porosity_used_;                ///< porosity clamped to the permeability's [min, max]
  std::vector<Vec<D>> solid_flux_, solid_velocity_, kappa_;
  /// Per cell, what the force on a grain needs, in one cache line: the mean
  /// solid velocity, 1/n and, at the clamped porosity, the drag per unit
  /// grain volume and unit slip, beta/(1-n):
  ///   Ergun/Wen-Yu: law = (viscous, inertial, wen_yu, re_factor) and
  ///     beta/(1-n) = viscous/d^2 + inertial |slip|/d + wen_yu C_dRe(re)/d^2,
  ///     re = re_factor d |slip|;
  ///   Darcy: law = (beta/(1-n) along each axis).
  struct alignas(64) CellDrag {
    std::array<double, D> solid_velocity{};
    double inv_n = 1.0;
    std::array<double, 4> law{};
  };
  std::vector<CellDrag> cell_drag_;
  std::vector<double> blend_atan_, n_power_;  ///< per cell, for the Ergun/Wen-Yu coefficients
  /// kappa/mu of each interior face, m^2/(Pa s): [axis][a] for the face
  /// between cell a and a + stride(axis) (as GridOperator::upper).
  std::array<std::vector<double>, D> face_lambda_;
  /// Pore fluid carried by the skeleton through each interior face in a
  /// fluid step, m^3, from a to a + stride(axis): [axis][a].
  std::array<std::vector<double>, D> carried_;
  std::array<std::vector<std::array<double, 2>>, D>
      face_gq_;                          ///< (grad, flux) side by side: one load per corner
  Vec<D> inv_spacing_ = Vec<D>::Ones();  ///< NaN along graded axes
  double uniform_volume_ = 1.0;          ///< the cells' volume without graded axes
  /// The cells' volume at the last fluid step (without graded axes): it
  /// changes while the grid follows a deforming cell (follow_cell).
  double volume_old_ = 1.0;
  std::vector<double> volume_;  ///< per cell, with graded axes (build_geometry)
  std::array<std::vector<double>, D> face_area_, face_inv_distance_, face_weight_;  ///< (build_geometry)
  /// Per graded axis, per layer of cells: the centre's coordinate, 1/width
  /// and 1/(distance to the next centre) (build_geometry, stencil_graded).
  std::array<std::vector<double>, D> layer_centre_, layer_inv_width_, layer_inv_gap_;
  std::array<std::vector<double>, D> solid_face_flux_;  ///< m^3/s of solid through each face
  /// Per face (FluidGrid::face_index), the part of its area open to flow,
  /// in [0, 1]: 1 - the part impermeable walls covered at both the last
  /// fluid step and this one (face_covered_); empty without impermeable
  /// walls.
  std::array<std::vector<double>, D> face_open_;
  std::array<std::vector<double>, D> face_covered_;  ///< per face, the part covered now
  std::vector<Face> faces_;
  /// A face across a periodic end of the grid: between the cell `low` on
  /// the last layer along `axis` and `high` on the first (flow from low to
  /// high is along +axis); its fields are at both face_first (face 0 along
  /// the axis) and face_last (face `cells`).
  struct WrapFace {
    std::uint32_t low, high;
    int axis;
    std::size_t face_first, face_last;
    std::size_t pos_lh = 0, pos_hl = 0;  ///< in the stored matrix (Cholesky)
    bool shared = false;                 ///< two cells along the axis: also a stencil face
    double area = 0.0;                   ///< m^2
  };
  std::vector<WrapFace> wrap_faces_;
  /// The open part of a wrap face: the smaller of its two ends' (a wall
  /// may lie against either end of the period).
  [[nodiscard]] double wrap_open(const WrapFace& f) const {
    if (face_open_[f.axis].empty()) return 1.0;
    return std::min(face_open_[f.axis][f.face_first], face_open_[f.axis][f.face_last]);
  }
  std::vector<double> wrap_lambda_;   ///< kappa/mu of each wrap face, m^2/(Pa s)
  std::vector<double> wrap_carried_;  ///< fluid carried across each, from low to high, m^3
  std::vector<BoundaryFace> boundary_faces_;
  /// Per boundary face, the pore fluid the skeleton carried in across it at
  /// the last fluid step (a drained side's; 0 elsewhere), as an inflow over
  /// the whole face, m/s.
  std::vector<double> boundary_carried_;
  std::vector<std::size_t> diag_pos_;
  std::array<std::array<std::size_t, D>, D> face_stride_{};  ///< [axis][j]: index step along j
  std::array<std::array<std::size_t, D>, D> corner_step_{};  ///< [component][j]: between stencil corners
  std::array<double, 2 * D> side_inflow_{};
  std::vector<double> patch_inflow_;       ///< m^3/s, per patch
  std::vector<double> source_inflow_;      ///< m^3/s, per source, in the last fluid step
  std::vector<std::size_t> source_cells_;  ///< the cell each source feeds
  /// Per source, a screened well's cells (source_cells), empty for a
  /// point source.
  std::vector<std::vector<SourceCell>> screens_;
  /// Solves for the pressures at the bores of the screened wells with a
  /// given inflow, (source, m^3/s) each, which the last solve left at
  /// zero, and adds what they give to the solution (superposition: see
  /// update()).
  void superpose_given_screens(const std::vector<std::pair<std::size_t, double>>& wells, double dt);
  /// Per source, whether a drain (FluidSource::drain) stands open: as the
  /// last fluid step left it (shut at the start).
  std::vector<int> drain_open_;
  /// A source that holds a pressure, in this fluid step: its index, the
  /// pressure, its cell's diagonal and right-hand side, and the couplings
  /// to its neighbours (cell, conductance) taken out of the system.
  struct HeldSource {
    std::size_t source = 0;
    double pressure = 0.0;
    double diagonal = 0.0;
    double rhs = 0.0;
    std::vector<std::pair<std::size_t, double>> couplings;
  };
  std::vector<HeldSource> held_sources_;
  /// A pass over the sources in a fluid step (pore_fluid_sources.cpp):
  /// the wells held at their bores (source, its well index; 0 for a
  /// screened one) and the screened wells given an inflow (source, m^3/s).
  struct SourcePass {
    std::vector<std::pair<std::size_t, double>> bore_held;
    std::vector<std::pair<std::size_t, double>> given_screens;
  };
  /// Puts the sources, as the drains stand, into the system's diagonal and
  /// right-hand side (and takes held cells out of it, hold_pressure).
  SourcePass assemble_sources(double dt, double time);
  /// After the solve: what each source gave (source_inflow_).
  void take_source_inflows(const SourcePass& placed, double dt, double time);
  /// Opens the drains the water stands above and shuts those that gave
  /// water; whether any changed.
  bool settle_drains(double time);
  std::vector<std::size_t> patch_faces_;  ///< boundary faces per patch
  std::vector<double> patch_area_;        ///< their area per patch, m^2
  /// An interior face a barrier closes: the cell below it along `axis`
  /// (index into face_lambda_ and carried_) and its index in face_gq_.
  struct BlockedFace {
    int axis;
    std::size_t cell_below;
    std::size_t face;
    std::size_t barrier;  ///< in `barriers`
  };
  std::vector<BlockedFace> blocked_;
  std::vector<std::size_t> barrier_faces_;  ///< faces per barrier
  PressureSolver::Matrix matrix_;           ///< the stored matrix, for the Cholesky solver
  GridOperator operator_;                   ///< the same as a stencil
  Eigen::VectorXd rhs_, solution_;
  PressureSolver solver_;
  SolveStats last_solve_;
  FluidUpdateTimes last_times_;
  mutable double force_seconds_ = 0.0;  ///< timing only: not part of the state
  /// What the last particle_forces call wrote (hold_forces): the output
  /// vector (null: none since the last fluid step), for how many particles,
  /// under which gravity.
  struct HeldForces {
    const std::vector<Vec<D>>* force = nullptr;
    std::size_t count = 0;
    Vec<D> gravity = Vec<D>::Zero();
  };
  mutable HeldForces held_;
  /// With drag_cells = overlaps, per grain, the means over the cells it
  /// overlaps weighted by the overlap volumes (spread_drag): the cells'
  /// drag coefficients (CellDrag::law), their mean excess-pressure gradient
  /// -mu qbar / kappa (qbar the mean of a cell's two face fluxes along each
  /// axis: the gradient of the half-cell reconstruction that the two-point
  /// fluxes imply, so summed over the cells it telescopes to the pressure
  /// on the grid's faces), and their fluid velocity v_s + qbar / n, weighted
  /// by the volumes times the coefficient of that axis (Darcy: then law x
  /// (fluid_velocity - v) is the weighted sum of the cells' drags) or by
  /// the volumes (Ergun). Scratch for particle_forces.
  struct GrainDrag {
    std::array<double, 4> law{};
    std::array<double, D> grad{};
    std::array<double, D> fluid_velocity{};
    std::array<double, D> weight{};  ///< the fluid velocity's weights, summed
    double volume = 0.0;             ///< the grain's volume in the grid
  };
  mutable std::vector<GrainDrag> grain_drag_;
  void spread_drag(const ParticleData<D>& p) const;
  FluidBalance last_, total_;
  std::uint64_t updates_ = 0;
  double time_ = 0.0;
  bool initialized_ = false;
};

}  // namespace darcydem

#include "darcydem/fluid/pore_fluid_overlap.hpp"
