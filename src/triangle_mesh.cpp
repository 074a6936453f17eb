#include "darcydem/walls/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

namespace darcydem {

namespace {
/// Whether a facet has no area worth the name: its normal below round-off
/// of its longest edge squared.
bool is_sliver(const Vec<3>& a, const Vec<3>& b, const Vec<3>& c) {
  const Vec<3> n = cross(Vec<3>(b - a), Vec<3>(c - a));
  const double scale = std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (c - b).squaredNorm()});
  return !(n.norm() > 1e-12 * scale);
}
}  // namespace

std::size_t TriangleMesh::drop_slivers() {
  const std::size_t before = triangle.size();
  std::erase_if(triangle, [&](const std::array<std::uint32_t, 3>& t) {
    return t[0] < vertex.size() && t[1] < vertex.size() && t[2] < vertex.size() &&
           is_sliver(vertex[t[0]], vertex[t[1]], vertex[t[2]]);
  });
  return before - triangle.size();
}

std::string TriangleMesh::finish() {
  if (triangle.empty()) return "it has no facets";
  if (vertex.size() >= std::numeric_limits<std::uint32_t>::max()) return "it has too many vertices";
  for (std::size_t v = 0; v < vertex.size(); ++v) {
    if (!vertex[v].allFinite()) return fmt::format("vertex {} is not finite", v);
  }
  facet_normal.assign(triangle.size(), Vec<3>::Zero());
  Vec<3> lo = Vec<3>::Constant(std::numeric_limits<double>::infinity());
  Vec<3> hi = -lo;
  double size_sum = 0.0;
  for (std::size_t f = 0; f < triangle.size(); ++f) {
    for (auto v : triangle[f]) {
      if (v >= vertex.size())
        return fmt::format("facet {} uses vertex {}, but there are {} vertices (numbered from 0)", f, v,
                           vertex.size());
    }
    const Vec<3>& a = vertex[triangle[f][0]];
    const Vec<3>& b = vertex[triangle[f][1]];
    const Vec<3>& c = vertex[triangle[f][2]];
    // A sliver thinner than round-off has no normal worth the name.
    if (is_sliver(a, b, c)) return fmt::format("facet {} has no area (its corners are in a line)", f);
    facet_normal[f] = cross(Vec<3>(b - a), Vec<3>(c - a)).normalized();
    const Vec<3> flo = a.cwiseMin(b).cwiseMin(c);
    const Vec<3> fhi = a.cwiseMax(b).cwiseMax(c);
    lo = lo.cwiseMin(flo);
    hi = hi.cwiseMax(fhi);
    size_sum += (fhi - flo).maxCoeff();
  }
  bounding_radius = 0.0;
  for (const auto& v : vertex) bounding_radius = std::max(bounding_radius, v.norm());
  // Bins about a facet's size, at most 64 along the longest side.
  const double extent = (hi - lo).maxCoeff();
  bin_size_ = std::max(extent / 64.0, size_sum / static_cast<double>(triangle.size()));
  bin_origin_ = lo;
  for (int k = 0; k < 3; ++k)
    bins_[k] = std::max(1, static_cast<int>(std::ceil((hi[k] - lo[k]) / bin_size_)));
  const std::size_t nbins = static_cast<std::size_t>(bins_[0]) * bins_[1] * bins_[2];
  std::vector<std::vector<std::uint32_t>> filed(nbins);
  auto bin_of = [&](const Vec<3>& x, int k) {
    return std::clamp(static_cast<int>(std::floor((x[k] - bin_origin_[k]) / bin_size_)), 0, bins_[k] - 1);
  };
  for (std::size_t f = 0; f < triangle.size(); ++f) {
    const Vec<3>& a = vertex[triangle[f][0]];
    const Vec<3>& b = vertex[triangle[f][1]];
    const Vec<3>& c = vertex[triangle[f][2]];
    const Vec<3> flo = a.cwiseMin(b).cwiseMin(c);
    const Vec<3> fhi = a.cwiseMax(b).cwiseMax(c);
    for (int i = bin_of(flo, 0); i <= bin_of(fhi, 0); ++i)
      for (int j = bin_of(flo, 1); j <= bin_of(fhi, 1); ++j)
        for (int k = bin_of(flo, 2); k <= bin_of(fhi, 2); ++k)
          filed[(static_cast<std::size_t>(k) * bins_[1] + j) * bins_[0] + i].push_back(
              static_cast<std::uint32_t>(f));
  }
  bin_offset_.assign(nbins + 1, 0);
  bin_facet_.clear();
  for (std::size_t b = 0; b < nbins; ++b) {
    bin_facet_.insert(bin_facet_.end(), filed[b].begin(), filed[b].end());
    bin_offset_[b + 1] = static_cast<std::uint32_t>(bin_facet_.size());
  }
  return {};
}

