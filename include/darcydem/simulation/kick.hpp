#pragma once
// The half kick of velocity Verlet for four particles at once:
//   f' = f - alpha |f| sign(v)          (Cundall's local damping, per component)
//   v += (f' / m - beta v) dt/2          (beta: global viscous damping)
// for a field stored particle after particle with W components each (W = D
// for velocities, 1 or 3 for angular velocities), skipping fixed particles.
// The W components of four particles are W vectors of four doubles; each
// particle's inverse mass is spread over its components by a shuffle. Every
// particle goes through this same code, also the last ones of a system whose
// size is not a multiple of four (padded copies), so a particle's velocity
// does not depend on where it falls in a group, a thread's share or a sweep.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include <Eigen/Core>

#include "darcydem/core/lanes.hpp"

namespace darcydem::kick {

using darcydem::LaneMask;
using darcydem::Lanes;

struct Settings {
  double local = 0.0;    ///< Cundall's alpha
  double viscous = 0.0;  ///< beta, 1/s
  double half_dt = 0.0;  ///< s
};

/// Lane l of vector k holds component (4k + l) of four particles laid out
/// W by W: it belongs to particle (4k + l) / W.
template <int W, int K>
inline Lanes spread(Lanes per_particle) {
  constexpr LaneMask index = {(4 * K + 0) / W, (4 * K + 1) / W, (4 * K + 2) / W, (4 * K + 3) / W};
  return __builtin_shuffle(per_particle, index);
}
template <int W, int K>
inline LaneMask spread(LaneMask per_particle) {
  constexpr LaneMask index = {(4 * K + 0) / W, (4 * K + 1) / W, (4 * K + 2) / W, (4 * K + 3) / W};
  return __builtin_shuffle(per_particle, index);
}

/// One vector of components: loads f and v, returns the kicked v.
[[gnu::always_inline]] inline Lanes kick_lanes(Lanes f, Lanes v, Lanes inv_mass, LaneMask free, Settings s) {
  if (s.local > 0.0) {
    const Lanes one = {1.0, 1.0, 1.0, 1.0};
    const LaneMask one_bits = reinterpret_cast<LaneMask>(one);
    const Lanes sign =
        reinterpret_cast<Lanes>((v > 0.0) & one_bits) - reinterpret_cast<Lanes>((v < 0.0) & one_bits);
    const LaneMask magnitude_bits = ~reinterpret_cast<LaneMask>(Lanes{-0.0, -0.0, -0.0, -0.0});
    const Lanes magnitude = reinterpret_cast<Lanes>(reinterpret_cast<LaneMask>(f) & magnitude_bits);
    f = f - s.local * magnitude * sign;
  }
  Lanes a = f * inv_mass;
  if (s.viscous > 0.0) a = a - s.viscous * v;
  const Lanes kicked = v + a * s.half_dt;
  return free != 0 ? kicked : v;
}

/// Kicks particles [first, first + count) (count <= 4) of a field with W
/// components per particle: v += ... from the load f and inverse masses.
template <int W>
[[gnu::always_inline]] inline void kick_group(double* velocity, const double* load_, const double* inv_mass,
                                              const std::uint8_t* fixed, int count, Settings s) {
  // A group of fewer than four works on copies whose lanes past `count`
  // hold zeros; they are never written back.
  alignas(32) double pad_v[4 * W];
  alignas(32) double pad_f[4 * W];
  Lanes m = {0.0, 0.0, 0.0, 0.0};
  LaneMask free = {0, 0, 0, 0};
  const bool full = count == 4;
  double* v = velocity;
  const double* f = load_;
  if (full) {
    m = load_lanes(inv_mass);
  } else {
    std::copy(velocity, velocity + count * W, pad_v);
    std::copy(load_, load_ + count * W, pad_f);
    std::fill(pad_v + count * W, pad_v + 4 * W, 0.0);
    std::fill(pad_f + count * W, pad_f + 4 * W, 0.0);
    v = pad_v;
    f = pad_f;
    for (int l = 0; l < count; ++l) m[l] = inv_mass[l];
  }
  for (int l = 0; l < count; ++l) free[l] = fixed[l] == 0 ? -1 : 0;
  [&]<int... K>(std::integer_sequence<int, K...>) {
    ((store_lanes(v + 4 * K, kick_lanes(load_lanes(f + 4 * K), load_lanes(v + 4 * K), spread<W, K>(m),
                                        spread<W, K>(free), s))),
     ...);
  }
  (std::make_integer_sequence<int, W>{});
  if (!full) std::copy(pad_v, pad_v + count * W, velocity);
}

/// Cundall's local damping force on a load f moving with v, one particle or
/// body at a time (the lanes above do the same four at a time):
/// -alpha |f_k| sign(v_k), component by component.
template <int K>
Eigen::Matrix<double, K, 1> local_damping(double alpha, const Eigen::Matrix<double, K, 1>& f,
                                          const Eigen::Matrix<double, K, 1>& v) {
  Eigen::Matrix<double, K, 1> out;
  for (int k = 0; k < K; ++k)
    out[k] = -alpha * std::abs(f[k]) * static_cast<double>((v[k] > 0.0) - (v[k] < 0.0));
  return out;
}

}  // namespace darcydem::kick
