// FluidGrid's runs of interior faces (face_run), against the cell and face
// indices computed coordinate by coordinate (index, face_index).
#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "darcydem/fluid/fluid_grid.hpp"

namespace darcydem {
namespace {

/// Every interior face normal to `axis`, as (lower cell, face index), from
/// the runs; each must come exactly once.
template <int D>
std::map<std::size_t, std::size_t> faces_from_runs(const FluidGrid<D>& grid, int axis) {
  std::map<std::size_t, std::size_t> faces;
  for (std::size_t r = 0; r < grid.face_runs(axis); ++r) {
    const auto run = grid.face_run(axis, r);
    for (std::size_t j = 0; j < run.count; ++j) {
      const bool fresh = faces.emplace(run.cell + j, run.face + j).second;
      EXPECT_TRUE(fresh) << "cell " << run.cell + j << " twice along axis " << axis;
    }
  }
  return faces;
}

/// The same by walking all cells: the face between c and its upper
/// neighbour is the lower face of that neighbour.
template <int D>
std::map<std::size_t, std::size_t> faces_by_coordinates(const FluidGrid<D>& grid, int axis) {
  std::map<std::size_t, std::size_t> faces;
  for (std::size_t c = 0; c < grid.size(); ++c) {
    auto cc = grid.coords(c);
    if (cc[axis] + 1 >= grid.cells[axis]) continue;
    auto up = cc;
    ++up[axis];
    EXPECT_EQ(grid.index(up), c + grid.stride(axis));
    faces.emplace(c, grid.face_index(axis, up));
  }
  return faces;
}

template <int D>
void expect_runs_match(const std::array<int, D>& cells) {
  FluidGrid<D> grid;
  grid.cells = cells;
  for (int axis = 0; axis < D; ++axis) {
    SCOPED_TRACE(testing::Message() << "axis " << axis);
    EXPECT_EQ(faces_from_runs(grid, axis), faces_by_coordinates(grid, axis));
  }
}

TEST(FluidGrid, FaceRunsVisitEveryInteriorFaceOnceWithItsIndex) {
  expect_runs_match<3>({5, 4, 3});
  expect_runs_match<3>({1, 6, 2});  // one cell wide along x: no x faces
  expect_runs_match<3>({3, 1, 7});
  expect_runs_match<2>({7, 5});
  expect_runs_match<2>({1, 25});  // the paper's column
}

}  // namespace
}  // namespace darcydem
