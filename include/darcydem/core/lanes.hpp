#pragma once
// Four doubles at a time, as a GCC/Clang vector (AVX2 registers with
// -march=native, pairs of SSE2 registers otherwise), and the few helpers
// that let one template serve a double and four lanes: arithmetic, the
// comparisons and `mask ? a : b` are the language's for both.
//
// A lane computes what the same formula computes on a double, up to where
// the compiler fuses a multiply and an add (GCC does so in either, not
// always at the same places): code that needs one answer for every
// element runs every element through the same path.
#include <cmath>
#include <cstdint>
#include <cstring>

namespace darcydem {

using Lanes = double __attribute__((vector_size(32)));
using LaneMask = std::int64_t __attribute__((vector_size(32)));
inline constexpr int lane_count = 4;

inline Lanes load_lanes(const double* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store_lanes(double* p, Lanes v) { std::memcpy(p, &v, sizeof v); }

inline double lane_sqrt(double x) { return std::sqrt(x); }
inline Lanes lane_sqrt(Lanes x) {
  Lanes r;
  for (int l = 0; l < lane_count; ++l) r[l] = std::sqrt(x[l]);
  return r;
}

/// std::max's choice (a < b ? b : a), for doubles or four lanes (either
/// argument may be a double that stands for four equal lanes).
template <class A, class B>
inline auto lane_max(A a, B b) {
  return a < b ? b : a;
}

}  // namespace darcydem
