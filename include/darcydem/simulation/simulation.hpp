#pragma once
// The DEM simulation: owns the particles, materials, walls and neighbour
// lists, and advances them by velocity Verlet. One step:
//   1. half kick (v += a dt/2, with damping) and drift (x += v dt)
//   2. walls move (servo walls update their speed from the last load)
//   3. neighbour lists rebuilt if anything moved more than half the skin
//   4. contact forces (one pass over pairs, then each particle gathers its
//      share in a fixed order), gravity and external forces
//   5. half kick with the new forces
#include <array>
#include <cstdint>
#include <vector>

#include "darcydem/contact/contact_laws.hpp"
#include "darcydem/contact/material.hpp"
#include "darcydem/core/cell_motion.hpp"
#include "darcydem/core/periodic_cell.hpp"
#include "darcydem/core/vec.hpp"
#include "darcydem/neighbour/verlet_list.hpp"
#include "darcydem/particles/clumps.hpp"
#include "darcydem/particles/particle_data.hpp"
#include "darcydem/simulation/energy_budget.hpp"
#include "darcydem/simulation/force_field.hpp"
#include "darcydem/walls/wall.hpp"

namespace darcydem {

struct DampingSettings {
  double local = 0.0;    ///< Cundall's non-viscous coefficient alpha, 0 <= alpha < 1
  double viscous = 0.0;  ///< global viscous damping rate beta, 1/s (F = -beta m v)
};

/// A contact of the last force evaluation (Simulation::contact_forces).
template <int D>
struct ContactRecord {
  std::size_t first = 0;   ///< particle index
  std::size_t second = 0;  ///< the other particle's index (first's own for a wall contact)
  int wall = -1;           ///< the wall's index, or -1 between two particles
  Vec<D> branch;  ///< m: from first's centre to the other's (nearest image) or to the point on the wall
  Vec<D> normal;  ///< unit, from first towards the contact
  double overlap = 0.0;     ///< m
  double arm_first = 0.0;   ///< m: from first's centre to the contact point, along normal
  double arm_second = 0.0;  ///< m: from the other's centre to it, against normal (0 for a wall)
  Vec<D> force;             ///< N, on first (on the other: -force)
  bool bonded = false;      ///< held by a contact bond (may pull: the grains may be apart)
  /// A bond with a moment: the magnitudes of its bending and (3D) twisting
  /// moments, N m (2D: per metre); 0 otherwise.
  double bending_moment = 0.0;
  double twisting_moment = 0.0;
};

template <int D>
class Simulation {
 public:
  using Moment = Eigen::Matrix<double, D, D>;  ///< a tensor of force x length (N m) or stress (Pa)
  ParticleData<D> particles;
  /// Rigid clumps of particles (clumps.hpp): their members are particles
  /// moved by their clumps; pairs within a clump never touch. Not with
  /// periodic boundaries, a domain or the energy budget (yet).
  Clumps<D> clumps;
  std::vector<Material> materials;
  ContactTable contact_table;
  std::vector<Wall<D>> walls;
  Vec<D> gravity = Vec<D>::Zero();  ///< m/s^2
  DampingSettings damping;
  double skin = 0.0;  ///< Verlet skin, m (0: 0.2 x the smallest radius)
  /// Above this many particles, every list build reorders the particles along
  /// the linked cells (neighbours close in memory); particle indices then
  /// change, ParticleData::id does not.
  std::size_t sort_threshold = 4096;
  /// Sum the magnitudes of the contact forces in every force evaluation, for
  /// unbalanced_force_ratio(). One square root per contact: about 10 % of a
  /// step in a dense packing, so a run that never asks can turn it off.
  bool measure_contact_forces = true;
  /// When set, the last step of the next advance() (or the next step())
  /// stores each pair's force as it applies it, and clears the flag:
  /// contact_stress and contact_moments then use those forces (dashpots
  /// included) rather than recomputing them. The runner sets it before a
  /// step that ends at a stress probe or a fluid snapshot.
  bool record_contact_forces = false;
  double time_step = 0.0;  ///< s
  double time = 0.0;       ///< s
  std::uint64_t steps = 0;
  /// Periodic boundaries (none by default): contacts across them take the
  /// partner's nearest image, and every list build puts the particles back
  /// into the period. Each period must exceed shortest_period().
  PeriodicCell<D> periodic;
  /// The periodic cell's deformation (cell_motion.hpp): none by default.
  /// Active, it needs every axis periodic and no walls, clumps, inlets,
  /// domain or force field; the grains' velocities are then the
  /// fluctuations about the cell's homogeneous field, and the energy
  /// budget's boundary work holds the cell's work on the contacts.
  CellMotion<D> cell_motion;
  /// The domain (PFC's domain with the condition "destroy"): when set, the
  /// particles whose centres have left the box [domain_lower, domain_upper]
  /// are removed from the run at the next list build, which comes before
  /// any of them has moved half the skin past where it was at the last
  /// build. Along a periodic axis the box must hold the period.
  bool has_domain = false;
  Vec<D> domain_lower = Vec<D>::Zero();  ///< m
  Vec<D> domain_upper = Vec<D>::Zero();  ///< m
  /// What has left the domain so far: how many particles, their mass (kg;
  /// 2D: per metre of thickness; a fixed particle counts no mass) and volume
  /// (m^3; 2D: m^2 per metre).
  std::uint64_t removed_count = 0;
  double removed_mass = 0.0;
  double removed_volume = 0.0;
  /// What has been added during the run (add_particle, an inlet's grains):
  /// how many and their mass (kg; 2D: per metre).
  std::uint64_t inserted_count = 0;
  double inserted_mass = 0.0;
  /// Contact bonds that have broken so far (their tension or tangential
  /// force above the pair's strength; also a bond whose grain left the
  /// domain, or whose grains came more than the skin apart between two
  /// list builds).
  std::uint64_t broken_bonds = 0;
  /// Optional body-force field (the pore fluid), evaluated every step; not owned.
  ParticleForceField<D>* force_field = nullptr;
  /// Track the energy budget (energy_budget.hpp) from the next advance() on:
  /// each half kick then splits the change of kinetic energy into the works
  /// of gravity, contacts, the force field, damping and moving boundaries
  /// (in parallel over groups of four, their sums added in order). The
  /// trajectory is the same, bit for bit.
  bool track_energy = false;
  EnergyBudget energy;

