#pragma once
// VTK XML output: particle snapshots as .vtu (points with radius, velocity,
// angular velocity, force, id) and a .pvd series that ParaView opens. The
// series file is rewritten after every snapshot, so it stays valid when a
// run is interrupted.
#include <string>
#include <utility>
#include <vector>

#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/particles/particle_data.hpp"

namespace darcydem {

template <int D>
void write_particles_vtu(const std::string& path, const ParticleData<D>& particles);

/// The pore fluid's cell fields as VTK ImageData (.vti): excess pressure,
/// porosity, intrinsic permeability, Darcy velocity, solid velocity. In 2D
/// the cells are 1 m thick.
template <int D>
void write_fluid_vti(const std::string& path, const PoreFluid<D>& fluid);

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
