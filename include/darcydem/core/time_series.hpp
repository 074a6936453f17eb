#pragma once
// A value given in time: a fluid boundary's pressure or inflow, a servo's
// target load.
#include <vector>

namespace darcydem {

/// A value that varies in time: piecewise linear through (times, values),
/// held constant before the first and after the last point. Times count
/// from `start` (the start of the stage that set it).
struct TimeSeries {
  std::vector<double> times{0.0};
  std::vector<double> values{0.0};
  double start = 0.0;  ///< s

  [[nodiscard]] double at(double t) const {
    const double s = t - start;
    if (s <= times.front()) return values.front();
    for (std::size_t i = 1; i < times.size(); ++i) {
      if (s <= times[i]) {
        const double f = (s - times[i - 1]) / (times[i] - times[i - 1]);
        return values[i - 1] + f * (values[i] - values[i - 1]);
      }
    }
    return values.back();
  }
  static TimeSeries constant(double v) { return TimeSeries{{0.0}, {v}, 0.0}; }
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(times, values, start);
  }
};

}  // namespace darcydem
