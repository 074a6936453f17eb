// TriangleMesh: the nearest point of a facet against a brute-force search
// over a fine sample of the facet, the mesh's nearest facet against all
// facets, and the STL reader: ASCII and binary files of the same surface
// give the same mesh, and a bad file is named with its line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include <fmt/format.h>

#include "darcydem/walls/triangle_mesh.hpp"

namespace darcydem {
namespace {

TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.vertex = {{0.0, 0.0, 0.0}, {1.0, 0.1, 0.0}, {0.2, 0.9, 0.1}, {0.3, 0.3, 0.8}};
  m.triangle = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  EXPECT_EQ(m.finish(), "");
  return m;
}

// The nearest point is a point of the facet no farther from x than any
// sampled point of it (a 400 x 400 barycentric sample, spacing 1/400 of the
// edges: the sample's best is at most that spacing, times the edge, farther
// than the true one). Points all round the facet: off its corners, edges
// and face, on both sides.
TEST(TriangleMesh, NearestPointOfAFacetIsNoFartherThanAnyOfItsPoints) {
  const TriangleMesh m = tetrahedron();
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  const int n = 400;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec<3> x(u(gen), u(gen), u(gen));
    const std::size_t f = trial % 4;
    const Vec<3> q = m.closest_point(f, x);
    const Vec<3>& a = m.vertex[m.triangle[f][0]];
    const Vec<3>& b = m.vertex[m.triangle[f][1]];
    const Vec<3>& c = m.vertex[m.triangle[f][2]];
    // q lies on the facet: its plane, and barycentric coordinates >= 0.
    EXPECT_NEAR((q - a).dot(m.facet_normal[f]), 0.0, 1e-12);
    double best = 1e300;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const Vec<3> p = a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a);
        best = std::min(best, (x - p).norm());
      }
    const double d = (x - q).norm();
    EXPECT_LE(d, best + 1e-12);
    EXPECT_GE(d, best - 2.0 / n);
  }
}

// nearest() against every facet, from points near and far.
TEST(TriangleMesh, NearestFacetIsTheNearestOfAll) {
  const TriangleMesh m = tetrahedron();
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-3.0, 4.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec<3> x(u(gen), u(gen), u(gen));
    double best = 1e300;
    for (std::size_t f = 0; f < 4; ++f) best = std::min(best, (x - m.closest_point(f, x)).norm());
    EXPECT_DOUBLE_EQ(m.nearest(x).distance, best);
  }
}

// facets_near finds every facet that comes within the reach (it may list
// more: those of the bins the reach covers).
TEST(TriangleMesh, FacetsNearMissNoFacetWithinReach) {
  TriangleMesh m;
  const int n = 20;  // a bumpy sheet of 2 n^2 facets
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertex.emplace_back(i * 0.1, j * 0.1, 0.03 * std::sin(i + 2.0 * j));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto a = static_cast<std::uint32_t>(j * (n + 1) + i);
      m.triangle.push_back({a, a + 1, a + n + 2});
      m.triangle.push_back({a, a + n + 2, a + n + 1});
    }
  ASSERT_EQ(m.finish(), "");
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-0.2, 2.2);
  std::vector<std::uint32_t> near;
  for (int trial = 0; trial < 100; ++trial) {
    const Vec<3> x(u(gen), u(gen), 0.3 * u(gen) - 0.3);
    const double reach = 0.05 + 0.1 * (trial % 3);
    m.facets_near(x, reach, near);
    for (std::size_t f = 0; f < m.triangle.size(); ++f) {
      if ((x - m.closest_point(f, x)).norm() < reach) {
        EXPECT_TRUE(std::binary_search(near.begin(), near.end(), static_cast<std::uint32_t>(f)))
            << "facet " << f << " at reach " << reach;
      }
    }
  }
}

std::filesystem::path temp_file(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "darcydem_mesh_test";
  std::filesystem::create_directories(dir);
  return dir / name;
}

// The tetrahedron written as ASCII and as binary STL (each facet with its
// own three corners, as STL keeps them) reads back as 4 vertices and the
// same 4 facets, scaled.
TEST(TriangleMesh, AsciiAndBinaryStlReadTheSameSurface) {
  const TriangleMesh m = tetrahedron();
  const auto ascii = temp_file("tet_ascii.stl");
  const auto binary = temp_file("tet_binary.stl");
  {
    std::ofstream out(ascii);
    out << "solid tet\n";
    for (std::size_t f = 0; f < 4; ++f) {
      const Vec<3>& n = m.facet_normal[f];
      out << fmt::format("  facet normal {} {} {}\n    outer loop\n", n[0], n[1], n[2]);
      for (auto v : m.triangle[f])
        out << fmt::format("      vertex {} {} {}\n", m.vertex[v][0], m.vertex[v][1], m.vertex[v][2]);
      out << "    endloop\n  endfacet\n";
    }
    out << "endsolid tet\n";
  }
  {
    std::ofstream out(binary, std::ios::binary);
    char header[80] = "solid but binary";
    out.write(header, 80);
    const std::uint32_t count = 4;
    out.write(reinterpret_cast<const char*>(&count), 4);
    for (std::size_t f = 0; f < 4; ++f) {
      float rec[12] = {};
      for (int c = 0; c < 3; ++c) {
        rec[c] = static_cast<float>(m.facet_normal[f][c]);
        for (int v = 0; v < 3; ++v) rec[3 + 3 * v + c] = static_cast<float>(m.vertex[m.triangle[f][v]][c]);
      }
      out.write(reinterpret_cast<const char*>(rec), 48);
      const std::uint16_t attribute = 0;
      out.write(reinterpret_cast<const char*>(&attribute), 2);
    }
  }
  const TriangleMesh a = read_stl(ascii.string(), 2.0);
  const TriangleMesh b = read_stl(binary.string(), 2.0);
  ASSERT_EQ(a.vertex.size(), 4u);
  ASSERT_EQ(b.vertex.size(), 4u);
  ASSERT_EQ(a.triangle.size(), 4u);
  ASSERT_EQ(b.triangle.size(), 4u);
  for (std::size_t f = 0; f < 4; ++f)
    for (int c = 0; c < 3; ++c) {
      const Vec<3> want = 2.0 * m.vertex[m.triangle[f][c]];
      // ASCII prints the shortest form that reads back exactly; binary keeps
      // floats (7 digits).
      EXPECT_LT((a.vertex[a.triangle[f][c]] - want).norm(), 1e-15);
      EXPECT_LT((b.vertex[b.triangle[f][c]] - want).norm(), 1e-6);
    }
}

TEST(TriangleMesh, ABadStlFileIsNamedWithItsLine) {
  const auto bad = temp_file("bad.stl");
  {
    std::ofstream out(bad);
    out << "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 zero\n";
  }
  try {
    (void)read_stl(bad.string(), 1.0);
    FAIL() << "read a bad file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string() + ":5: 'vertex' needs three finite numbers"),
              std::string::npos)
        << e.what();
  }
  try {
    (void)read_stl(temp_file("missing.stl").string(), 1.0);
    FAIL() << "read a missing file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open the STL file"), std::string::npos) << e.what();
  }
  TriangleMesh flat;
  flat.vertex = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.triangle = {{0, 1, 2}};
  EXPECT_EQ(flat.finish(), "facet 0 has no area (its corners are in a line)");
}

}  // namespace
}  // namespace darcydem
