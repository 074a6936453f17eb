#include "darcydem/scene/scene_inlet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "darcydem/scene/scene_region.hpp"
#include "darcydem/scene/scene_sizes.hpp"

namespace darcydem {

template <int D>
Inlet<D> read_inlet(TableReader& r, std::uint16_t material, const Simulation<D>& sim,
                    const PoreFluid<D>* fluid, const std::vector<std::string>& names_so_far,
                    const ClumpShape<D>* clump) {
  Inlet<D> in;
  in.material = material;
  in.name = r.string("name");
  if (in.name.empty() || in.name.find_first_of(",\"\n") != std::string::npos)
    r.fail("name", "must be a non-empty name without commas or quotes");
  if (std::find(names_so_far.begin(), names_so_far.end(), in.name) != names_so_far.end())
    r.fail("name", fmt::format("inlet \"{}\" is defined twice", in.name));
  // A box, or a cylinder (its box the one that holds it).
  in.cylinder = read_cylinder<D>(r);
  std::vector<double> lo(D);
  std::vector<double> hi(D);
  for (int k = 0; k < D && in.cylinder; ++k) {
    lo[k] = in.cylinder->lower()[k];
    hi[k] = in.cylinder->upper()[k];
  }
  if (!in.cylinder) {
    lo = r.numbers("min", D);
    hi = r.numbers("max", D);
  }
  // A cylinder's refusals name its key.
  auto key = [&](const char* box_key) { return in.cylinder ? "cylinder" : box_key; };
  for (int k = 0; k < D; ++k) {
    if (!(std::isfinite(lo[k]) && std::isfinite(hi[k]) && hi[k] > lo[k])) {
      r.fail(key("max"),
             fmt::format("must be greater than 'min' along every axis (m); along {} min = {} and max = {}",
                         "xyz"[k], TableReader::format_number(lo[k]), TableReader::format_number(hi[k])));
    }
    in.lower[k] = lo[k];
    in.upper[k] = hi[k];
  }
  // How much: a count rate or a mass rate.
  if (r.has("rate") == r.has("mass_rate")) {
    r.fail(r.has("rate") ? "mass_rate" : "rate",
           r.has("rate") ? "give 'rate' (grains per second) or 'mass_rate' (kg/s), not both"
                         : fmt::format("is required: grains per second; or instead 'mass_rate', kg/s{}",
                                       D == 2 ? " per metre of thickness" : ""));
  }
  if (r.has("rate")) {
    in.rate = r.check("rate", r.number("rate"), is_positive, "> 0 grains per second");
  } else {
    in.mass_rate = r.check("mass_rate", r.number("mass_rate"), is_positive,
                           D == 2 ? "> 0 kg/s per metre of thickness" : "> 0 kg/s");
  }
  if (auto c = r.optional_integer("count")) {
    if (*c < 1) r.fail("count", "must be >= 1 (the most grains the inlet adds)");
    in.max_count = static_cast<std::uint64_t>(*c);
  }
  if (auto m = r.optional_number("mass")) {
    in.max_mass = r.check("mass", *m, is_positive, "> 0 kg (the most mass the inlet adds)");
  }
  in.interval = r.check("interval", r.number_or("interval", 0.01), is_positive, "> 0 s");
  // Each insertion may try this many places per grain while the box is
  // full, insertion after insertion: bounded so that a run cannot stall.
  in.max_attempts = r.optional_integer("max_attempts").value_or(1000);
  if (in.max_attempts < 1 || in.max_attempts > 1'000'000)
    r.fail("max_attempts", "must be in 1..1000000 (random places tried per grain at each insertion)");
  const auto seed = r.optional_integer("seed").value_or(1);
  in.rng.seed(static_cast<std::uint64_t>(seed));
  in.active = r.boolean_or("active", true);
  if (auto v = r.optional_numbers("velocity", D)) {
    for (int k = 0; k < D; ++k) in.velocity[k] = (*v)[k];
    if (!in.velocity.allFinite()) r.fail("velocity", "must be finite (m/s)");
  }
  if (clump != nullptr) {
    in.clump = *clump;
    in.clump_name = *r.optional_string("clump");
    in.aligned = r.optional_choice("orientation", {"random", "aligned"}).value_or("random") == "aligned";
  } else if (r.has("orientation")) {
    r.fail("orientation", "orients an inlet's clumps: give 'clump' too (a [[clump_template]]'s name)");
  }
  in.radii = read_radius(r, D);
  const double largest = in.radii.largest();
  for (int k = 0; k < D; ++k) {
    if (hi[k] - lo[k] <= 2.0 * largest) {
      r.fail(key("max"),
             fmt::format("the {} must be wider than the largest grain ({:.6g} m across) along every "
                         "axis; along {} it is {:.6g} m",
                         in.cylinder ? "cylinder" : "box", 2.0 * largest, "xyz"[k], hi[k] - lo[k]));
    }
  }
  r.finish();
  const auto& cell = sim.periodic;
  for (int k = 0; k < D; ++k) {
    if (!cell.periodic[k]) continue;
    const double end = cell.lower[k] + cell.length[k];
    if (lo[k] < cell.lower[k] || hi[k] > end) {
      r.fail(key(lo[k] < cell.lower[k] ? "min" : "max"),
             fmt::format("along the periodic axis {} the box must lie in the period [{}, {}]", "xyz"[k],
                         TableReader::format_number(cell.lower[k]), TableReader::format_number(end)));
    }
  }
  if (sim.has_domain) {
    for (int k = 0; k < D; ++k) {
      if (lo[k] < sim.domain_lower[k] || hi[k] > sim.domain_upper[k]) {
        const bool low = lo[k] < sim.domain_lower[k];
        r.fail(key(low ? "min" : "max"),
               fmt::format("the box must lie in the [domain] (allowed: {} {} {}): a grain placed outside it "
                           "would be removed at once",
                           low ? "min >=" : "max <=",
                           TableReader::format_number(low ? sim.domain_lower[k] : sim.domain_upper[k]),
                           std::string("along ") + "xyz"[k]));
      }
    }
  }
  if (fluid != nullptr) {
    // The grains must enter the water by moving: one appearing in a cell
    // would be a sudden compression of its pore water.
    const Vec<D> g_lo = fluid->grid.origin;
    const Vec<D> g_hi = fluid->grid.upper();
    const bool apart = box_beside<D>(in.lower, in.upper, g_lo, g_hi, cell);
    // A grain removed by the [domain] must have left the grid, as the
    // scene's grains must (read_domain): the margin holds this inlet's too.
    for (int k = 0; k < D && sim.has_domain; ++k) {
      if (cell.periodic[k]) continue;
      if (g_lo[k] - largest < sim.domain_lower[k] || g_hi[k] + largest > sim.domain_upper[k]) {
        const char* size_key = r.has("radius")       ? "radius"
                               : r.has("radius_max") ? "radius_max"
                               : r.has("radii")      ? "radii"
                                                     : "grading";
        r.fail(size_key,
               fmt::format(
                   "its largest grain's radius ({:.6g} m) must fit between the fluid grid, [{:.6g}, "
                   "{:.6g}] along {}, and the [domain]'s side, [{:.6g}, {:.6g}]: a grain removed while it "
                   "overlaps the grid would take its volume out of the pore water's balance",
                   largest, g_lo[k], g_hi[k], "xyz"[k], sim.domain_lower[k], sim.domain_upper[k]));
      }
    }
    if (!apart) {
      std::string grid;
      for (int k = 0; k < D; ++k)
        grid += fmt::format("{}{} in [{:.6g}, {:.6g}]", k == 0 ? "" : ", ", "xyz"[k], g_lo[k], g_hi[k]);
      r.fail(key("min"),
             fmt::format("the box must lie outside the fluid grid ({} m; beside it along an axis "
                         "that is not periodic): a grain that appeared in a cell would compress its "
                         "pore water at once, by K_f/n times its volume fraction; place the box above "
                         "the grid and let the grains fall in",
                         grid));
    }
  }
  return in;
}

template <int D>
std::pair<double, double> radius_range(const ParticleData<D>& particles,
                                       const std::vector<Inlet<D>>& inlets) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = 0.0;
  for (double r : particles.radius) {
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  for (const auto& in : inlets) {
    double smallest_member = 1.0;  // of the bounding radius
    if (in.clump) smallest_member = *std::min_element(in.clump->radius.begin(), in.clump->radius.end());
    lo = std::min(lo, in.radii.smallest() * smallest_member);
    hi = std::max(hi, in.radii.largest());
  }
  return {lo, hi};
}

template Inlet<2> read_inlet<2>(TableReader&, std::uint16_t, const Simulation<2>&, const PoreFluid<2>*,
                                const std::vector<std::string>&, const ClumpShape<2>*);
template Inlet<3> read_inlet<3>(TableReader&, std::uint16_t, const Simulation<3>&, const PoreFluid<3>*,
                                const std::vector<std::string>&, const ClumpShape<3>*);
template std::pair<double, double> radius_range<2>(const ParticleData<2>&, const std::vector<Inlet<2>>&);
template std::pair<double, double> radius_range<3>(const ParticleData<3>&, const std::vector<Inlet<3>>&);

}  // namespace darcydem
