#pragma once
// A deforming periodic cell (YADE's Cell with a velocity gradient and
// PeriTriaxController, PFC's periodic space with a strain rate): a cell
// periodic along every axis stretches or shrinks along each axis at a strain
// rate, set or servo-controlled on a target stress, so that a packing can be
// compressed, sheared to a triaxial or biaxial state or held at a stress
// without walls.
//
// The grains' velocities are the fluctuations about the homogeneous field
// v = rate (x) (x - c) (componentwise; c the cell's centre, which stays
// put); each drift moves a grain by its own velocity and by the field's over
// the step, and the cell's lengths by the same factor (1 + rate dt), so a
// grain at rest in the field keeps its place relative to the cell. Contacts see the field too: the relative
// velocity of j's image against i takes rate (x) d on top of the grains'
// own, d = x_j - x_i the separation.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "darcydem/core/periodic_cell.hpp"
#include "darcydem/core/vec.hpp"

namespace darcydem {

template <int D>
struct CellMotion {
  /// Per axis: held at a target stress (true) or strained at a set rate.
  std::array<bool, D> by_stress{};
  Vec<D> strain_rate = Vec<D>::Zero();    ///< 1/s, the rate of the last and next drift, per axis
  Vec<D> target_stress = Vec<D>::Zero();  ///< Pa, compression positive, on the axes held by stress
  double gain = 0.0;                      ///< 1/(Pa s): rate = gain (stress - target)
  double max_strain_rate = 0.0;           ///< 1/s, the servo's largest rate (magnitude)
  /// The servo holds the total stress: the contacts' plus the pore
  /// water's mean excess pressure (an undrained test with the water
  /// itself); false: the contacts' alone, the effective stress.
  bool total_stress = false;
  Vec<D> stress = Vec<D>::Zero();  ///< Pa: the normal stresses the servo last saw
  /// m: the periods when the run's present stage began, from which the
  /// cell_strain probe counts (the runner sets them).
  Vec<D> reference_length = Vec<D>::Zero();

  /// The most a step may stretch the cell, |rate| dt: a tenth of a percent
  /// per step is already far beyond a quasi-static test.
  static constexpr double largest_stretch = 1e-3;
  /// Whether a strain rate (1/s) keeps within largest_stretch per step of dt.
  [[nodiscard]] static bool rate_allowed(double rate, double dt) {
    return std::isfinite(rate) && std::abs(rate) * dt < largest_stretch;
  }
  /// Whether an axis is held by stress without the servo's gain or its
  /// largest rate.
  [[nodiscard]] bool servo_incomplete() const {
    return any_by_stress() && !(gain > 0.0 && max_strain_rate > 0.0);
  }

  /// Whether the cell moves or may move (a rate, or a servo on an axis).
  [[nodiscard]] bool active() const {
    for (int k = 0; k < D; ++k) {
      if (by_stress[k] || strain_rate[k] != 0.0) return true;
    }
    return false;
  }
  [[nodiscard]] bool any_by_stress() const {
    for (bool s : by_stress) {
      if (s) return true;
    }
    return false;
  }
  /// The servo: each axis held by stress takes the rate gain (stress -
  /// target), at most max_strain_rate either way (compression positive, so
  /// too little stress shrinks the cell).
  void servo(const Vec<D>& normal_stress) {
    stress = normal_stress;
    for (int k = 0; k < D; ++k) {
      if (!by_stress[k]) continue;
      const double r = gain * (normal_stress[k] - target_stress[k]);
      strain_rate[k] = std::isnan(r) ? 0.0 : std::clamp(r, -max_strain_rate, max_strain_rate);
    }
  }
  /// The logarithmic strain ln(L / L_ref) along axis k since the stage
  /// began (the sum of ln(1 + rate dt) over its drifts: negative while
  /// the cell shrinks, as the strain rate), or with k < 0 the volumetric
  /// strain ln(V / V_ref), the sum over the axes.
  [[nodiscard]] double strain(const PeriodicCell<D>& cell, int k) const {
    if (k >= 0) return std::log(cell.length[k] / reference_length[k]);
    double sum = 0.0;
    for (int a = 0; a < D; ++a) sum += std::log(cell.length[a] / reference_length[a]);
    return sum;
  }
  /// The cell after a drift of dt at the present rate: each length times
  /// (1 + rate dt), about the cell's centre, which stays where it is (the
  /// field's fixed point).
  void stretch(PeriodicCell<D>& cell, double dt) const {
    for (int k = 0; k < D; ++k) {
      if (strain_rate[k] == 0.0) continue;
      const double centre = cell.lower[k] + 0.5 * cell.length[k];
      cell.length[k] *= 1.0 + strain_rate[k] * dt;
      cell.lower[k] = centre - 0.5 * cell.length[k];
      cell.inv_length[k] = 1.0 / cell.length[k];
    }
  }

  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(by_stress, strain_rate, target_stress, gain, max_strain_rate, stress, reference_length, total_stress);
  }
};

/// What a stage changes of the cell's motion: per axis a rate or a target
/// stress (axes not given keep theirs), and the servo's settings.
template <int D>
struct CellChange {
  struct Axis {
    bool by_stress = false;
    double value = 0.0;  ///< 1/s or Pa
  };
  std::array<std::optional<Axis>, D> axes{};
  std::optional<double> gain;
  std::optional<double> max_strain_rate;
  std::optional<bool> total_stress;

  void apply(CellMotion<D>& m) const {
    for (int k = 0; k < D; ++k) {
      if (!axes[k]) continue;
      m.by_stress[k] = axes[k]->by_stress;
      if (axes[k]->by_stress) {
        m.target_stress[k] = axes[k]->value;
      } else {
        m.strain_rate[k] = axes[k]->value;
      }
    }
    if (gain) m.gain = *gain;
    if (max_strain_rate) m.max_strain_rate = *max_strain_rate;
    if (total_stress) m.total_stress = *total_stress;
  }
};

}  // namespace darcydem
