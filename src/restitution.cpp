#include "darcydem/contact/restitution.hpp"

#include <cmath>
#include <stdexcept>

namespace darcydem {
namespace {

struct State {
  double x;
  double v;
};

double clamped_force(NormalLaw law, double gamma, double x, double v) {
  const double xp = x > 0.0 ? x : 0.0;
  double f = 0.0;
  if (law == NormalLaw::linear) {
    f = xp + gamma * v;
  } else {
    f = xp * std::sqrt(xp) + gamma * std::sqrt(std::sqrt(xp)) * v;
  }
  return f > 0.0 ? f : 0.0;
}

}  // namespace

double restitution_of_damping(NormalLaw law, double gamma) {
  // Classic RK4; the dimensionless contact lasts about pi (linear) or 3.2
  // (Hertz) time units, so h = 1e-4 gives errors far below 1e-6 in e.
  const double h = 1e-4;
  State s{0.0, 1.0};
  auto accel = [&](const State& q) { return -clamped_force(law, gamma, q.x, q.v); };
  for (int step = 0; step < 10'000'000; ++step) {
    const State k1{s.v, accel(s)};
    const State s2{s.x + 0.5 * h * k1.x, s.v + 0.5 * h * k1.v};
    const State k2{s2.v, accel(s2)};
    const State s3{s.x + 0.5 * h * k2.x, s.v + 0.5 * h * k2.v};
    const State k3{s3.v, accel(s3)};
    const State s4{s.x + h * k3.x, s.v + h * k3.v};
    const State k4{s4.v, accel(s4)};
    const State next{s.x + h / 6.0 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x),
                     s.v + h / 6.0 * (k1.v + 2 * k2.v + 2 * k3.v + k4.v)};
    if (next.x <= 0.0) {
      // Interpolate the exit speed linearly at x = 0.
      const double w = s.x / (s.x - next.x);
      return -(s.v + w * (next.v - s.v));
    }
    // Once the clamped force vanishes while unloading it stays zero (the
    // spring term falls faster than the damping term), so the particle leaves
    // with its present speed.
    if (next.v < 0.0 && clamped_force(law, gamma, next.x, next.v) == 0.0) {
      return -next.v;
    }
    s = next;
  }
  throw std::runtime_error("restitution_of_damping: impact did not end");
}

double damping_for_restitution(NormalLaw law, double e) {
  if (!(e > 0.0 && e <= 1.0)) {
    throw std::invalid_argument("restitution must be in (0, 1]");
  }
  if (e == 1.0) {
    return 0.0;
  }
  double lo = 0.0;  // e(0) = 1 > target
  double hi = 1.0;
  while (restitution_of_damping(law, hi) > e) {
    hi *= 2.0;
  }
  for (int it = 0; it < 40 && (hi - lo) > 1e-10 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (restitution_of_damping(law, mid) > e) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace darcydem
