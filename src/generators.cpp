#include "darcydem/generation/generators.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>

#include <fmt/format.h>

#include "darcydem/core/periodic_cell.hpp"

namespace darcydem {

RadiusDistribution RadiusDistribution::grading(std::vector<double> diameters, std::vector<double> passing,
                                               int weight_exponent) {
  const std::size_t m = diameters.size();
  if (m < 2 || passing.size() != m) {
    throw std::invalid_argument("a grading needs at least two sieves, with a passing fraction for each");
  }
  if (weight_exponent < 0) throw std::invalid_argument("a grading's weight exponent must be >= 0");
  for (std::size_t i = 0; i < m; ++i) {
    if (!(diameters[i] > 0.0) || !std::isfinite(diameters[i]) ||
        (i > 0 && !(diameters[i] > diameters[i - 1]))) {
      throw std::invalid_argument("a grading's diameters must be positive, finite and increasing");
    }
    if (!(passing[i] >= 0.0 && passing[i] <= 1.0) || (i > 0 && passing[i] < passing[i - 1])) {
      throw std::invalid_argument("a grading's passing fractions must lie in [0, 1] and never decrease");
    }
  }
  if (passing.front() != 0.0 || passing.back() != 1.0) {
    throw std::invalid_argument(
        "a grading's passing fraction must be 0 at the first sieve and 1 at the last");
  }
  RadiusDistribution d;
  d.kind = Kind::grading;
  d.weight_exponent = weight_exponent;
  // Between sieves a and b the weighted fraction dP is spread evenly in
  // log d, a density dP / ln(b/a) / d; the number of grains is that over
  // d^p, so the interval holds dP / ln(b/a) * (a^-p - b^-p) / p of them
  // (dP itself for p = 0), in units of d_0^-p to stay in range.
  const double p = weight_exponent;
  double total = 0.0;
  d.interval_cumulative.resize(m - 1);
  for (std::size_t i = 0; i + 1 < m; ++i) {
    const double dp = passing[i + 1] - passing[i];
    double count = dp;
    if (p > 0.0 && dp > 0.0) {
      const double a = diameters[i] / diameters[0];
      const double b = diameters[i + 1] / diameters[0];
      count = dp / std::log(b / a) * (std::pow(a, -p) - std::pow(b, -p)) / p;
    }
    total += count;
    d.interval_cumulative[i] = total;
  }
  for (double& c : d.interval_cumulative) c /= total;
  d.interval_cumulative.back() = 1.0;
  d.diameters = std::move(diameters);
  d.passing = std::move(passing);
  return d;
}

double RadiusDistribution::passing_diameter(double x) const {
  if (kind != Kind::grading) throw std::logic_error("passing_diameter: not a grading curve");
  std::size_t i = 1;
  while (i + 1 < passing.size() && passing[i] < x) ++i;
  const double p0 = passing[i - 1];
  const double p1 = passing[i];
  if (!(p1 > p0)) return diameters[i];
  const double t = std::clamp((x - p0) / (p1 - p0), 0.0, 1.0);
  return diameters[i - 1] * std::pow(diameters[i] / diameters[i - 1], t);
}

double RadiusDistribution::largest() const {
  switch (kind) {
    case Kind::constant:
      return value;
    case Kind::uniform:
      return max;
    case Kind::table:
      return *std::max_element(radii.begin(), radii.end());
    case Kind::grading: {
      // The first sieve that everything passes.
      const auto all = std::find(passing.begin(), passing.end(), 1.0);
      return 0.5 * diameters[static_cast<std::size_t>(all - passing.begin())];
    }
  }
  return value;
}

double RadiusDistribution::smallest() const {
  switch (kind) {
    case Kind::constant:
      return value;
    case Kind::uniform:
      return min;
    case Kind::table: {
      double r = largest();
      for (std::size_t k = 0; k < radii.size(); ++k) {
        if (fractions[k] > 0.0) r = std::min(r, radii[k]);
      }
      return r;
    }
    case Kind::grading: {
      // The last sieve that nothing passes.
      const auto none = std::find_if(passing.begin(), passing.end(), [](double p) { return p > 0.0; });
      return 0.5 * diameters[static_cast<std::size_t>(none - passing.begin()) - 1];
    }
  }
  return value;
}

double RadiusDistribution::sample(std::mt19937_64& rng) const {
  switch (kind) {
    case Kind::constant:
      return value;
    case Kind::uniform:
      return min + (max - min) * unit_random(rng);
    case Kind::table: {
      const double u = unit_random(rng);
      double acc = 0.0;
      for (std::size_t k = 0; k < radii.size(); ++k) {
        acc += fractions[k];
        if (u < acc) return radii[k];
      }
      return radii.back();
    }
    case Kind::grading: {
      // An interval by its number fraction, then d in it from the density
      // d^-(p+1) by its inverse distribution (log-uniform for p = 0).
      const double u = unit_random(rng);
      std::size_t i = 0;
      while (i + 1 < interval_cumulative.size() && !(u < interval_cumulative[i])) ++i;
      const double a = diameters[i];
      const double b = diameters[i + 1];
      const double v = unit_random(rng);
      if (weight_exponent == 0) return 0.5 * a * std::pow(b / a, v);
      const double p = weight_exponent;
      const double x = std::pow(1.0 - v * (1.0 - std::pow(a / b, p)), -1.0 / p);
      return 0.5 * std::min(a * x, b);
    }
  }
  return value;
}

/// Calls f(idx) for every index of an n[0] x ... x n[D-1] block of cells,
/// the first axis fastest.
template <int D, class F>
void for_each_cell_index(const std::array<int, D>& n, F&& f) {
  std::int64_t total = 1;
  for (int k = 0; k < D; ++k) total *= n[k];
  std::array<int, D> idx{};
  for (std::int64_t c = 0; c < total; ++c) {
    std::int64_t rest = c;
    for (int k = 0; k < D; ++k) {
      idx[k] = static_cast<int>(rest % n[k]);
      rest /= n[k];
    }
    f(idx);
  }
}

template <int D>
Packing<D> lattice_packing(const Vec<D>& lo, const Vec<D>& hi, double spacing, double radius) {
  Packing<D> out;
  std::array<int, D> n{};
  for (int k = 0; k < D; ++k) {
    const double span = hi[k] - lo[k] - 2.0 * radius;
    n[k] = span < 0.0 ? 0 : static_cast<int>(std::floor(span / spacing + 1e-9)) + 1;
  }
  for_each_cell_index<D>(n, [&](const std::array<int, D>& idx) {
    Vec<D> x;
    for (int k = 0; k < D; ++k) x[k] = lo[k] + radius + idx[k] * spacing;
    out.position.push_back(x);
    out.radius.push_back(radius);
  });
  return out;
}

template <int D>
Packing<D> dense_lattice_packing(const Vec<D>& lo, const Vec<D>& hi, double spacing, double radius) {
  // A rectangular cell (2D: a by a sqrt(3); 3D: a cube of edge a sqrt(2))
  // and its basis, in units of the cell.
  std::vector<Vec<D>> basis;
  Vec<D> cell;
  if constexpr (D == 2) {
    cell = Vec<D>(spacing, spacing * std::sqrt(3.0));
    basis = {Vec<D>(0.0, 0.0), Vec<D>(0.5, 0.5)};
  } else {
    cell = Vec<D>::Constant(spacing * std::sqrt(2.0));
    basis = {Vec<D>(0.0, 0.0, 0.0), Vec<D>(0.5, 0.5, 0.0), Vec<D>(0.5, 0.0, 0.5), Vec<D>(0.0, 0.5, 0.5)};
  }
  const Vec<D> first = lo + Vec<D>::Constant(radius);
  const Vec<D> last = hi - Vec<D>::Constant(radius);
  // A centre within 1e-9 of a spacing outside the box still counts, as in
  // lattice_packing (the box's edges are usually multiples of it).
  const double slack = 1e-9 * spacing;
  std::array<int, D> n{};
  for (int k = 0; k < D; ++k) {
    const double span = last[k] - first[k];
    n[k] = span < -slack ? 0 : static_cast<int>(std::floor((span + slack) / cell[k])) + 1;
  }
  std::vector<Vec<D>> centres;
  for_each_cell_index<D>(n, [&](const std::array<int, D>& idx) {
    for (const auto& b : basis) {
      Vec<D> x;
      bool inside = true;
      for (int k = 0; k < D; ++k) {
        x[k] = first[k] + (idx[k] + b[k]) * cell[k];
        inside = inside && x[k] <= last[k] + slack;
      }
      if (inside) centres.push_back(x);
    }
  });
  // By height, then along y (3D), then x.
  std::sort(centres.begin(), centres.end(), [](const Vec<D>& a, const Vec<D>& b) {
    for (int k = D - 1; k >= 0; --k) {
      if (a[k] != b[k]) return a[k] < b[k];
    }
    return false;
  });
  Packing<D> out;
  out.position = std::move(centres);
  out.radius.assign(out.position.size(), radius);
  return out;
}

template <int D>
Packing<D> column_packing(const Vec<D>& base, const Vec<D>& axis, int count, double radius, double gap) {
  Packing<D> out;
  const Vec<D> a = axis.normalized();
  for (int i = 0; i < count; ++i) {
    out.position.push_back(base + a * (radius + i * (2.0 * radius + gap)));
    out.radius.push_back(radius);
  }
  return out;
}

namespace {

/// Random sequential addition into [lo, hi] of `count` particles whose
/// radii `next_radius()` gives in turn (none above r_max), positions from
/// `rng`. Along an axis that `wrap` marks the box is a period: centres
/// anywhere in [lo, hi), distances to the nearest image. `what_to_change`
/// ends the message when one finds no room.
template <int D, class NextRadius>
Packing<D> place_randomly(const Vec<D>& lo, const Vec<D>& hi, const std::array<bool, D>& wrap,
                          std::int64_t count, double r_max, NextRadius&& next_radius, std::mt19937_64& rng,
                          std::int64_t max_attempts, std::string_view what_to_change,
                          const Cylinder<D>* cylinder) {
  Packing<D> out;
  // Search cells at least 2 r_max wide; along a period a whole number of
  // them fills it, so that the cells wrap.
  std::array<std::int64_t, D> dims{};
  Vec<D> width;
  const Vec<D> length = hi - lo;
  for (int k = 0; k < D; ++k) {
    const double n = length[k] / (2.0 * r_max);
    dims[k] = std::max<std::int64_t>(1, static_cast<std::int64_t>(wrap[k] ? std::floor(n) : std::ceil(n)));
    width[k] = wrap[k] ? length[k] / static_cast<double>(dims[k]) : 2.0 * r_max;
  }
  auto cell_of = [&](const Vec<D>& x, int k) {
    return std::clamp<std::int64_t>(static_cast<std::int64_t>((x[k] - lo[k]) / width[k]), 0, dims[k] - 1);
  };
  PeriodicCell<D> period;
  for (int k = 0; k < D; ++k) {
    if (wrap[k]) period.set_axis(k, lo[k], hi[k]);
  }
  auto flat = [&](const std::array<std::int64_t, D>& c) {
    std::int64_t f = c[D - 1];
    for (int k = D - 2; k >= 0; --k) f = f * dims[k] + c[k];
    return f;
  };
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid;
  for (std::int64_t made = 0; made < count; ++made) {
    const double r = next_radius();
    bool placed = false;
    for (std::int64_t attempt = 0; attempt < max_attempts && !placed; ++attempt) {
      Vec<D> x;
      if (cylinder != nullptr) {
        x = cylinder->sample(r, rng);
      } else {
        for (int k = 0; k < D; ++k) {
          x[k] = wrap[k] ? lo[k] + length[k] * unit_random(rng)
                         : lo[k] + r + (length[k] - 2.0 * r) * unit_random(rng);
        }
      }
      x = period.wrap(x);  // a centre rounded up to the period's end
      std::array<std::int64_t, D> c{};
      for (int k = 0; k < D; ++k) c[k] = cell_of(x, k);
      bool free = true;
      std::array<std::int64_t, D> o{};
      const int neighbours = (D == 2) ? 9 : 27;
      for (int m = 0; m < neighbours && free; ++m) {
        int rest = m;
        bool inside = true;
        for (int k = 0; k < D; ++k) {
          o[k] = c[k] + (rest % 3) - 1;
          rest /= 3;
          if (wrap[k]) o[k] = (o[k] + dims[k]) % dims[k];
          inside = inside && o[k] >= 0 && o[k] < dims[k];
        }
        if (!inside) continue;
        auto it = grid.find(flat(o));
        if (it == grid.end()) continue;
        for (std::uint32_t j : it->second) {
          const double reach = r + out.radius[j];
          if (period.shortest(out.position[j] - x).squaredNorm() < reach * reach) {
            free = false;
            break;
          }
        }
      }
      if (free) {
        grid[flat(c)].push_back(static_cast<std::uint32_t>(out.position.size()));
        out.position.push_back(x);
        out.radius.push_back(r);
        placed = true;
      }
    }
    if (!placed) {
      throw std::runtime_error(fmt::format(
          "random packing: no room for particle {} of {} after {} attempts (the {} is too full; "
          "{})",
          made + 1, count, max_attempts, cylinder != nullptr ? "cylinder" : "box", what_to_change));
    }
  }
  return out;
}

}  // namespace

template <int D>
Packing<D> random_packing(const Vec<D>& lo, const Vec<D>& hi, std::int64_t count,
                          const RadiusDistribution& radii, std::uint64_t seed, std::int64_t max_attempts,
                          const std::array<bool, D>& wrap, const Cylinder<D>* cylinder) {
  std::mt19937_64 rng(seed);
  const std::string_view change = "enlarge it, reduce the count, or raise max_attempts";
  if (radii.kind != RadiusDistribution::Kind::grading) {
    // Each size drawn just before its place, as always (the same packings).
    return place_randomly<D>(
        lo, hi, wrap, count, radii.largest(), [&] { return radii.sample(rng); }, rng, max_attempts, change,
        cylinder);
  }
  // A grading's sizes are drawn first and placed largest first.
  std::vector<double> drawn(static_cast<std::size_t>(count));
  for (double& r : drawn) r = radii.sample(rng);
  std::sort(drawn.begin(), drawn.end(), std::greater<>());
  std::size_t next = 0;
  return place_randomly<D>(
      lo, hi, wrap, count, radii.largest(), [&] { return drawn[next++]; }, rng, max_attempts, change,
      cylinder);
}

template <int D>
Packing<D> random_packing_to_porosity(const Vec<D>& lo, const Vec<D>& hi, double porosity,
                                      const RadiusDistribution& radii, std::uint64_t seed,
                                      std::int64_t max_attempts, const std::array<bool, D>& wrap,
                                      const Cylinder<D>* cylinder) {
  std::mt19937_64 rng(seed);
  double box = 1.0;
  for (int k = 0; k < D; ++k) box *= hi[k] - lo[k];
  if (cylinder != nullptr) box = cylinder->volume();
  const double target = (1.0 - porosity) * box;
  // Draw until the grains' volume reaches the target; keep the last one
  // only if that brings the volume nearer to it.
  std::vector<double> drawn;
  double solid = 0.0;
  while (solid < target) {
    const double r = radii.sample(rng);
    const double v = particle_volume<D>(r);
    if (solid + v - target > target - solid) break;
    drawn.push_back(r);
    solid += v;
  }
  if (drawn.empty()) {
    throw std::runtime_error(fmt::format(
        "a porosity of {} leaves room for less than half of the first grain drawn (of {:.4g} m^3) in "
        "the box's {:.4g} m^3; lower it, or enlarge the box",
        porosity, particle_volume<D>(radii.sample(rng)), box));
  }
  std::sort(drawn.begin(), drawn.end(), std::greater<>());
  std::size_t next = 0;
  const std::string change = fmt::format(
      "random sequential addition fills at most about {} % of a box; raise the porosity, settle a looser "
      "cloud "
      "under gravity, or raise max_attempts",
      D == 3 ? 38 : 54);
  return place_randomly<D>(
      lo, hi, wrap, static_cast<std::int64_t>(drawn.size()), radii.largest(), [&] { return drawn[next++]; },
      rng, max_attempts, change, cylinder);
}

template <int D>
Vec<D> Cylinder<D>::lower() const {
  Vec<D> lo = centre - Vec<D>::Constant(radius);
  if constexpr (D == 3) lo[axis] = centre[axis] - 0.5 * length;
  return lo;
}

template <int D>
Vec<D> Cylinder<D>::upper() const {
  Vec<D> hi = centre + Vec<D>::Constant(radius);
  if constexpr (D == 3) hi[axis] = centre[axis] + 0.5 * length;
  return hi;
}

template <int D>
double Cylinder<D>::volume() const {
  const double area = std::numbers::pi * radius * radius;
  return D == 3 ? area * length : area;
}

template <int D>
Vec<D> Cylinder<D>::sample(double r, std::mt19937_64& rng) const {
  // Across: uniform over the disc of radius R - r (the square root of a
  // uniform number for the distance); along (3D): uniform.
  const double rho = (radius - r) * std::sqrt(unit_random(rng));
  const double theta = 2.0 * std::numbers::pi * unit_random(rng);
  Vec<D> x = centre;
  if constexpr (D == 2) {
    x[0] += rho * std::cos(theta);
    x[1] += rho * std::sin(theta);
  } else {
    const int a = (axis + 1) % 3;
    const int b = (axis + 2) % 3;
    x[a] += rho * std::cos(theta);
    x[b] += rho * std::sin(theta);
    x[axis] += (unit_random(rng) - 0.5) * (length - 2.0 * r);
  }
  return x;
}

template struct Cylinder<2>;
template struct Cylinder<3>;

template <int D>
Packing<D> read_packing_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the particle file", path));
  Packing<D> out;
  std::string line;
  int line_no = 0;
  bool header = true;
  bool clumps = false;
  std::int64_t last_clump = -1;
  std::vector<std::uint8_t> clump_done;  // a clump whose rows have ended
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (header) {
      header = false;
      const std::string want = D == 2 ? "x,y,radius" : "x,y,z,radius";
      std::string got;
      for (auto& c : cells) {
        c.erase(std::remove_if(c.begin(), c.end(), ::isspace), c.end());
        got += (got.empty() ? "" : ",") + c;
      }
      clumps = got == want + ",clump";
      if (got != want && !clumps) {
        throw std::runtime_error(fmt::format("{}:{}: the header must be '{}' or '{},clump', got '{}'", path,
                                             line_no, want, want, got));
      }
      continue;
    }
    const std::size_t columns = clumps ? D + 2 : D + 1;
    if (cells.size() != columns) {
      throw std::runtime_error(fmt::format("{}:{}: expected {} comma-separated numbers, got {}", path,
                                           line_no, columns, cells.size()));
    }
    if (clumps) {
      std::int64_t c = -2;
      std::size_t used = 0;
      try {
        c = std::stoll(cells[D + 1], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      while (used < cells[D + 1].size() && std::isspace(static_cast<unsigned char>(cells[D + 1][used])))
        ++used;
      if (used == 0 || used != cells[D + 1].size() || c < -1) {
        throw std::runtime_error(fmt::format(
            "{}:{}: the clump column must be an integer >= 0 (the particle's clump) or -1 (none), got '{}'",
            path, line_no, cells[D + 1]));
      }
      if (c != last_clump && last_clump >= 0) clump_done[static_cast<std::size_t>(last_clump)] = 1;
      if (c >= 0) {
        const auto k = static_cast<std::size_t>(c);
        if (k >= clump_done.size()) clump_done.resize(k + 1, 0);
        if (clump_done[k] != 0) {
          throw std::runtime_error(fmt::format(
              "{}:{}: clump {} began on an earlier row and other rows came between: a clump's members must "
              "be on consecutive rows",
              path, line_no, c));
        }
      }
      last_clump = c;
      out.clump.push_back(c);
    }
    Vec<D> x;
    double r = 0.0;
    try {
      for (int k = 0; k < D; ++k) x[k] = std::stod(cells[k]);
      r = std::stod(cells[D]);
    } catch (const std::exception&) {
      throw std::runtime_error(fmt::format("{}:{}: not a number in '{}'", path, line_no, line));
    }
    if (!(r > 0.0) || !x.allFinite()) {
      throw std::runtime_error(
          fmt::format("{}:{}: radius must be > 0 and coordinates finite", path, line_no));
    }
    out.position.push_back(x);
    out.radius.push_back(r);
  }
  if (header) throw std::runtime_error(fmt::format("{}: the file is empty", path));
  return out;
}

template <int D>
void write_packing_csv(const std::string& path, const ParticleData<D>& p, const std::string& comment,
                       const std::vector<std::int32_t>* clump_of) {
  const std::vector<std::size_t> by_id = p.creation_order();
  std::string text;
  std::stringstream lines(comment);
  std::string line;
  while (std::getline(lines, line)) text += "# " + line + "\n";
  const bool clumps = clump_of != nullptr && clump_of->size() == p.size();
  text += D == 2 ? "x,y,radius" : "x,y,z,radius";
  text += clumps ? ",clump\n" : "\n";
  for (std::size_t i : by_id) {
    for (int k = 0; k < D; ++k) text += fmt::format("{:.17g},", p.position[i][k]);
    text += fmt::format("{:.17g}", p.radius[i]);
    text += clumps ? fmt::format(",{}\n", (*clump_of)[i]) : "\n";
  }
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the particle file", path));
}

#define DARCYDEM_INSTANTIATE(D)                                                                             \
  template Packing<D> lattice_packing<D>(const Vec<D>&, const Vec<D>&, double, double);                     \
  template Packing<D> dense_lattice_packing<D>(const Vec<D>&, const Vec<D>&, double, double);               \
  template Packing<D> column_packing<D>(const Vec<D>&, const Vec<D>&, int, double, double);                 \
  template Packing<D> random_packing<D>(const Vec<D>&, const Vec<D>&, std::int64_t,                         \
                                        const RadiusDistribution&, std::uint64_t, std::int64_t,             \
                                        const std::array<bool, D>&, const Cylinder<D>*);                    \
  template Packing<D> random_packing_to_porosity<D>(const Vec<D>&, const Vec<D>&, double,                   \
                                                    const RadiusDistribution&, std::uint64_t, std::int64_t, \
                                                    const std::array<bool, D>&, const Cylinder<D>*);        \
  template Packing<D> read_packing_csv<D>(const std::string&);                                              \
  template void write_packing_csv<D>(const std::string&, const ParticleData<D>&, const std::string&,        \
                                     const std::vector<std::int32_t>*);
DARCYDEM_INSTANTIATE(2)
DARCYDEM_INSTANTIATE(3)
#undef DARCYDEM_INSTANTIATE

}  // namespace darcydem