  /// Chooses the contact law loop, builds the neighbour lists and evaluates
  /// the initial forces. Call after setting everything up and before step().
  void prepare();
  void step();
  /// `count` steps; the same as calling step() `count` times, bitwise, but
  /// each step's second half kick and the next one's first half kick and
  /// drift share one sweep over the particles. Nothing may look at or change
  /// the simulation in between, so callers advance to their next event.
  void advance(std::uint64_t count);

  /// Adds a free particle during a run (an inlet's grain), numbered after
  /// every particle created so far (ids are not reused after a removal);
  /// returns its index. Its force is its weight under the current gravity,
  /// the first evaluation's for a grain that touches nothing, so a free
  /// fall from it is velocity Verlet's exactly; the neighbour lists are
  /// rebuilt at the next step, the other particles keeping their contact
  /// histories. Call between steps (not inside advance()).
  std::size_t add_particle(const Vec<D>& x, double radius, std::uint16_t material, const Vec<D>& velocity);

  /// Adds a free clump during a run (an inlet's clump) as add_particle adds
  /// a grain: `shape` scaled by `size` (m), its centre of mass at x, turned
  /// by q, moving at `velocity` without spin; its members numbered after
  /// every particle created so far, each one's force its weight, so the
  /// clump's is its weight with no moment about its centre of mass. Counts
  /// its members in inserted_count and its mass in inserted_mass; returns
  /// its number. Call between steps.
  std::size_t add_clump(const ClumpShape<D>& shape, double size, const Vec<D>& x, const Orientation<D>& q,
                        std::uint16_t material, const Vec<D>& velocity);

  /// Bonds every pair of particles that touch or are less than `gap` apart
  /// (m, below the skin) whose materials' contact has a bond strength
  /// (PFC's `contact method bond gap`, YADE's setCohesionNow): from now on
  /// the pair also carries tension and its tangential spring has no
  /// Coulomb limit, until a force exceeds the bond's strength (evaluate_bond
  /// in contact_kernel.hpp). Returns how many pairs were bonded now. Call
  /// between steps, after prepare().
  std::size_t make_bonds(double gap = 0.0);
  /// Bonds intact now.
  [[nodiscard]] std::size_t bond_count() const;

