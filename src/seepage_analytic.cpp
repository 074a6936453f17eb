#include "darcydem/analysis/seepage_analytic.hpp"

#include <cmath>
#include <numbers>

namespace darcydem {
namespace {
constexpr double pi = std::numbers::pi;
constexpr int max_terms = 200000;
}  // namespace

double seepage_pressure(const SeepageColumnParameters& p, double depth, double time) {
  if (time <= 0.0) return 0.0;
  const double h = p.height;
  const double tv = p.consolidation_coefficient() * time / (h * h);
  double sum = 0.0;
  for (int m = 0; m < max_terms; ++m) {
    const double k = 2.0 * m + 1.0;
    const double decay = std::exp(-k * k * pi * pi * tv / 4.0);
    const double term = 8.0 / (pi * pi * k * k) * std::sin(k * pi * depth / (2.0 * h)) * decay;
    sum += (m % 2 == 0 ? term : -term);
    if (decay < 1e-18) break;
  }
  return p.steady_bottom_pressure() * (depth / h - sum);
}

double seepage_uplift(const SeepageColumnParameters& p, double time) {
  if (time <= 0.0) return 0.0;
  const double h = p.height;
  const double tv = p.consolidation_coefficient() * time / (h * h);
  double sum = 0.0;
  for (int m = 0; m < max_terms; ++m) {
    const double k = 2.0 * m + 1.0;
    const double decay = std::exp(-k * k * pi * pi * tv / 4.0);
    const double term = 32.0 / (pi * pi * pi * k * k * k) * decay;
    sum += (m % 2 == 0 ? term : -term);
    if (decay < 1e-18) break;
  }
  return p.final_uplift() * (1.0 - sum);
}

}  // namespace darcydem
