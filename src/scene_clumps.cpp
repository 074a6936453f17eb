// [[clump_template]] and the generators' `clump` key (scene_clumps.hpp).
#include "darcydem/scene/scene_clumps.hpp"

#include <fmt/format.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace darcydem {

template <int D>
std::pair<std::string, ClumpShape<D>> read_clump_template(TableReader& r) {
  const std::string name = r.string("name");
  const char* key = D == 2 ? "circles" : "spheres";
  const char* form = D == 2 ? "[x, y, r]" : "[x, y, z, r]";
  const toml::array* rows = r.optional_array(key);
  const std::string what = fmt::format(
      "a non-empty array of the clump's members, {} each (centre and radius, in any one unit: the clump is "
      "scaled to each grain it replaces)",
      form);
  if (rows == nullptr) r.missing(key, what);
  if (rows->empty()) r.fail(key, "must be " + what);
  std::vector<Vec<D>> centres;
  std::vector<double> radii;
  for (std::size_t i = 0; i < rows->size(); ++i) {
    const toml::array* row = (*rows)[i].as_array();
    bool ok = row != nullptr && row->size() == D + 1;
    std::array<double, D + 1> v{};
    for (std::size_t c = 0; ok && c < D + 1; ++c) {
      const auto x = (*row)[c].value<double>();
      ok = x.has_value() && std::isfinite(*x);
      if (ok) v[c] = *x;
    }
    if (!ok) r.fail(key, fmt::format("member {} must be {}, {} finite numbers", i + 1, form, D + 1));
    if (!(v[D] > 0.0)) r.fail(key, fmt::format("member {}: its radius must be > 0, got {}", i + 1, v[D]));
    Vec<D> x;
    for (int k = 0; k < D; ++k) x[k] = v[k];
    centres.push_back(x);
    radii.push_back(v[D]);
  }
  try {
    return {name, make_clump_shape<D>(centres, radii)};
  } catch (const std::invalid_argument& e) {
    r.fail(key, e.what());
  }
}

template <int D>
std::size_t add_clumps(TableReader& r, Simulation<D>& sim, const ClumpShape<D>& shape,
                       const Packing<D>& packing, std::uint16_t material, bool fixed,
                       const Vec<D>& velocity) {
  const std::string orientation = r.optional_choice("orientation", {"random", "aligned"}).value_or("random");
  const auto seed = r.optional_integer("orientation_seed").value_or(1);
  if (seed < 0) r.fail("orientation_seed", "must be an integer >= 0");
  if (r.has("orientation_seed") && orientation != "random")
    r.fail("orientation_seed", "seeds a random orientation; this generator's clumps are \"aligned\"");
  std::mt19937_64 rng(static_cast<std::uint64_t>(seed));
  const double density = sim.materials.at(material).density;
  const std::size_t before = sim.particles.size();
  for (std::size_t k = 0; k < packing.position.size(); ++k) {
    Orientation<D> q = ClumpShape<D>::identity_orientation();
    if (orientation == "random") q = random_orientation<D>(rng);
    sim.clumps.add(sim.particles, shape, packing.radius[k], packing.position[k], q, density, material, fixed,
                   velocity);
  }
  return sim.particles.size() - before;
}

template <int D>
std::size_t add_clumps_from_file(TableReader& r, Simulation<D>& sim, const Packing<D>& packing,
                                 std::uint16_t material, bool fixed, const Vec<D>& velocity) {
  const double density = sim.materials.at(material).density;
  std::size_t clumps = 0;
  const std::size_t n = packing.position.size();
  for (std::size_t row = 0; row < n;) {
    const std::int64_t c = packing.clump[row];
    if (c < 0) {
      sim.particles.add(packing.position[row], packing.radius[row], density, material, fixed, velocity);
      ++row;
      continue;
    }
    std::size_t end = row;
    while (end < n && packing.clump[end] == c) ++end;
    const std::vector<Vec<D>> centres(packing.position.begin() + static_cast<std::ptrdiff_t>(row),
                                      packing.position.begin() + static_cast<std::ptrdiff_t>(end));
    const std::vector<double> radii(packing.radius.begin() + static_cast<std::ptrdiff_t>(row),
                                    packing.radius.begin() + static_cast<std::ptrdiff_t>(end));
    try {
      const ClumpShape<D> shape = make_clump_shape<D>(centres, radii);
      // Placed as it stands, its members where the file has them.
      const auto [size, x] = clump_as_given<D>(shape, centres[0], radii[0]);
      sim.clumps.add(sim.particles, shape, size, x, ClumpShape<D>::identity_orientation(), density, material,
                     fixed, velocity);
    } catch (const std::invalid_argument& e) {
      r.fail("file", fmt::format("clump {} (its {} rows from particle {} of the file): {}", c, end - row, row,
                                 e.what()));
    }
    ++clumps;
    row = end;
  }
  return clumps;
}

template std::pair<std::string, ClumpShape<2>> read_clump_template<2>(TableReader&);
template std::pair<std::string, ClumpShape<3>> read_clump_template<3>(TableReader&);
template std::size_t add_clumps<2>(TableReader&, Simulation<2>&, const ClumpShape<2>&, const Packing<2>&,
                                   std::uint16_t, bool, const Vec<2>&);
template std::size_t add_clumps<3>(TableReader&, Simulation<3>&, const ClumpShape<3>&, const Packing<3>&,
                                   std::uint16_t, bool, const Vec<3>&);
template std::size_t add_clumps_from_file<2>(TableReader&, Simulation<2>&, const Packing<2>&, std::uint16_t,
                                             bool, const Vec<2>&);
template std::size_t add_clumps_from_file<3>(TableReader&, Simulation<3>&, const Packing<3>&, std::uint16_t,
                                             bool, const Vec<3>&);

}  // namespace darcydem
