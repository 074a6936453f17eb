#pragma once
// Particle generators: regular lattice, a single column, random
// non-overlapping packing in a box, and a CSV file.
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "darcydem/core/vec.hpp"
#include "darcydem/particles/particle_data.hpp"

namespace darcydem {

struct RadiusDistribution {
  enum class Kind { constant, uniform, table, grading };
  Kind kind = Kind::constant;
  double value = 0.0;  ///< constant radius, m
  double min = 0.0;    ///< uniform range, m
  double max = 0.0;
  std::vector<double> radii;      ///< table of sizes, m
  std::vector<double> fractions;  ///< number fractions of the table (sum 1)
  /// Grading curve (Kind::grading, made by `grading()`): sieve diameters
  /// d_0 < ... < d_m, m, and the fraction passing each, 0 at d_0 to 1 at
  /// d_m, never decreasing; between two sieves the fraction passing is
  /// linear in log d, as a grading curve is drawn on its semi-log chart.
  std::vector<double> diameters;
  std::vector<double> passing;
  /// The power of d the passing fraction weighs the grains by: the
  /// dimension for a grading by mass (a sphere's mass goes as d^3, a disc's
  /// of unit thickness as d^2), 0 for a grading by number.
  int weight_exponent = 0;
  /// Cumulative number fractions of the grains in each interval between
  /// sieves, worked out by `grading()`.
  std::vector<double> interval_cumulative;

  /// A grading curve; throws std::invalid_argument unless diameters are
  /// positive and increasing, passing runs from 0 to 1 without decreasing,
  /// the two have the same length >= 2 and weight_exponent >= 0.
  static RadiusDistribution grading(std::vector<double> diameters, std::vector<double> passing,
                                    int weight_exponent);

  /// A grading's D_x: the diameter the curve passes x (in (0, 1]) at,
  /// read between sieves linearly in log d; the first such for a flat part.
  [[nodiscard]] double passing_diameter(double x) const;
  [[nodiscard]] double largest() const;
  /// The smallest radius that can be drawn, m.
  [[nodiscard]] double smallest() const;
  [[nodiscard]] double sample(std::mt19937_64& rng) const;
};

/// Uniform double in [0, 1) from 53 random bits (portable across libraries).
inline double unit_random(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

template <int D>
struct Packing {
  std::vector<Vec<D>> position;
  std::vector<double> radius;
  /// From a file with a `clump` column: each particle's clump (-1: none);
  /// empty otherwise.
  std::vector<std::int64_t> clump;
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

/// A cylinder that a random cloud or an inlet fills instead of a box
/// (3D: standing along `axis`, `length` long; 2D: a circle, `axis` and
/// `length` unused): a mould, a triaxial cell, a drum.
template <int D>
struct Cylinder {
  Vec<D> centre = Vec<D>::Zero();  ///< m, its middle
  double radius = 0.0;             ///< m
  int axis = D - 1;
  double length = 0.0;  ///< m (3D)

  /// The box that holds it.
  [[nodiscard]] Vec<D> lower() const;
  [[nodiscard]] Vec<D> upper() const;
  /// m^3 (2D: its area times 1 m).
  [[nodiscard]] double volume() const;
  /// A centre drawn uniformly among those of a ball of radius r wholly
  /// inside it (r below its radius and, 3D, half its length).
  [[nodiscard]] Vec<D> sample(double r, std::mt19937_64& rng) const;
};

/// Random sequential addition of `count` non-overlapping particles inside the
/// box [lo, hi]. Throws std::runtime_error when `max_attempts` tries per
/// particle do not find room. With a grading curve every size is drawn
/// first and the largest grains are placed first, so that a wide grading
/// fits (the sizes drawn are the same; only the order of placing changes).
/// Along an axis that `wrap` marks, [lo, hi) is a period: the centres lie
/// anywhere in it and grains may straddle its ends, kept apart from each
/// other's nearest image (a cloud filling a [periodic] cell).
/// With `cylinder` the particles fill it instead ([lo, hi] its box, no
/// axis wrapped).
template <int D>
Packing<D> random_packing(const Vec<D>& lo, const Vec<D>& hi, std::int64_t count,
                          const RadiusDistribution& radii, std::uint64_t seed, std::int64_t max_attempts,
                          const std::array<bool, D>& wrap = {}, const Cylinder<D>* cylinder = nullptr);

/// The same, with as many particles as bring the grains' volume nearest to
/// (1 - porosity) of the box's (spheres; in 2D discs of unit thickness over
/// the box's area x 1 m): sizes drawn until the volume reaches it, the last
/// kept only if that is nearer, so the volume is off by at most half a
/// grain; then placed largest first. Random sequential addition jams at a
/// solid fraction of about 0.38 (spheres) or 0.55 (discs) of equal grains,
/// so a lower porosity throws std::runtime_error. `wrap` as above.
/// With `cylinder`, of the cylinder's volume.
template <int D>
Packing<D> random_packing_to_porosity(const Vec<D>& lo, const Vec<D>& hi, double porosity,
                                      const RadiusDistribution& radii, std::uint64_t seed,
                                      std::int64_t max_attempts, const std::array<bool, D>& wrap = {},
                                      const Cylinder<D>* cylinder = nullptr);

/// Reads `x,y[,z],radius` rows (a header line naming the columns first),
/// or `x,y[,z],radius,clump`: the clump (an integer >= 0) each particle is
/// a member of, -1 for none, a clump's members on consecutive rows.
/// Throws std::runtime_error naming the file and line on a bad row.
template <int D>
Packing<D> read_packing_csv(const std::string& path);

/// Writes the particles' centres and radii as read_packing_csv reads them,
/// in creation order (ParticleData::id), to 17 significant digits (read
/// back exactly); with `clump_of` (each particle's clump, -1 for none; not
/// empty) a `clump` column too. `comment` goes first as '#' lines. Throws
/// std::runtime_error if the file cannot be written.
template <int D>
void write_packing_csv(const std::string& path, const ParticleData<D>& particles, const std::string& comment,
                       const std::vector<std::int32_t>* clump_of = nullptr);

}  // namespace darcydem
