#pragma once
// An inlet: grains added to a running simulation at a steady rate in a box
// (LIGGGHTS's fix insert/rate/region, YADE's BoxFactory, PFC's ball
// generation in a cycle loop): pluviating a specimen, feeding a hopper,
// raining sediment. Every `interval` seconds while it is active the inlet
// adds what its rate has made due since (a count, or a mass: sizes drawn
// ahead so that a grain goes in once the mass budget covers it), each at a
// random place in the box where it touches no grain and no wall; what does
// not fit waits for the next insertion. With a clump template the inlet
// adds clumps (PFC's clump generation in a cycle loop): each grain's size
// is the sphere that holds the clump, the clump turned at random (or as the
// template stands) and placed where none of its members touches a particle
// or a wall.
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "darcydem/core/vec.hpp"
#include "darcydem/generation/generators.hpp"
#include "darcydem/particles/clumps.hpp"
#include "darcydem/simulation/simulation.hpp"

namespace darcydem {

template <int D>
struct Inlet {
  // Settings (the scene's [[inlet]]).
  std::string name;
  std::uint16_t material = 0;
  Vec<D> lower = Vec<D>::Zero();  ///< m: the box the grains are placed in, whole
  Vec<D> upper = Vec<D>::Zero();  ///< m
  /// The cylinder they are placed in instead, whole ([lower, upper] the
  /// box that holds it); none: the box.
  std::optional<Cylinder<D>> cylinder;
  RadiusDistribution radii;
  Vec<D> velocity = Vec<D>::Zero();  ///< m/s, each new grain's
  double rate = 0.0;                 ///< grains per second (0: by mass)
  double mass_rate = 0.0;            ///< kg/s (2D: kg/(s m)); used when rate is 0
  std::uint64_t max_count = std::numeric_limits<std::uint64_t>::max();  ///< the most it adds in all
  double max_mass = std::numeric_limits<double>::infinity();            ///< kg (2D: kg/m)
  double interval = 0.0;                                                ///< s between insertions
  std::int64_t max_attempts = 1000;  ///< random places tried per grain at each insertion
  bool active = true;
  /// The scene's `clump`: a clump of this shape in place of each grain,
  /// scaled so that the sphere about its centre of mass that holds it is
  /// the grain (the sizes, the box and the rates count clumps); none:
  /// spheres (2D: discs).
  std::optional<ClumpShape<D>> clump;
  std::string clump_name;
  bool aligned = false;  ///< each clump stands as its template does; else turned at random

  // State (checkpointed).
  std::mt19937_64 rng;
  double next_time = 0.0;    ///< s: the next insertion (while active)
  double budget = 0.0;       ///< grains (by count) or kg (by mass) due and not yet added
  double next_radius = 0.0;  ///< m: the next grain's size, drawn ahead
  std::uint64_t inserted = 0;
  double inserted_mass = 0.0;      ///< kg (2D: kg/m)
  std::uint64_t short_events = 0;  ///< insertions that left grains due for want of room

  /// Whether it has added all it may.
  [[nodiscard]] bool exhausted() const { return inserted >= max_count || inserted_mass >= max_mass; }
  /// The particles it has added: its grains, or its clumps' members.
  [[nodiscard]] std::uint64_t inserted_particles() const {
    return inserted * (clump ? clump->radius.size() : 1);
  }

  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(active, rng, next_time, budget, next_radius, inserted, inserted_mass, short_events);
  }
};

/// What one insertion did.
struct InsertionResult {
  std::uint64_t added = 0;
  bool short_of_room = false;  ///< grains were due that found no place
};

/// The inlet's insertion at the simulation's time: adds the grains due
/// (Simulation::add_particle, or add_clump), each at the first of up to
/// max_attempts random places in the box (a clump each time also turned at
/// random, unless aligned) where it overlaps no particle (nearest image
/// across periodic axes) and no wall, and moves next_time on by the
/// interval. The grains' forces are their weight under the current gravity.
template <int D>
InsertionResult insert_due(Inlet<D>& inlet, Simulation<D>& sim);

/// Every insertion due at the simulation's time, of each active inlet that
/// may still add (one each, unless rounding of the clock puts two within
/// half a step): the runner and the Python module insert alike through it.
template <int D>
void insert_all_due(std::vector<Inlet<D>>& inlets, Simulation<D>& sim);

/// The next insertion of an active inlet that may still add, s (1e300: none).
template <int D>
double next_insertion_time(const std::vector<Inlet<D>>& inlets);

/// Whether the box [lo, hi] lies outside the box [grid_lo, grid_hi] beside
/// it along an axis that is not periodic (an inlet's box or a new grain
/// against the pore fluid's grid).
template <int D>
bool box_beside(const Vec<D>& lo, const Vec<D>& hi, const Vec<D>& grid_lo, const Vec<D>& grid_hi,
                const PeriodicCell<D>& cell);

/// The mass of a grain of the inlet's material and of this size (m), kg
/// (2D: kg/m): a sphere's, or a clump's of that size.
template <int D>
double inlet_grain_mass(const Inlet<D>& inlet, const Simulation<D>& sim, double radius);

}  // namespace darcydem
