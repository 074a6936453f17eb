#pragma once
// Periodic boundaries: along each periodic axis k the domain repeats with
// period length[k] from lower[k] on, so a particle leaving through one side
// comes back through the other and particles near opposite sides touch.
// Contacts take the nearest image of the partner (x_j - x_i shifted by whole
// periods into [-L/2, L/2]); particles are put back into [lower, lower + L)
// at every neighbour-list build. Non-periodic axes are left alone.
#include <array>
#include <cmath>

#include "darcydem/core/vec.hpp"

namespace darcydem {

template <int D>
struct PeriodicCell {
  std::array<bool, D> periodic{};      ///< which axes repeat
  Vec<D> lower = Vec<D>::Zero();       ///< start of the period along each periodic axis, m
  Vec<D> length = Vec<D>::Zero();      ///< period along each periodic axis, m (0 elsewhere)
  Vec<D> inv_length = Vec<D>::Zero();  ///< 1 / length, 0 on non-periodic axes

  /// Makes axis k periodic over [lo, hi).
  void set_axis(int k, double lo, double hi) {
    periodic[k] = true;
    lower[k] = lo;
    length[k] = hi - lo;
    inv_length[k] = 1.0 / (hi - lo);
  }
  [[nodiscard]] bool any() const {
    for (bool p : periodic) {
      if (p) return true;
    }
    return false;
  }
  /// The nearest image of the separation d = x_j - x_i. On non-periodic
  /// axes inv_length is 0, so d is unchanged there.
  [[nodiscard]] Vec<D> shortest(Vec<D> d) const {
    for (int k = 0; k < D; ++k) d[k] -= length[k] * std::nearbyint(d[k] * inv_length[k]);
    return d;
  }
  /// The image of x (moved by whole periods along the periodic axes) in
  /// the box [lo, hi], if one is: the first at or above lo along each
  /// periodic axis (the only one for a box no longer than the period).
  [[nodiscard]] bool image_in_box(Vec<D> x, const Vec<D>& lo, const Vec<D>& hi,
                                  Vec<D>* image = nullptr) const {
    for (int k = 0; k < D; ++k) {
      if (periodic[k]) x[k] -= length[k] * std::floor((x[k] - lo[k]) * inv_length[k]);
      if (!(x[k] >= lo[k] && x[k] <= hi[k])) return false;
    }
    if (image != nullptr) *image = x;
    return true;
  }
  /// x moved by whole periods into [lower, lower + length) on the periodic axes.
  [[nodiscard]] Vec<D> wrap(Vec<D> x) const {
    for (int k = 0; k < D; ++k) {
      if (!periodic[k]) continue;
      x[k] -= length[k] * std::floor((x[k] - lower[k]) * inv_length[k]);
      // Round-off can leave x exactly at the upper end (x just below lower).
      if (x[k] >= lower[k] + length[k]) x[k] = lower[k];
    }
    return x;
  }
};

}  // namespace darcydem
