#pragma once
// Elementary functions over arrays, for the hot loops that need many of
// them at once (the exact grain/cell overlaps need several atan2 per grain).
// With AVX2 and glibc's vector math library (libmvec, glibc >= 2.35) four
// values are computed at a time; otherwise the scalar std:: function.
// libmvec's results are within a few ulp of std::atan2 (tested), not
// bitwise the same; a given build always takes the same path, so runs stay
// reproducible.
#include <cstddef>

namespace darcydem {

/// out[i] = atan2(y[i], x[i]) for i in [0, n).
void atan2_batch(const double* y, const double* x, double* out, std::size_t n);

/// out[i] = atan(x[i]) for i in [0, n).
void atan_batch(const double* x, double* out, std::size_t n);

/// out[i] = x[i]^e as exp(e ln x[i]) for x[i] > 0, i in [0, n): about
/// twice as fast as the vector library's pow, for a power law in a hot
/// loop. The rounding of e ln x is amplified by |e ln x|, so the
/// relative error is within (4 + 5 |e ln x|) ulp (tested), not pow's few
/// ulp; x[i] = 0 gives 0 for e > 0.
void power_law_batch(const double* x, double e, double* out, std::size_t n);

/// True when atan2_batch uses the vector library (for the benchmark's log).
[[nodiscard]] bool vector_math_available();

}  // namespace darcydem
