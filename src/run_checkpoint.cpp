#include "darcydem/simulation/run_checkpoint.hpp"

#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "darcydem/output/checkpoint_archive.hpp"
#include "darcydem/version.hpp"

namespace darcydem {
namespace {

constexpr const char* checkpoint_magic = "darcydem checkpoint";
constexpr std::uint32_t format = 22;  // 2: the pore fluid's patches; 3: the walls' series; 4: the contacts'
// series; 5: the particles removed outside the domain; 6: inlets; 7: contact bonds; 8: bonds' moments; 9:
// bonds' strengths; 10: the walls' spin and torque, stress servos, the pairs' friction a stage set;
// 11: the cylinders' radius servo and radial_velocity; 12: turning planes and boxes (axis, axes, pivot);
// 13: walls that oscillate; 14: servo targets in time (schedule, cycle); 15: the fluid's sources; 16: sources
// that hold a pressure; 17: mesh walls' facets in the wall contacts, clumps; 18: particles' volume_scale
// (clumps of overlapping members); 19: the sources' series; 20: the periodic cell's lengths and motion; 21:
// the periodic cell's lengths at the stage's start (cell_strain); 22: the fluid grid's origin and spacing
// and its cells' volume at the last fluid step (a grid that follows a deforming cell)
constexpr const char* end_mark = "end of checkpoint";

/// The header: what a reader must share with the writer.
struct Header {
  std::string magic;
  std::uint32_t format = 0;
  std::int32_t dimension = 0;
  std::uint64_t byte_order = 0;  ///< 0x0102030405060708 as this machine stores it
  double one_and_a_half = 0.0;   ///< 1.5: the same floating-point format
  std::string version;
  std::string scene_hash;
  std::uint64_t particles = 0;
  bool fluid = false;
  bool analysis = false;

  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(this->magic);
    if constexpr (Archive::loading) {
      if (this->magic != checkpoint_magic) throw CheckpointError(ar.name() + ": not a darcydem checkpoint");
    }
    ar(this->format, dimension, byte_order, one_and_a_half, version, scene_hash, particles, fluid, analysis);
  }
};

template <int D>
Header header_of(const Scene<D>& scene, const RunState<D>& state) {
  Header h;
  h.magic = checkpoint_magic;
  h.format = format;
  h.dimension = D;
  h.byte_order = 0x0102030405060708ULL;
  h.one_and_a_half = 1.5;
  h.version = version_string;
  h.scene_hash = scene.text_hash;
  // As the scene built them: those removed outside the [domain] included,
  // those an inlet added not.
  const auto& sim = state.simulation;
  h.particles = sim.particles.size() + sim.removed_count - sim.inserted_count;
  h.fluid = state.fluid != nullptr;
  h.analysis = state.analysis != nullptr;
  return h;
}

template <class Archive, int D>
void state_items(Archive& ar, const RunState<D>& state) {
  ar(state.position, state.simulation, state.inlets);
  if (state.fluid != nullptr) state.fluid->checkpoint(ar, &state.simulation.field_forces());
  if (state.analysis != nullptr) ar(*state.analysis);
  ar(state.particle_series, state.fluid_series, state.wall_series, state.contact_series, state.source_series);
}

}  // namespace

template <int D>
void write_checkpoint(const std::string& path, const Scene<D>& scene, const RunState<D>& state) {
  const std::string temporary = path + ".part";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write the checkpoint", temporary));
    CheckpointWriter ar(out, temporary);
    Header h = header_of(scene, state);
    ar(h);
    state_items(ar, state);
    std::string end = end_mark;
    ar(end);
    out.close();
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write the checkpoint", temporary));
  }
  std::filesystem::rename(temporary, path);
}

template <int D>
void read_checkpoint(const std::string& path, const Scene<D>& scene, const RunState<D>& state) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw CheckpointError(
        fmt::format("{}: no checkpoint to resume from (a run writes one when it is interrupted, and every "
                    "--checkpoint-every seconds; a run that completes removes it)",
                    path));
  }
  CheckpointReader ar(in, path);
  Header h;
  ar(h);
  const Header want = header_of(scene, state);
  if (h.format != format)
    throw CheckpointError(
        fmt::format("{}: checkpoint format {}; this darcydem reads format {}", path, h.format, format));
  if (h.byte_order != want.byte_order || h.one_and_a_half != want.one_and_a_half)
    throw CheckpointError(
        fmt::format("{}: written on a machine with another byte order or number format", path));
  if (h.version != want.version)
    throw CheckpointError(fmt::format("{}: written by darcydem {}; this is {}: resume with the same version",
                                      path, h.version, want.version));
  if (h.dimension != D)
    throw CheckpointError(
        fmt::format("{}: a {}D run; the scene {} is {}D", path, h.dimension, scene.file, D));
  if (h.scene_hash != want.scene_hash)
    throw CheckpointError(
        fmt::format("{}: written for a scene with hash fnv1a64:{}, but {} has fnv1a64:{}; resume needs "
                    "the scene file the run started with, unchanged",
                    path, h.scene_hash, scene.file, want.scene_hash));
  if (h.particles != want.particles || h.fluid != want.fluid || h.analysis != want.analysis)
    throw CheckpointError(fmt::format("{}: does not match the run that {} builds", path, scene.file));
  state_items(ar, state);
  std::string end;
  ar(end);
  if (end != end_mark) throw CheckpointError(fmt::format("{}: damaged (no end mark)", path));
  const auto& sim = state.simulation;
  if (sim.particles.size() + sim.removed_count - sim.inserted_count != want.particles)
    throw CheckpointError(fmt::format("{}: damaged (particle arrays of the wrong length)", path));
}

template void write_checkpoint<2>(const std::string&, const Scene<2>&, const RunState<2>&);
template void write_checkpoint<3>(const std::string&, const Scene<3>&, const RunState<3>&);
template void read_checkpoint<2>(const std::string&, const Scene<2>&, const RunState<2>&);
template void read_checkpoint<3>(const std::string&, const Scene<3>&, const RunState<3>&);

}  // namespace darcydem
