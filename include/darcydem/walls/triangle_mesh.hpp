#pragma once
// A triangulated surface for a mesh wall (3D): YADE's facets imported from
// an STL file, PFC's wall made from a geometry. Its vertices are kept in the
// wall's own frame (relative to Wall::point, along Wall::axes), so that the
// wall moves and turns without touching them. Facets are filed in a uniform
// grid of bins over the mesh's bounding box, so that the facets near a
// point are found without visiting all of them.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "darcydem/core/vec.hpp"

namespace darcydem {

struct TriangleMesh {
  std::vector<Vec<3>> vertex;  ///< m, in the wall's own frame
  std::vector<std::array<std::uint32_t, 3>> triangle;
  std::vector<Vec<3>> facet_normal;  ///< unit, right-handed about the vertex order
  double bounding_radius = 0.0;      ///< m, the farthest vertex from the frame's origin

  /// Computes the facets' normals, the bounding radius and the bins.
  /// Returns an empty string, or why the mesh cannot be used (no facets, a
  /// vertex index out of range, a facet of zero area, a vertex not finite).
  [[nodiscard]] std::string finish();

  /// Removes the facets of no area (corners in a line, to round-off: the
  /// slivers a CAD program's tessellation leaves in STL files); returns how
  /// many. Call before finish().
  std::size_t drop_slivers();

  /// The point of facet f nearest to x (both in the wall's own frame).
  [[nodiscard]] Vec<3> closest_point(std::size_t f, const Vec<3>& x) const;

  /// The facets whose bounding boxes come within `reach` of x (own frame),
  /// each once, in increasing order.
  void facets_near(const Vec<3>& x, double reach, std::vector<std::uint32_t>& out) const;

  /// The facet nearest to x (own frame) and its distance, m.
  struct Nearest {
    std::uint32_t facet = 0;
    double distance = 0.0;
  };
  [[nodiscard]] Nearest nearest(const Vec<3>& x) const;

  /// Facet f's area and the total, m^2.
  [[nodiscard]] double facet_area(std::size_t f) const;
  [[nodiscard]] double area() const;

 private:
  Vec<3> bin_origin_ = Vec<3>::Zero();
  double bin_size_ = 1.0;
  std::array<int, 3> bins_{1, 1, 1};
  std::vector<std::uint32_t> bin_offset_;  ///< CSR over the bins
  std::vector<std::uint32_t> bin_facet_;
};

/// Reads an STL file, ASCII or binary, scaled by `scale` (its units to m).
/// Vertices that coincide in the file become one. Throws std::runtime_error
/// naming the file (and for ASCII the line) when it cannot be read.
TriangleMesh read_stl(const std::string& path, double scale);

}  // namespace darcydem