// The nearest point of a triangle to x, by the region of the triangle's
// plane x projects into: a corner's, an edge's or the face's (barycentric
// coordinates from the dot products of the edges with x's offsets).
Vec<3> TriangleMesh::closest_point(std::size_t f, const Vec<3>& x) const {
  const Vec<3>& a = vertex[triangle[f][0]];
  const Vec<3>& b = vertex[triangle[f][1]];
  const Vec<3>& c = vertex[triangle[f][2]];
  const Vec<3> ab = b - a;
  const Vec<3> ac = c - a;
  const Vec<3> ax = x - a;
  const double d1 = ab.dot(ax);
  const double d2 = ac.dot(ax);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec<3> bx = x - b;
  const double d3 = ab.dot(bx);
  const double d4 = ac.dot(bx);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Vec<3> cx = x - c;
  const double d5 = ab.dot(cx);
  const double d6 = ac.dot(cx);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return b + w * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  return a + (vb * denom) * ab + (vc * denom) * ac;
}

void TriangleMesh::facets_near(const Vec<3>& x, double reach, std::vector<std::uint32_t>& out) const {
  out.clear();
  std::array<int, 3> lo{};
  std::array<int, 3> hi{};
  for (int k = 0; k < 3; ++k) {
    const double a = std::floor((x[k] - reach - bin_origin_[k]) / bin_size_);
    const double b = std::floor((x[k] + reach - bin_origin_[k]) / bin_size_);
    if (b < 0.0 || a > bins_[k] - 1.0) return;  // beyond the mesh's box
    lo[k] = static_cast<int>(std::max(a, 0.0));
    hi[k] = static_cast<int>(std::min(b, bins_[k] - 1.0));
  }
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const std::size_t b = (static_cast<std::size_t>(k) * bins_[1] + j) * bins_[0] + i;
        out.insert(out.end(), bin_facet_.begin() + bin_offset_[b], bin_facet_.begin() + bin_offset_[b + 1]);
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

TriangleMesh::Nearest TriangleMesh::nearest(const Vec<3>& x) const {
  Nearest best{0, std::numeric_limits<double>::infinity()};
  auto visit = [&](std::uint32_t f) {
    const double d = (x - closest_point(f, x)).norm();
    if (d < best.distance) best = {f, d};
  };
  // Facets within a growing reach: once the nearest found is within the
  // reach, no facet outside it can be nearer.
  const Vec<3> top = bin_origin_ + bin_size_ * Vec<3>(bins_[0], bins_[1], bins_[2]);
  const double span = (x - bin_origin_).cwiseAbs().cwiseMax((x - top).cwiseAbs()).norm();
  std::vector<std::uint32_t> near;
  for (double reach = bin_size_; reach < span; reach *= 2.0) {
    facets_near(x, reach, near);
    for (auto f : near) visit(f);
    if (best.distance <= reach) return best;
  }
  for (std::size_t f = 0; f < triangle.size(); ++f) visit(static_cast<std::uint32_t>(f));
  return best;
}

double TriangleMesh::facet_area(std::size_t f) const {
  const auto& t = triangle[f];
  return 0.5 * cross(Vec<3>(vertex[t[1]] - vertex[t[0]]), Vec<3>(vertex[t[2]] - vertex[t[0]])).norm();
}

double TriangleMesh::area() const {
  double sum = 0.0;
  for (std::size_t f = 0; f < triangle.size(); ++f) sum += facet_area(f);
  return sum;
}

namespace {

/// Files each corner once: coinciding corners (as read) are one vertex.
struct VertexPool {
  std::map<std::array<double, 3>, std::uint32_t> index;
  TriangleMesh mesh;
  std::uint32_t add(double x, double y, double z, double scale) {
    const std::array<double, 3> key{x, y, z};
    const auto [it, fresh] = index.try_emplace(key, static_cast<std::uint32_t>(mesh.vertex.size()));
    if (fresh) mesh.vertex.emplace_back(scale * x, scale * y, scale * z);
    return it->second;
  }
};

TriangleMesh read_binary_stl(const std::string& path, const std::string& bytes, double scale) {
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  VertexPool pool;
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* rec = bytes.data() + 84 + 50 * static_cast<std::size_t>(t);
    std::array<std::uint32_t, 3> tri{};
    for (int c = 0; c < 3; ++c) {
      float xyz[3];
      std::memcpy(xyz, rec + 12 + 12 * c, 12);
      if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
        throw std::runtime_error(
            fmt::format("{}: facet {} has a corner that is not a finite number", path, t));
      tri[c] = pool.add(xyz[0], xyz[1], xyz[2], scale);
    }
    pool.mesh.triangle.push_back(tri);
  }
  return std::move(pool.mesh);
}

TriangleMesh read_ascii_stl(const std::string& path, const std::string& text, double scale) {
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  VertexPool pool;
  std::array<std::uint32_t, 3> tri{};
  int corners = -1;  // -1: outside a facet
  auto fail = [&](const std::string& why) {
    throw std::runtime_error(fmt::format("{}:{}: {}", path, line_no, why));
  };
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream words(line);
    std::string word;
    if (!(words >> word)) continue;
    if (word == "solid" || word == "endsolid" || word == "outer" || word == "endloop") continue;
    if (word == "facet") {
      if (corners >= 0) fail("'facet' inside a facet (a missing 'endfacet')");
      corners = 0;
    } else if (word == "vertex") {
      if (corners < 0) fail("'vertex' outside a facet");
      if (corners == 3) fail("a facet with more than 3 vertices (an STL facet is a triangle)");
      double x = 0.0;
      double y = 0.0;
      double z = 0.0;
      if (!(words >> x >> y >> z) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        fail("'vertex' needs three finite numbers");
      tri[corners++] = pool.add(x, y, z, scale);
    } else if (word == "endfacet") {
      if (corners != 3) fail(fmt::format("a facet with {} vertices (an STL facet is a triangle)", corners));
      pool.mesh.triangle.push_back(tri);
      corners = -1;
    } else {
      fail(
          fmt::format("'{}' is not a word of an ASCII STL file (solid, facet, outer loop, vertex, endloop, "
                      "endfacet, endsolid)",
                      word));
    }
  }
  if (corners >= 0) fail("the file ends inside a facet");
  return std::move(pool.mesh);
}

}  // namespace

TriangleMesh read_stl(const std::string& path, double scale) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error(fmt::format("{}: cannot open the STL file", path));
  std::ostringstream buffer;
  buffer << file.rdbuf();
  const std::string bytes = buffer.str();
  // Binary: an 80-byte header, a count and 50 bytes a facet, whatever the
  // header says (some binary files begin with "solid" too).
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50 * static_cast<std::size_t>(count)) return read_binary_stl(path, bytes, scale);
  }
  if (bytes.compare(0, 5, "solid") != 0)
    throw std::runtime_error(fmt::format(
        "{}: not an STL file (ASCII begins with 'solid'; binary has 84 + 50 bytes a facet)", path));
  return read_ascii_stl(path, bytes, scale);
}

}  // namespace darcydem
