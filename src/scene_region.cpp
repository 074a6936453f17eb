// A random cloud's or an inlet's `cylinder` (scene_region.hpp).
#include "darcydem/scene/scene_region.hpp"

#include <cmath>

#include <fmt/format.h>

namespace darcydem {

template <int D>
std::optional<Cylinder<D>> read_cylinder(TableReader& r) {
  const toml::table* t = r.optional_table("cylinder");
  if (t == nullptr) return std::nullopt;  // optional_table refuses a value that is not a table
  for (const char* key : {"min", "max"}) {
    if (r.has(key))
      r.fail(key, "the grains go in the 'cylinder'; give it or 'min' and 'max' (a box), not both");
  }
  TableReader c(*t, r.where() + " cylinder", r.file());
  Cylinder<D> cyl;
  const auto centre = c.numbers("centre", D);
  for (int k = 0; k < D; ++k) cyl.centre[k] = centre[k];
  if (!cyl.centre.allFinite()) c.fail("centre", "must be finite (m)");
  cyl.radius = c.check(
      "radius", c.number("radius"), [](double v) { return v > 0.0 && std::isfinite(v); }, "> 0 m");
  if constexpr (D == 3) {
    const std::string axis = c.optional_choice("axis", {"x", "y", "z"}).value_or("z");
    cyl.axis = axis[0] - 'x';
    cyl.length = c.check(
        "length", c.number("length"), [](double v) { return v > 0.0 && std::isfinite(v); },
        "> 0 m (along its axis, centred on 'centre')");
  }
  c.finish();
  return cyl;
}

template std::optional<Cylinder<2>> read_cylinder<2>(TableReader&);
template std::optional<Cylinder<3>> read_cylinder<3>(TableReader&);

}  // namespace darcydem