  /// The skin prepare() uses: `skin`, or 0.2 x the smallest radius if it is 0.
  [[nodiscard]] double skin_or_default() const;
  /// The shortest period allowed: 2 (2 r_max + skin), so that a pair within
  /// the list's reach has one image within it (skin_or_default()).
  [[nodiscard]] double shortest_period() const;

  /// Critical time step: 1/omega of the fastest mode of one grain of the
  /// smallest mass on a linear contact against a wall: sqrt(m_min / k_n), or
  /// with friction sqrt(m_min / (k_t (1 + 1/alpha))) (the tangential spring
  /// turns the grain, I = alpha m r^2), the rolling spring's
  /// 2.25 mu_r^2 k_n / alpha added to that stiffness if any; the
  /// Rayleigh step pi r sqrt(rho/G) / (0.1631 nu + 0.8766) for Hertz.
  [[nodiscard]] double critical_time_step() const;

  // Diagnostics (deterministic whatever the thread count).
  [[nodiscard]] double kinetic_energy() const;        ///< J (translational + rotational)
  [[nodiscard]] double gravitational_energy() const;  ///< J, -sum m g.x
  [[nodiscard]] std::size_t contact_count() const;    ///< touching pairs incl. walls
  [[nodiscard]] double mean_coordination() const;     ///< contacts per particle
  [[nodiscard]] double max_overlap() const;           ///< m
  [[nodiscard]] double unbalanced_force_ratio()
      const;  ///< mean |F_i| / mean |F_contact| (needs measure_contact_forces)
  /// J stored in the contacts' springs: the normal spring (linear: 1/2 k_n d^2,
  /// in tension too for a bond; Hertz: 8/15 E* sqrt(R*) d^2.5) and, for the
  /// linear law, the tangential (1/2 k_t |xi|^2) and rolling (1/2 k_r |theta|^2)
  /// springs and a bond's bending and twisting springs.
  [[nodiscard]] double elastic_energy() const;
  /// J lost in the contacts since tracking began (EnergyBudget; 0 before).
  [[nodiscard]] double contact_dissipation() const;
  /// J of the kinetic energy's change since tracking began that the works
  /// do not explain (EnergyBudget::unaccounted; 0 before).
  [[nodiscard]] double unaccounted_energy() const;
  /// The mean stress of the contact forces in the box [lo, hi] (Love and
  /// Weber), Pa, compression positive: -(1/V) sum over the particles whose
  /// centres lie in the box (along a periodic axis: whose image does; the
  /// box no longer than the period) and over their contacts (with particles and
  /// walls) of (x_c - x_p) (x) f_c, symmetrised; V is the box's volume (2D:
  /// area x 1 m). In a saturated bed the contacts carry the effective
  /// stress. Forces as in the last evaluation (src/contact_stress.cpp).
  [[nodiscard]] Moment contact_stress(const Vec<D>& lo, const Vec<D>& hi) const;
  /// The mean stress of the contacts over the whole periodic cell (every
  /// axis periodic), as contact_stress over the cell's box (Pa, compression
  /// positive; 2D: per metre over 1 m).
  [[nodiscard]] Moment cell_stress() const;
  /// Satake's fabric tensor of the contacts between grains of which at
  /// least one has its centre in the box [lo, hi] (as contact_stress
  /// selects them; contacts with walls left out, bonds whose grains are
  /// apart counted): (1/N_c) sum of n (x) n over those N_c contacts, n their
  /// unit normals; trace 1. NaN in every component when there is none.
  [[nodiscard]] Moment contact_fabric(const Vec<D>& lo, const Vec<D>& hi) const;
  /// Each particle's sum over its contacts of (x_c - x_p) (x) f_c, N m:
  /// contact_stress is -1/V times the symmetric part of their sum over a
  /// volume's particles (e.g. per fluid cell, write_fluid_vti).
  [[nodiscard]] std::vector<Moment> contact_moments() const;
  /// The contacts of the last force evaluation, each pair once and each
  /// touching wall, with their forces: as applied if the last step recorded
  /// them (record_contact_forces), else recomputed as contact_stress does.
  [[nodiscard]] std::vector<ContactRecord<D>> contact_forces() const;
  [[nodiscard]] const VerletList<D>& pair_list() const { return list_; }
  /// For each wall, the force the particles put on each of its facets at the
  /// last force evaluation (N; empty for a wall that is not a mesh): the
  /// wall's force shared out by the facet each contact was on.
  [[nodiscard]] std::vector<std::vector<Vec<D>>> facet_forces() const;
  /// The particle-wall candidates with their histories and last forces.
  [[nodiscard]] const WallContactList<D>& wall_contacts() const { return wall_list_; }
  [[nodiscard]] std::size_t list_builds() const { return list_.builds(); }
  /// Bytes held by the particle, list and wall-contact arrays (capacity).
  [[nodiscard]] std::size_t memory_bytes() const;
  /// The whole state of the simulation for a checkpoint: particles, walls,
  /// the settings stages change, the clock, the neighbour lists with their
  /// contact histories, and the forces of the last evaluation. Loading it into
  /// a simulation built from the same scene and prepared continues the run
  /// bit for bit.
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(particles, walls, gravity, damping, skin, time_step, time, steps, list_, wall_list_, field_force_,
       block_sums_, removed_count, removed_mass, removed_volume, inserted_count, inserted_mass, broken_bonds,
       energy, force_gravity_, clumps);
    // The cell as it has deformed (a deforming periodic cell), its motion.
    ar(periodic.lower, periodic.length, periodic.inv_length, cell_motion, built_length_, cell_moment_,
       cell_moment_step_);
    if constexpr (Archive::loading) clumps.refresh(particles);
    // A stage may have changed the pairs' friction (Stage::frictions).
    std::vector<double> friction = contact_table.frictions();
    ar(friction);
    if constexpr (Archive::loading) contact_table.set_frictions(friction);
    bool from_field = field_forces_from_ != nullptr;
    ar(from_field);
    if constexpr (Archive::loading) field_forces_from_ = from_field ? force_field : nullptr;
  }
  /// Forces of the force field in the last evaluation (empty without one), N.
  [[nodiscard]] const std::vector<Vec<D>>& field_forces() const { return field_force_; }

