#include "darcydem/core/vector_math.hpp"

#include <cmath>

#if defined(DARCYDEM_HAVE_LIBMVEC) && defined(__AVX2__)
#include <immintrin.h>
#define DARCYDEM_VECTOR_MATH 1
// glibc's AVX2 variant of atan2 (x86_64 vector function ABI name: 'd' =
// AVX2, N4 = four lanes, not masked, two vector arguments).
extern "C" __m256d _ZGVdN4vv_atan2(__m256d y, __m256d x);
extern "C" __m256d _ZGVdN4v_atan(__m256d x);
extern "C" __m256d _ZGVdN4v_exp(__m256d x);
extern "C" __m256d _ZGVdN4v_log(__m256d x);
#endif

namespace darcydem {

#ifdef DARCYDEM_VECTOR_MATH
namespace {

/// out = fn(a, b) four at a time; the tail through the same vector
/// function, so that a value does not depend on where it falls in a batch.
template <class Fn>
void apply_4(Fn fn, const double* a, const double* b, double* out, std::size_t n) {
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) _mm256_storeu_pd(out + i, fn(_mm256_loadu_pd(a + i), _mm256_loadu_pd(b + i)));
  if (i == n) return;
  alignas(32) double ta[4] = {1.0, 1.0, 1.0, 1.0};
  alignas(32) double tb[4] = {1.0, 1.0, 1.0, 1.0};
  alignas(32) double to[4];
  for (std::size_t k = 0; i + k < n; ++k) {
    ta[k] = a[i + k];
    tb[k] = b[i + k];
  }
  _mm256_store_pd(to, fn(_mm256_load_pd(ta), _mm256_load_pd(tb)));
  for (std::size_t k = 0; i + k < n; ++k) out[i + k] = to[k];
}

}  // namespace
#endif

void atan2_batch(const double* y, const double* x, double* out, std::size_t n) {
#ifdef DARCYDEM_VECTOR_MATH
  apply_4([](__m256d a, __m256d b) { return _ZGVdN4vv_atan2(a, b); }, y, x, out, n);
#else
  for (std::size_t i = 0; i < n; ++i) out[i] = std::atan2(y[i], x[i]);
#endif
}

void atan_batch(const double* x, double* out, std::size_t n) {
#ifdef DARCYDEM_VECTOR_MATH
  apply_4([](__m256d a, __m256d) { return _ZGVdN4v_atan(a); }, x, x, out, n);
#else
  for (std::size_t i = 0; i < n; ++i) out[i] = std::atan(x[i]);
#endif
}

void power_law_batch(const double* x, double e, double* out, std::size_t n) {
#ifdef DARCYDEM_VECTOR_MATH
  const __m256d exponent = _mm256_set1_pd(e);
  apply_4([exponent](__m256d a, __m256d) { return _ZGVdN4v_exp(_mm256_mul_pd(exponent, _ZGVdN4v_log(a))); },
          x, x, out, n);
#else
  for (std::size_t i = 0; i < n; ++i) out[i] = std::exp(e * std::log(x[i]));
#endif
}

bool vector_math_available() {
#ifdef DARCYDEM_VECTOR_MATH
  return true;
#else
  return false;
#endif
}

}  // namespace darcydem
