#pragma once
// Clumps: rigid bodies made of several particles (PFC's clumps, YADE's
// clumps). Each member stays an ordinary particle for contacts, walls, the
// pore fluid and output; its own integration is switched off (its `fixed`
// flag is ParticleData::clump_member) and it moves with its clump:
//   x_i = x_c + R b_i,  v_i = v_c + w x (R b_i),  w_i = w,
// b_i its offset in the clump's principal frame, R the clump's orientation.
// Members that do not overlap keep their own masses, and the clump's mass,
// centre of mass and inertia are their sums. Members that overlap (PFC's
// usual clump of pebbles) make a clump with the mass, centre of mass and
// inertia of their union (ball_union.hpp), each member's mass and solid
// volume for the pore fluid its share of the union, the shares placed so
// that gravity and buoyancy on the members put no moment on the clump
// about its centre of mass. The clump takes the members' forces
// (contacts, gravity, the pore fluid's) and moments about its centre, and
// integrates them by velocity Verlet: half kicks of its momentum and
// angular momentum, and a drift that turns it at the angular velocity of
// the midpoint of the turn (implicit midpoint: the angular momentum of a
// free clump is kept to round-off, its energy to second order in dt).
// Pairs of members of one clump are never in contact.
#include <array>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "darcydem/core/periodic_cell.hpp"
#include "darcydem/core/vec.hpp"
#include "darcydem/particles/particle_data.hpp"
#include "darcydem/simulation/energy_budget.hpp"

namespace darcydem {

/// A clump's orientation: 2D the angle (rad, counter-clockwise); 3D a unit
/// quaternion (w, x, y, z).
template <int D>
using Orientation = Eigen::Matrix<double, D == 2 ? 1 : 4, 1>;

/// The rotation matrix of an orientation.
Eigen::Matrix<double, 2, 2> rotation_matrix(const Orientation<2>& q);
Eigen::Matrix<double, 3, 3> rotation_matrix(const Orientation<3>& q);

/// The shape of a clump: its members' centres and radii about its centre of
/// mass, in its principal axes, scaled so that the sphere (2D: circle) about
/// the centre of mass that holds every member has radius 1.
template <int D>
struct ClumpShape {
  std::vector<Vec<D>> centre;
  std::vector<double> radius;
  /// Each member's share of the clump's volume at this scale: its own
  /// volume, or with overlapping members its share of their union
  /// (volume_shares in clumps.cpp). Its mass and the pore fluid's solid.
  std::vector<double> share;
  bool overlapping = false;  ///< some members overlap (then share < own volume)
  /// Principal moments of inertia per unit density at this scale
  /// (kg m^2 / (kg/m^3) for a size of 1 m; 2D: one, per metre).
  AngVec<D> inertia_per_density = AngVec<D>::Zero();
  double volume = 0.0;  ///< per unit size cubed (2D: squared, per metre)
  /// The principal axes in the frame the members were given in: a clump
  /// placed at orientation q stands as given, turned by q.
  Orientation<D> principal = identity_orientation();
  static Orientation<D> identity_orientation() {
    Orientation<D> q = Orientation<D>::Zero();
    if constexpr (D == 3) q[0] = 1.0;
    return q;
  }
};

/// An orientation drawn uniformly over all orientations (3D: Shoemake's
/// quaternion; 2D: an angle in [0, 2 pi)).
template <int D>
Orientation<D> random_orientation(std::mt19937_64& rng);
template <>
Orientation<2> random_orientation<2>(std::mt19937_64& rng);
template <>
Orientation<3> random_orientation<3>(std::mt19937_64& rng);

/// The orientation q1 after q0: turned by q0, then by q1.
Orientation<2> compose(const Orientation<2>& q1, const Orientation<2>& q0);
Orientation<3> compose(const Orientation<3>& q1, const Orientation<3>& q0);

/// Makes a clump's shape from members given in any frame and unit
/// (centres and radii): moves their centre of mass to the origin, turns
/// them into their principal axes and scales them to a bounding radius of 1.
/// Members may overlap (by more than 1e-9 of the smaller radius): then the
/// volume, centre of mass and inertia are those of their union
/// (ball_union.hpp) and each member gets a share of that volume. Throws
/// std::invalid_argument, saying which, if fewer than one member is given,
/// a radius is not positive, or no positive shares put the weight at the
/// union's centre of mass.
template <int D>
ClumpShape<D> make_clump_shape(const std::vector<Vec<D>>& centres, const std::vector<double>& radii);

/// What Clumps::advance needs to split each clump's load by kind for the
/// energy budget (energy_budget.hpp), and where it puts the works.
template <int D>
struct ClumpLoadKinds {
  Vec<D> gravity = Vec<D>::Zero();             ///< m/s^2, as the last force evaluation had it
  const std::vector<Vec<D>>* field = nullptr;  ///< N, the force field's per particle (or none)
  std::vector<EnergyBudget>* works = nullptr;  ///< per clump: each half kick's works added
};

template <int D>
struct Clumps {
  // Per clump.
  std::vector<std::uint32_t> first;  ///< its members are member_id[first[c] .. first[c + 1])
  std::vector<double> mass;          ///< kg (2D: per metre)
  std::vector<AngVec<D>> inertia;    ///< principal moments, kg m^2 (2D: per metre)
  std::vector<std::uint8_t> fixed;   ///< 1: its velocities are prescribed
  std::vector<Vec<D>> position;      ///< centre of mass, m
  std::vector<Orientation<D>> orientation;
  std::vector<Vec<D>> velocity;             ///< m/s
  std::vector<AngVec<D>> angular_velocity;  ///< rad/s, world frame
  std::vector<Vec<D>> force;                ///< N: the members' last forces, summed
  std::vector<AngVec<D>> torque;            ///< N m, about the centre of mass
  // Per member, in clump order.
  std::vector<std::uint32_t> member_id;  ///< the particle's id (creation number)
  std::vector<Vec<D>> offset;            ///< b_i, m, in the principal frame
  /// Derived from the particles' order (refresh): each member's index now,
  /// and each particle's clump (-1 for none). Not checkpointed.
  std::vector<std::uint32_t> member_index;
  std::vector<std::int32_t> clump_of;
  /// The simulation's periodic boundaries (it sets them on every list
  /// build): each member is placed at the image of x_c + R b_i nearest to
  /// where it was, so it moves continuously while the list builds put the
  /// particles, and the clumps' centres, back into the period one by one.
  PeriodicCell<D> period;

