#pragma once
// What the walls do, in words, for `darcydem check`: each wall's motion as
// the scene sets it and as each stage changes it.
#include <string>

#include "darcydem/scene/scene.hpp"

namespace darcydem {

/// One line per wall that moves, turns, shakes or is a servo in [[wall]],
/// and per wall a stage sets in motion ("stage NAME: wall ..."): its
/// velocity, a servo's target (a schedule's range and duration, a cycle's
/// amplitude, frequency and phase, and what load it reads), a turn, a
/// cylinder's rate of change of radius, and an oscillation's amplitude,
/// frequency and peak acceleration, with Gamma = A omega^2 / g along the
/// gravity of the stage (above 1 a bed resting on the wall leaves it once
/// a cycle).
template <int D>
std::string describe_wall_motions(const Scene<D>& scene);

}  // namespace darcydem