 private:
  /// What the force evaluation ends with, particle by particle: nothing (at
  /// preparation), the second half kick (a step's end), or that and the next
  /// step's first half kick and drift (inside advance()).
  enum class Finish { none, kick, kick_kick_drift };
  /// Evaluates the forces; returns the largest displacement since the last
  /// list build after a drift (m), else 0.
  template <class Law, bool Rolling, bool Periodic>
  double compute_forces_with(Finish finish);
  template <class Law>
  double compute_forces_for_law(Finish finish);
  double compute_forces(Finish finish);
  /// Half kick (with damping) of the four particles from `first` on (fewer
  /// at the end), translation and rotation (kick.hpp).
  [[gnu::always_inline]] inline void kick_group(std::size_t first, double half_dt);
  /// Drift of the same particles; returns their largest squared
  /// displacement since the last build (infinite without reference positions).
  [[gnu::always_inline]] inline double drift_group(std::size_t first, bool referenced);
  /// First half kick and drift; returns the largest displacement since the
  /// last list build (m).
  double kick_drift();
  /// With track_energy: a half kick of every particle, its works added to
  /// `energy` (src/energy_budget.cpp), and with `drift` the drift after it;
  /// returns what kick_drift returns (0 without the drift).
  double tracked_kick(bool drift);
  /// With a deforming periodic cell: a half kick of every particle and
  /// with `drift` the drift after it, the cell's field included, and the
  /// cell's stretch over it; returns what kick_drift returns.
  double deforming_kick(bool drift);
  /// The drift of drift_group with the cell's field: each particle also
  /// moves by rate (x) (x - c) dt.
  double drift_group_in_field(std::size_t first, bool referenced);
  /// After a force evaluation with a deforming cell: with `tracked` (the
  /// pair forces recorded) the cell's work over the last drift into the
  /// budget's boundary work; the servo's new rates, from the recorded
  /// forces or, untracked, from the moments the force pass summed.
  void cell_step(bool tracked);
  /// The cell's stretch over a drift, which the force field follows.
  void stretch_cell();
  /// The normal stresses the cell's servo holds, from the contacts' (Pa,
  /// compression positive): with CellMotion::total_stress the force
  /// field's mean pressure added (the pore water's).
  [[nodiscard]] Vec<D> servo_stress(const Vec<D>& contacts) const;
  /// -1/V sym(sum d (x) f) over the pairs' forces the present evaluation
  /// recorded, at the positions it saw: the cell's stress for the budget
  /// (and its servo) on the tracked path.
  /// With `before_drift`, also the diagonal of sum d0 (x) f, d0 each
  /// pair's separation before the last drift (N m).
  [[nodiscard]] Moment recorded_cell_stress(Vec<D>* before_drift = nullptr) const;
  /// Adds to `energy` the works of one particle's half kick from the
  /// velocities it had before (v, w).
  void account_kick(std::size_t i, const Vec<D>& v, const AngVec<D>& w, double half_dt,
                    EnergyBudget& sum) const;
  /// Adds the walls' work to `energy` over a step that began with the
  /// walls as `before` (their places and loads).
  void account_walls(const std::vector<Wall<D>>& before);
  /// Calls visit(contact, list slot k, first selected, second selected) for
  /// each contact between two particles of which one at least is selected
  /// (selected(p) holds), its geometry only: force and moments left zero
  /// (src/contact_stress.cpp).
  template <class Select, class Visit>
  void for_each_selected_pair(Select&& selected, Visit&& visit) const;
  /// Calls visit(contact, first selected, second selected) for each contact
  /// of a particle for which selected(p) holds, with its force: the pairs of
  /// for_each_selected_pair, then the selected particles' wall contacts
  /// (src/contact_stress.cpp).
  template <class Select, class Visit>
  void for_each_contact_force(Select&& selected, Visit&& visit) const;
  /// Calls add(p, (x_c - x_p) (x) f_c) for each contact c of each particle
  /// p for which selected(p) holds (src/contact_stress.cpp).
  template <class Select, class Add>
  void for_each_contact_moment(Select&& selected, Add&& add) const;
  void rebuild_if_needed(double moved);
  /// Sets each servo's target from its schedule and cycle at the present
  /// time (where they vary), and a stress-controlled one's target force to
  /// its target stress times its loaded area now; throws if the walls no
  /// longer bound it.
  void update_servo_targets();
  /// Throws if a period is too short for the particles and skin.
  void check_periods() const;
  void rebuild();
  /// Removes the particles outside the domain (has_domain); returns, for
  /// each particle kept, the index it had (empty if none was removed).
  std::vector<std::uint32_t> remove_outside_domain();

