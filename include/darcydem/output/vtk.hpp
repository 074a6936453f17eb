#pragma once
// VTK XML output: particle snapshots as .vtu (points with radius, velocity,
// angular velocity, force, id) and a .pvd series that ParaView opens. The
// series file is rewritten after every snapshot, so it stays valid when a
// run is interrupted.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/particles/particle_data.hpp"
#include "darcydem/simulation/simulation.hpp"
#include "darcydem/walls/wall.hpp"

namespace darcydem {

/// The particles as VTK points (.vtu): radius, id, velocity, force,
/// angular_velocity, and with `fluid_force` (one per particle, N) the pore
/// fluid's force on each too, and with `clump` (one per particle) the clump
/// each is a member of (-1: none; Clumps::clump_of), to colour clumps by.
template <int D>
void write_particles_vtu(const std::string& path, const ParticleData<D>& particles,
                         const std::vector<Vec<D>>* fluid_force = nullptr,
                         const std::vector<std::int32_t>* clump = nullptr);

/// The contact network as VTK lines (.vtu), one per contact: from the first
/// particle's centre to the other's (its nearest periodic image) or to the
/// contact point on a wall. Cell data: normal_force (N, compression
/// positive), tangential_force (N, magnitude), force (N, on the first
/// particle), overlap (m), first_id and second_id (particle ids; -1 for a
/// wall), wall_id (-1 between particles). As ParaView's force chains: colour
/// or "Tube" radius by normal_force.
template <int D>
void write_contacts_vtu(const std::string& path, const ParticleData<D>& particles,
                        const std::vector<ContactRecord<D>>& contacts);

/// The walls as VTK cells (.vtu), with their index (`wall_id`), force and
/// velocity as cell data. A box is a hexahedron in 3D and a quad in 2D
/// (flat for a plate or a segment); an infinite plane is drawn as a square
/// in 3D or a line in 2D, centred on the point of the plane nearest the
/// centre of [lo, hi] and as wide as 1.1 times that box's diagonal. A mesh
/// is a triangle a facet; with `facet_forces` (Simulation::facet_forces)
/// each facet's cell has the force on that facet, and `normal_stress` (Pa)
/// its normal part over the facet's area (0 on the cells of other walls).
template <int D>
void write_walls_vtu(const std::string& path, const std::vector<Wall<D>>& walls, const Vec<D>& lo,
                     const Vec<D>& hi, const std::vector<std::vector<Vec<D>>>* facet_forces = nullptr);

/// The pore fluid's cell fields as VTK ImageData (.vti), or RectilinearGrid
/// (.vtr, the faces' coordinates) when an axis is graded: excess pressure,
/// porosity, intrinsic permeability, Darcy velocity, solid velocity and,
/// given the cells' contact stress (cell_contact_stress), the effective
/// stress as a tensor (9 components, compression positive; zz = 0 in 2D)
/// and its mean (trace / D). In 2D the cells are 1 m thick.
template <int D>
void write_fluid_vti(const std::string& path, const PoreFluid<D>& fluid,
                     const std::vector<Eigen::Matrix<double, D, D>>* effective_stress = nullptr);

/// The pore fluid's sources and wells (`[[fluid.source]]`) as VTK cells
/// (.vtu): a point source a vertex at its position, a screened well a line
/// along its screen. Cell data: source_id (its index in the scene),
/// inflow (what it gave in the last fluid step, m^3/s; 2D per metre,
/// negative: pumped out), pressure (at its bore, or in its cell without a
/// radius, Pa), radius (m, 0: none), held (1 while it holds a pressure, 0
/// while it gives an inflow), open (a drain's state in the last fluid
/// step: 1 open, 0 shut; 1 for other sources).
template <int D>
void write_sources_vtu(const std::string& path, const PoreFluid<D>& fluid);

class PvdSeries {
 public:
  explicit PvdSeries(std::string path) : path_(std::move(path)) {}
  /// Adds a dataset (file name relative to the .pvd) at a time and rewrites the series.
  void add(double time, const std::string& file);
  /// The entries so far (a resumed run rewrites the series with them).
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(entries_);
  }

 private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace darcydem
