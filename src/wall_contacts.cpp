#include <algorithm>
#include <cmath>
#include <limits>

#include "darcydem/neighbour/verlet_list.hpp"
#include "darcydem/walls/wall.hpp"

namespace darcydem {

template <int D>
void WallContactList<D>::build(const std::vector<Vec<D>>& position, const std::vector<double>& radius,
                               std::vector<Wall<D>>& walls, double skin, bool keep_rolling,
                               const std::vector<std::uint32_t>* old_index) {
  const std::size_t n = position.size();
  std::vector<std::uint32_t> next_offset(n + 1, 0);
  std::vector<std::uint16_t> next_wall;
  std::vector<std::uint32_t> next_facet;
  std::vector<Vec<D>> next_tangential;
  std::vector<AngVec<D>> next_rolling;
  const bool have_old = old_list_fits(offset.size(), n, old_index);
  const bool old_rolling = keep_rolling && rolling.size() == wall.size();
  std::vector<std::uint32_t> near;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t o = old_index != nullptr ? (*old_index)[i] : i;
    // A candidate, with the history it had at the last build.
    auto add = [&](std::size_t w, std::uint32_t f) {
      next_wall.push_back(static_cast<std::uint16_t>(w));
      next_facet.push_back(f);
      Vec<D> t = Vec<D>::Zero();
      AngVec<D> r = AngVec<D>::Zero();
      if (have_old && o != no_old_index) {
        for (std::uint32_t k = offset[o]; k < offset[o + 1]; ++k) {
          if (wall[k] == w && facet[k] == f) {
            t = tangential[k];
            if (old_rolling) r = rolling[k];
          }
        }
      }
      next_tangential.push_back(t);
      if (keep_rolling) next_rolling.push_back(r);
    };
    const double reach = radius[i] + skin;
    for (std::size_t w = 0; w < walls.size(); ++w) {
      const Wall<D>& wall_w = walls[w];
      if constexpr (D == 3) {
        if (wall_w.is_mesh()) {
          // Each facet within reach, in the mesh's own frame.
          const Vec<D> local = wall_w.to_local(position[i]);
          wall_w.mesh->facets_near(local, reach, near);
          for (auto f : near) {
            if (wall_w.facet_touch_local(local, f).gap < reach) add(w, f);
          }
          continue;
        }
      }
      if (wall_w.gap(position[i]) < reach) add(w, 0);
    }
    next_offset[i + 1] = static_cast<std::uint32_t>(next_wall.size());
  }
  offset = std::move(next_offset);
  wall = std::move(next_wall);
  facet = std::move(next_facet);
  tangential = std::move(next_tangential);
  rolling = std::move(next_rolling);
  force_on_particle.assign(wall.size(), Vec<D>::Zero());
  torque_on_particle.assign(wall.size(), AngVec<D>::Zero());
  for (auto& w : walls) {
    w.mark_build();
    // A turning plane sweeps further the further out it is: its reach.
    if (w.is_plane()) {
      double far2 = 0.0;
      if (w.spin != 0.0) {
        for (const auto& x : position) far2 = std::max(far2, (x - w.pivot).squaredNorm());
      }
      w.reach = w.spin != 0.0 ? std::sqrt(far2) + skin : std::numeric_limits<double>::infinity();
    }
  }
}

template struct WallContactList<2>;
template struct WallContactList<3>;

}  // namespace darcydem
