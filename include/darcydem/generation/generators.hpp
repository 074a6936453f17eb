#pragma once
// Particle generators: regular lattice, a single column, random
// non-overlapping packing in a box, and a CSV file.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "darcydem/core/vec.hpp"
#include "darcydem/particles/particle_data.hpp"

namespace darcydem {

struct RadiusDistribution {
  enum class Kind { constant, uniform, table };
  Kind kind = Kind::constant;
  double value = 0.0;  ///< constant radius, m
  double min = 0.0;    ///< uniform range, m
  double max = 0.0;
  std::vector<double> radii;      ///< table of sizes, m
  std::vector<double> fractions;  ///< number fractions of the table (sum 1)

  [[nodiscard]] double largest() const;
  [[nodiscard]] double sample(std::mt19937_64& rng) const;
};

/// Uniform double in [0, 1) from 53 random bits (portable across libraries).
inline double unit_random(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

template <int D>
struct Packing {
  std::vector<Vec<D>> position;
  std::vector<double> radius;
};

/// Centres of a square (2D) or cubic (3D) lattice of the given spacing whose
/// particles of radius r lie inside [lo, hi].
template <int D>
Packing<D> lattice_packing(const Vec<D>& lo, const Vec<D>& hi, double spacing, double radius);

/// The densest regular arrangement with nearest centres `spacing` apart:
/// hexagonal in 2D (rows along x, every other row shifted by half a
/// spacing), face-centred cubic in 3D (a cubic cell of edge sqrt(2) spacing
/// with four centres); the particles of radius r inside [lo, hi], in order of
/// height, then y, then x.
template <int D>
Packing<D> dense_lattice_packing(const Vec<D>& lo, const Vec<D>& hi, double spacing, double radius);

/// `count` particles stacked along `axis` from `base` (the point the lowest
/// particle rests on), centre to centre 2r + gap.
template <int D>
Packing<D> column_packing(const Vec<D>& base, const Vec<D>& axis, int count, double radius, double gap);

/// Random sequential addition of `count` non-overlapping particles inside the
/// box [lo, hi]. Throws std::runtime_error when `max_attempts` tries per
/// particle do not find room.
template <int D>
Packing<D> random_packing(const Vec<D>& lo, const Vec<D>& hi, std::int64_t count,
                          const RadiusDistribution& radii, std::uint64_t seed, std::int64_t max_attempts);

/// Reads `x,y[,z],radius` rows (a header line naming the columns first).
/// Throws std::runtime_error naming the file and line on a bad row.
template <int D>
Packing<D> read_packing_csv(const std::string& path);

/// Writes the particles' centres and radii as read_packing_csv reads them,
/// in creation order (ParticleData::id), to 17 significant digits (read
/// back exactly); `comment` goes first as '#' lines. Throws
/// std::runtime_error if the file cannot be written.
template <int D>
void write_packing_csv(const std::string& path, const ParticleData<D>& particles, const std::string& comment);

}  // namespace darcydem
