#include "darcydem/particles/grading.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace darcydem {

template <int D>
GradingSummary grading_of(const std::vector<double>& radius) {
  if (radius.empty()) throw std::invalid_argument("grading_of: no grains");
  std::vector<double> d(radius.size());
  std::transform(radius.begin(), radius.end(), d.begin(), [](double r) { return 2.0 * r; });
  std::sort(d.begin(), d.end());
  double total = 0.0;
  for (double x : d) total += std::pow(x, D);
  GradingSummary g;
  g.d_min = d.front();
  g.d_max = d.back();
  // Walk up the sorted sizes; D_x is the first whose cumulative mass
  // fraction reaches x.
  const double wanted[4] = {0.1, 0.3, 0.5, 0.6};
  double* out[4] = {&g.d10, &g.d30, &g.d50, &g.d60};
  double finer = 0.0;
  std::size_t next = 0;
  for (std::size_t i = 0; i < d.size() && next < 4; ++i) {
    finer += std::pow(d[i], D);
    while (next < 4 && finer >= wanted[next] * total) *out[next++] = d[i];
  }
  for (; next < 4; ++next) *out[next] = d.back();  // round-off at the top
  return g;
}

template <int D>
std::string describe_grading(const std::vector<double>& radius) {
  if (radius.empty()) return "grains: none\n";
  const GradingSummary g = grading_of<D>(radius);
  if (g.d_max == g.d_min) return fmt::format("grains: all d = {:.4g} mm\n", g.d_min * 1e3);
  return fmt::format(
      "grains: d {:.4g} to {:.4g} mm; by mass D10 {:.4g}, D30 {:.4g}, D50 {:.4g}, D60 {:.4g} mm, Cu {:.3g}, "
      "Cc {:.3g}\n",
      g.d_min * 1e3, g.d_max * 1e3, g.d10 * 1e3, g.d30 * 1e3, g.d50 * 1e3, g.d60 * 1e3, g.uniformity(),
      g.curvature());
}

template GradingSummary grading_of<2>(const std::vector<double>&);
template GradingSummary grading_of<3>(const std::vector<double>&);
template std::string describe_grading<2>(const std::vector<double>&);
template std::string describe_grading<3>(const std::vector<double>&);

}  // namespace darcydem
