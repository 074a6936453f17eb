#pragma once
// Loops over particles that run in parallel (OpenMP) only when there are
// enough of them to pay for the threads: entering an OpenMP region costs a
// few microseconds even with an if() clause, which dominates the step of a
// small system (the paper's 50-disc column takes millions of steps).
#include <algorithm>
#include <cstdint>

namespace darcydem {

inline constexpr std::int64_t parallel_threshold = 2000;

/// body(i) for i in [0, n), statically scheduled (each index to a fixed thread).
template <class F>
void for_each_index(std::int64_t n, F&& body) {
  if (n > parallel_threshold) {
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) body(i);
  } else {
    for (std::int64_t i = 0; i < n; ++i) body(i);
  }
}

/// body(i) for i in [0, n), dynamically scheduled in chunks (uneven work).
template <class F>
void for_each_index_dynamic(std::int64_t n, F&& body) {
  if (n > parallel_threshold) {
#pragma omp parallel for schedule(dynamic, 512)
    for (std::int64_t i = 0; i < n; ++i) body(i);
  } else {
    for (std::int64_t i = 0; i < n; ++i) body(i);
  }
}

/// The largest of 0 and value(i) for i in [0, n), statically scheduled across the
/// threads when n > threshold (a caller whose index is a group of particles
/// passes parallel_threshold over the group's size).
template <class F>
double max_over_index(std::int64_t n, std::int64_t threshold, F&& value) {
  double largest = 0.0;
  if (n > threshold) {
#pragma omp parallel for schedule(static) reduction(max : largest)
    for (std::int64_t i = 0; i < n; ++i) largest = std::max(largest, value(i));
  } else {
    for (std::int64_t i = 0; i < n; ++i) largest = std::max(largest, value(i));
  }
  return largest;
}

}  // namespace darcydem
