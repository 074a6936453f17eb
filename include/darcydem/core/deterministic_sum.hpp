#pragma once
// Parallel sums whose result does not depend on the number of threads: the
// range is cut into fixed blocks, each block is summed in order, and the
// block sums are added in order.
#include <cstdint>
#include <vector>

namespace darcydem {

template <class F>
double deterministic_sum(std::int64_t n, F&& term) {
  constexpr std::int64_t block = 4096;
  const std::int64_t blocks = (n + block - 1) / block;
  std::vector<double> partial(static_cast<std::size_t>(blocks), 0.0);
#pragma omp parallel for schedule(static) if (blocks > 1)
  for (std::int64_t b = 0; b < blocks; ++b) {
    double s = 0.0;
    const std::int64_t end = (b + 1) * block < n ? (b + 1) * block : n;
    for (std::int64_t i = b * block; i < end; ++i) s += term(i);
    partial[b] = s;
  }
  double total = 0.0;
  for (double s : partial) total += s;
  return total;
}

/// The same for any value with + (an Eigen vector or matrix): `zero` is
/// the sum of nothing.
template <class T, class F>
T deterministic_sum(std::int64_t n, const T& zero, F&& term) {
  constexpr std::int64_t block = 4096;
  const std::int64_t blocks = (n + block - 1) / block;
  std::vector<T> partial(static_cast<std::size_t>(blocks), zero);
#pragma omp parallel for schedule(static) if (blocks > 1)
  for (std::int64_t b = 0; b < blocks; ++b) {
    T s = zero;
    const std::int64_t end = (b + 1) * block < n ? (b + 1) * block : n;
    for (std::int64_t i = b * block; i < end; ++i) s += term(i);
    partial[static_cast<std::size_t>(b)] = s;
  }
  T total = zero;
  for (const T& s : partial) total += s;
  return total;
}

}  // namespace darcydem