  enum class LawChoice { linear, hertz, mixed };
  LawChoice law_choice_ = LawChoice::linear;
  bool rolling_ = false;
  bool prepared_ = false;
  VerletList<D> list_;
  WallContactList<D> wall_list_;
  std::vector<Vec<D>> field_force_;
  std::vector<EnergyBudget> group_works_;  ///< tracked_kick's works per group of four
  std::vector<EnergyBudget> clump_works_;  ///< tracked_kick's works per clump
  Vec<D> force_gravity_ = Vec<D>::Zero();  ///< the gravity in the last force evaluation (the budget's split)
  bool recording_ = false;                 ///< this force evaluation stores pair_force_
  std::vector<Vec<D>> pair_force_;         ///< force on i of each pair, as recorded
  std::uint64_t pair_force_step_ = ~std::uint64_t{0};  ///< the step that recorded pair_force_
  bool summing_moments_ = false;     ///< this force evaluation sums pair_moment_ (a servo-held cell)
  std::vector<Vec<D>> pair_moment_;  ///< per grain: the diagonal of sum d (x) f over its row of pairs, N m
  const ParticleForceField<D>* field_forces_from_ = nullptr;  ///< the field that gave field_force_
  std::vector<std::array<double, 2>> block_sums_;  ///< per force block: sum of |F| of contacts, count
  Vec<D> built_length_ = Vec<D>::Zero();           ///< the periods at the last list build, m
  /// The diagonal of sum d (x) f over the pairs at the evaluation of step
  /// cell_moment_step_ (N m): one end of the cell's work over a drift.
  Vec<D> cell_moment_ = Vec<D>::Zero();
  std::uint64_t cell_moment_step_ = ~std::uint64_t{0};
};

}  // namespace darcydem
