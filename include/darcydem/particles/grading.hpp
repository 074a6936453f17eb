#pragma once
// The grains' grading as a sieve analysis reads it: the diameters D_x that
// a fraction x of the mass passes, and the coefficients of uniformity and
// curvature soil classification uses.
#include <string>
#include <vector>

namespace darcydem {

struct GradingSummary {
  double d_min = 0.0;  ///< smallest diameter, m
  double d_max = 0.0;  ///< largest diameter, m
  /// D_x: the smallest grain diameter that, with all grains no larger,
  /// carries x of the mass, m.
  double d10 = 0.0;
  double d30 = 0.0;
  double d50 = 0.0;
  double d60 = 0.0;
  /// Coefficient of uniformity Cu = D60 / D10.
  [[nodiscard]] double uniformity() const { return d60 / d10; }
  /// Coefficient of curvature Cc = D30^2 / (D10 D60).
  [[nodiscard]] double curvature() const { return d30 * d30 / (d10 * d60); }
};

/// The grading by mass of grains of the given radii (spheres, mass as d^3;
/// in 2D discs of unit thickness, d^2). At least one radius.
template <int D>
GradingSummary grading_of(const std::vector<double>& radius);

/// One line for the run log and `darcydem check`: the sizes, and for
/// unequal ones D10, D30, D50, D60, Cu and Cc by mass.
template <int D>
std::string describe_grading(const std::vector<double>& radius);

}  // namespace darcydem
