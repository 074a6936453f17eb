#include "darcydem/analysis/seepage_analytic.hpp"

#include <cmath>
#include <numbers>

namespace darcydem {
namespace {
constexpr double pi = std::numbers::pi;
constexpr int max_terms = 200000;

/// sum over m of s^m term(k) exp(-k^2 pi^2 Tv / 4), k = 2m + 1, with s = -1
/// (alternating) or +1, until the exponential falls below 1e-18.
template <class Term>
double series(const SeepageColumnParameters& p, double time, Term&& term, bool alternating = true) {
  const double tv = p.consolidation_coefficient() * time / (p.height * p.height);
  double sum = 0.0;
  for (int m = 0; m < max_terms; ++m) {
    const double k = 2.0 * m + 1.0;
    const double decay = std::exp(-k * k * pi * pi * tv / 4.0);
    sum += (m % 2 == 0 || !alternating ? 1.0 : -1.0) * term(k) * decay;
    if (decay < 1e-18) break;
  }
  return sum;
}
}  // namespace

double seepage_pressure(const SeepageColumnParameters& p, double depth, double time) {
  if (time <= 0.0) return 0.0;
  const double h = p.height;
  const double sum = series(
      p, time, [&](double k) { return 8.0 / (pi * pi * k * k) * std::sin(k * pi * depth / (2.0 * h)); });
  return p.steady_bottom_pressure() * (depth / h - sum);
}

double seepage_uplift(const SeepageColumnParameters& p, double time) {
  if (time <= 0.0) return 0.0;
  const double sum = series(p, time, [](double k) { return 32.0 / (pi * pi * pi * k * k * k); });
  return p.final_uplift() * (1.0 - sum);
}

double consolidation_degree(const SeepageColumnParameters& p, double time) {
  if (time <= 0.0) return 0.0;
  const double b = p.undrained_share();
  return 1.0 - b * series(
                       p, time, [](double k) { return 8.0 / (pi * pi * k * k); }, false);
}

double consolidation_pressure(const SeepageColumnParameters& p, double stress, double distance, double time) {
  const double b = p.undrained_share();
  if (time <= 0.0) return distance > 0.0 ? b * stress : 0.0;
  const double h = p.height;
  return b * stress *
         series(
             p, time, [&](double k) { return 4.0 / (pi * k) * std::sin(k * pi * distance / (2.0 * h)); },
             false);
}

}  // namespace darcydem