  using Rotation = Eigen::Matrix<double, D, D>;

  [[nodiscard]] std::size_t size() const { return mass.size(); }
  [[nodiscard]] bool empty() const { return mass.empty(); }

  /// Adds a clump of `shape` scaled by `size` (m) with its centre of mass at
  /// x, turned by q from the frame its shape was given in, its members appended to the particles (material
  /// `mat` of `density`), all moving at velocity v without spin; returns its
  /// number. The members' indices (member_index, clump_of) are those of the
  /// particles now, until they are reordered or removed (refresh()).
  std::size_t add(ParticleData<D>& particles, const ClumpShape<D>& shape, double size, const Vec<D>& x,
                  const Orientation<D>& q, double density, std::uint16_t mat, bool is_fixed, const Vec<D>& v);

  /// Keeps the clumps c with kept[c] != 0 (in order), drops the others
  /// with their members' entries; member_index and clump_of are left for
  /// refresh() (their particles were removed too).
  void keep(const std::vector<std::uint8_t>& kept);

  /// Re-derives member_index and clump_of from the particles' ids (after the
  /// particles were reordered, removed or added).
  void refresh(const ParticleData<D>& particles);

  /// Each clump's force and moment from its members' (particles.force and
  /// torque, as the last force evaluation left them).
  void gather(const ParticleData<D>& particles);

  /// Each clump (in parallel over the clumps): gathers its force and moment;
  /// unless fixed, takes `kicks` half kicks with Cundall's local damping
  /// alpha on each component of its force and moment and viscous damping
  /// beta (as kick.hpp does for particles); then with dt > 0 drifts (moves
  /// and turns over dt) and puts its members where it carries them, else
  /// gives them its velocities. Returns the largest squared displacement of
  /// a member from `reference` (its place at the last list build; infinite
  /// when `reference` does not cover the particles; 0 without a drift).
  /// With `kinds`, each half kick's works by kind of load go into
  /// kinds->works[c] (sized to the clumps): gravity, the field's and the
  /// external forces' (the members' loads of each kind and their moments
  /// about the centre of mass), the contacts' (the rest), damping's; for a
  /// fixed clump the contacts' work on it, as a boundary's.
  double advance(ParticleData<D>& particles, int kicks, double half_dt, double alpha, double beta, double dt,
                 const std::vector<Vec<D>>& reference, const ClumpLoadKinds<D>* kinds = nullptr);

  /// The clumps' kinetic energy, 1/2 M v^2 + 1/2 w.L, the fixed ones' left
  /// out (as fixed particles' are) (J; 2D per metre).
  [[nodiscard]] double kinetic_energy() const;
  /// Clump c's.
  [[nodiscard]] double kinetic_energy(std::size_t c) const;

  /// Puts each member where its clump is, at its clump's velocity.
  void place_members(ParticleData<D>& particles) const;
  /// The same for the members of clump c, at its orientation's rotation r.
  void place(std::size_t c, const Rotation& r, ParticleData<D>& particles) const;

  /// The largest distance from a clump's centre of mass to its members'
  /// surfaces (m; 0 without clumps).
  [[nodiscard]] double largest_reach(const ParticleData<D>& particles) const;

  /// The least effective mass of a normal contact on member k of clump c
  /// over the contact's directions (kg): what the critical time step takes
  /// for a member (its tangential mode as for a sphere's, a factor of the
  /// contact law's).
  [[nodiscard]] double contact_mass(std::size_t c, std::size_t k) const;

  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(first, mass, inertia, fixed, position, orientation, velocity, angular_velocity, force, torque,
       member_id, offset);
  }

 private:
  void gather_one(std::size_t c, const Rotation& r, const ParticleData<D>& particles);
  /// Returns the local damping's force and moment it applied.
  std::pair<Vec<D>, AngVec<D>> kick_one(std::size_t c, const Rotation& r, double half_dt, double alpha,
                                        double beta);
  /// One half kick as kick_one, its works by kind added to `works`.
  void account_kick(std::size_t c, const Rotation& r, double half_dt, double alpha, double beta,
                    const std::array<Vec<D>, 3>& load, const std::array<AngVec<D>, 3>& moment,
                    EnergyBudget& works);
  /// Turns clump c over dt from orientation r (its angular velocity follows
  /// in 3D); returns its new rotation.
  Rotation turn_one(std::size_t c, const Rotation& r, double dt);
};

}  // namespace darcydem
