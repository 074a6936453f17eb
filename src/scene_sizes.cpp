#include "darcydem/scene/scene_sizes.hpp"

#include <cmath>

#include <fmt/format.h>

namespace darcydem {
namespace {

/// A `grading = { diameters, passing, by }` table: a grading curve by mass
/// (the default, as a sieve analysis gives it) or by number.
RadiusDistribution read_grading(TableReader& r, const toml::table& t, int dimension) {
  TableReader g(t, r.where() + " grading", r.file());
  const std::vector<double> diameters = g.number_list("diameters");
  const std::vector<double> passing = g.number_list("passing");
  const std::string by = g.optional_choice("by", {"mass", "number"}).value_or("mass");
  g.finish();
  if (diameters.size() < 2) g.fail("diameters", "needs at least two sieve diameters (m), smallest first");
  if (passing.size() != diameters.size()) {
    g.fail("passing", fmt::format("needs one fraction per diameter: {} diameters, {} fractions",
                                  diameters.size(), passing.size()));
  }
  for (std::size_t i = 0; i < diameters.size(); ++i) {
    g.check("diameters", diameters[i], is_positive, "> 0 m");
    if (i > 0 && !(diameters[i] > diameters[i - 1])) {
      g.fail("diameters",
             fmt::format("must increase, smallest first; element {} ({}) is not above element {} ({})", i + 1,
                         TableReader::format_number(diameters[i]), i,
                         TableReader::format_number(diameters[i - 1])));
    }
    g.check(
        "passing", passing[i], [](double v) { return v >= 0.0 && v <= 1.0; },
        "fractions in [0, 1] (not percent)");
    if (i > 0 && passing[i] < passing[i - 1]) {
      g.fail("passing",
             fmt::format("must never decrease (the fraction finer than each diameter); element {} ({}) "
                         "is below element {} ({})",
                         i + 1, TableReader::format_number(passing[i]), i,
                         TableReader::format_number(passing[i - 1])));
    }
  }
  if (passing.front() != 0.0 || passing.back() != 1.0) {
    g.fail(
        "passing",
        fmt::format("must be 0 at the smallest diameter and 1 at the largest (nothing finer than the "
                    "first sieve, everything finer than the last); got {} and {}",
                    TableReader::format_number(passing.front()), TableReader::format_number(passing.back())));
  }
  return RadiusDistribution::grading(diameters, passing, by == "mass" ? dimension : 0);
}

}  // namespace

RadiusDistribution read_radius(TableReader& r, int dimension) {
  r.allow({"radius", "radius_min", "radius_max", "radii", "fractions", "grading"});
  // Exactly one way of giving the sizes: a second one would be ignored.
  const std::vector<std::pair<std::string_view, bool>> ways = {
      {"radius", r.has("radius")},
      {"radius_min", r.has("radius_min") || r.has("radius_max")},
      {"radii", r.has("radii") || r.has("fractions")},
      {"grading", r.has("grading")}};
  std::string_view first;
  for (const auto& [key, given] : ways) {
    if (!given) continue;
    if (!first.empty()) {
      r.fail(key == "radius_min" && !r.has("radius_min") ? "radius_max" : key,
             fmt::format("give the sizes one way only; '{}' is given too", first));
    }
    first = key;
  }
  RadiusDistribution d;
  if (r.has("radius")) {
    d.kind = RadiusDistribution::Kind::constant;
    d.value = r.check("radius", r.number("radius"), is_positive, "> 0 m");
  } else if (r.has("radius_min") || r.has("radius_max")) {
    d.kind = RadiusDistribution::Kind::uniform;
    d.min = r.check("radius_min", r.number("radius_min"), is_positive, "> 0 m");
    d.max = r.number("radius_max");
    r.check(
        "radius_max", d.max, [&](double v) { return v >= d.min; }, ">= radius_min");
  } else if (r.has("radii") || r.has("fractions")) {
    d.kind = RadiusDistribution::Kind::table;
    d.radii = r.number_list("radii");
    d.fractions = r.number_list("fractions");
    if (d.fractions.size() != d.radii.size()) {
      r.fail("fractions", "must have as many entries as 'radii'");
    }
    double sum = 0.0;
    for (double f : d.fractions) sum += r.check("fractions", f, is_non_negative, ">= 0");
    for (double x : d.radii) r.check("radii", x, is_positive, "> 0 m");
    if (std::abs(sum - 1.0) > 1e-9)
      r.fail("fractions", fmt::format("must add up to 1, they add up to {}", sum));
  } else if (const toml::table* t = r.optional_table("grading")) {
    d = read_grading(r, *t, dimension);
  } else {
    r.fail_table(
        "needs a size: 'radius' (constant), 'radius_min' and 'radius_max' (uniform), "
        "'radii' with 'fractions' (a table of sizes by number), or 'grading' (a grading curve: "
        "{ diameters = [...], passing = [...], by = \"mass\" or \"number\" })");
  }
  return d;
}

}  // namespace darcydem
