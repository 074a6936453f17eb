#pragma once
// The closed form of the pore water's thrust on a sheet pile in a confined
// layer, which two verification tests compare with.
#include <cmath>
#include <numbers>

namespace darcydem::testing {

/// Harr's confined sheet pile (a pile from the drained top of a layer of
/// thickness T down to depth s, heads differing by dh across it, the base
/// impermeable) mapped onto a rectangle: the
/// downstream half of the layer (depth d from the top, 0..T, x beyond the
/// pile) goes by tau = cosh^2(pi (x + i d) / (2T)) onto the upper half
/// plane, the base onto tau < 0, the line below the tip (at dh / 2 by
/// symmetry) onto [0, tau_s], the pile's face onto [tau_s, 1] (tau_s =
/// cos^2(pi s / 2T)) and the drained top onto tau > 1. The head is linear
/// across the rectangle onto which dw = dtau / sqrt(tau (tau - tau_s)
/// (tau - 1)) maps that, so on the pile's downstream face at depth d
///   h(d) = (dh / 2) I(tau(d)) / I(tau_s),  I(tau) = integral from tau to 1 of |dw|,
/// and, with tau = tau_s + (1 - tau_s) sin^2(theta), I is the integral of
/// 2 dtheta / sqrt(tau) from theta(tau) to pi/2, smooth. (The same map gives
/// Harr's Q: the lengths of [0, tau_s] and [tau_s, 1] are 2K(m') and 2K(m).)
/// By symmetry the upstream face is at dh - h(d), so the thrust per metre
/// is the integral over 0..s of rho g (dh - 2 h(d)), N/m. Midpoint rules,
/// 4000 points in d (the tip's singularity, h ~ sqrt(s - d), leaves about
/// 1e-6 of the result) and 400 in theta (smooth: far below that).
inline double sheet_pile_thrust(double t, double s, double dh) {
  const double p = 1000.0 * 9.80665 * dh;
  const double pi = std::numbers::pi;
  const double tau_s = std::pow(std::cos(pi * s / (2.0 * t)), 2);
  auto integral = [&](double from) {  // I, from theta = from to pi/2
    constexpr int n = 400;
    const double step = (0.5 * pi - from) / n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double sn = std::sin(from + (i + 0.5) * step);
      sum += 2.0 * step / std::sqrt(tau_s + (1.0 - tau_s) * sn * sn);
    }
    return sum;
  };
  const double whole = integral(0.0);
  constexpr int n = 4000;
  double thrust = 0.0;
  for (int i = 0; i < n; ++i) {
    const double d = (i + 0.5) * s / n;
    const double tau = std::pow(std::cos(pi * d / (2.0 * t)), 2);
    const double theta = std::asin(std::sqrt((tau - tau_s) / (1.0 - tau_s)));
    const double downstream = 0.5 * p * integral(theta) / whole;
    thrust += (p - 2.0 * downstream) * s / n;
  }
  return thrust;
}

}  // namespace darcydem::testing
