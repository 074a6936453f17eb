#include "darcydem/output/vtk.hpp"

#include <cmath>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include <fmt/format.h>
#include <fmt/os.h>

namespace darcydem {
namespace {

template <int D, class Get>
void write_vector_array(fmt::ostream& out, const char* name, std::size_t n, Get&& get) {
  out.print("        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\" format=\"ascii\">\n",
            name);
  for (std::size_t i = 0; i < n; ++i) {
    const auto v = get(i);
    out.print("{:.17g} {:.17g} {:.17g}\n", v[0], v[1], D == 3 ? v[2] : 0.0);
  }
  out.print("        </DataArray>\n");
}

template <class Get>
void write_scalar_array(fmt::ostream& out, const char* type, const char* name, std::size_t n, Get&& get) {
  out.print("        <DataArray type=\"{}\" Name=\"{}\" format=\"ascii\">\n", type, name);
  for (std::size_t i = 0; i < n; ++i) {
    if constexpr (std::is_floating_point_v<decltype(get(i))>) {
      out.print("{:.17g}\n", get(i));
    } else {
      out.print("{}\n", get(i));
    }
  }
  out.print("        </DataArray>\n");
}

/// An unstructured grid's head: its points and the start of its cell data
/// (`scalars`: the array ParaView colours by at first).
void write_points_and_open_cells(fmt::ostream& out, const std::vector<Vec<3>>& points, std::size_t cells,
                                 const char* scalars) {
  out.print(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
      "byte_order=\"LittleEndian\">\n");
  out.print("  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", points.size(),
            cells);
  out.print("      <Points>\n");
  write_vector_array<3>(out, "position", points.size(), [&](std::size_t i) { return points[i]; });
  out.print("      </Points>\n      <CellData Scalars=\"{}\">\n", scalars);
}

/// The end of an unstructured grid's cell data, its cells (the points in
/// order, cell by cell: `offsets` the end of each, `types` its VTK type)
/// and the file's closing tags.
void write_cells_and_close(fmt::ostream& out, std::size_t points, const std::vector<int>& offsets,
                           const std::vector<int>& types) {
  out.print("      </CellData>\n      <Cells>\n");
  out.print("        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n");
  for (std::size_t i = 0; i < points; ++i) out.print("{}\n", i);
  out.print("        </DataArray>\n        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n");
  for (int o : offsets) out.print("{}\n", o);
  out.print("        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (int t : types) out.print("{}\n", t);
  out.print("        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
}

}  // namespace

template <int D>
void write_particles_vtu(const std::string& path, const ParticleData<D>& p,
                         const std::vector<Vec<D>>* fluid_force, const std::vector<std::int32_t>* clump) {
  try {
    auto out = fmt::output_file(path);
    const std::size_t n = p.size();
    out.print(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
        "byte_order=\"LittleEndian\">\n");
    out.print("  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"0\">\n", n);
    out.print("      <Points>\n");
    write_vector_array<D>(out, "position", n, [&](std::size_t i) { return p.position[i]; });
    out.print("      </Points>\n      <PointData Scalars=\"radius\">\n");
    out.print("        <DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < n; ++i) out.print("{:.17g}\n", p.radius[i]);
    out.print("        </DataArray>\n");
    out.print("        <DataArray type=\"Int64\" Name=\"id\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < n; ++i) out.print("{}\n", p.id[i]);
    out.print("        </DataArray>\n");
    write_vector_array<D>(out, "velocity", n, [&](std::size_t i) { return p.velocity[i]; });
    write_vector_array<D>(out, "force", n, [&](std::size_t i) { return p.force[i]; });
    if (fluid_force != nullptr && fluid_force->size() == n) {
      write_vector_array<D>(out, "fluid_force", n, [&](std::size_t i) { return (*fluid_force)[i]; });
    }
    write_vector_array<D>(out, "angular_velocity", n, [&](std::size_t i) {
      if constexpr (D == 2) {
        return Vec<3>(0.0, 0.0, p.angular_velocity[i][0]);
      } else {
        return p.angular_velocity[i];
      }
    });
    if (clump != nullptr && clump->size() == n) {
      write_scalar_array(out, "Int32", "clump", n, [&](std::size_t i) { return (*clump)[i]; });
    }
    out.print("      </PointData>\n      <Cells>\n");
    out.print("        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\"></DataArray>\n");
    out.print("        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\"></DataArray>\n");
    out.print("        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\"></DataArray>\n");
    out.print("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    out.close();
  } catch (const std::system_error& e) {
    throw std::runtime_error(fmt::format("{}: cannot write the snapshot: {}", path, e.what()));
  }
}

template <int D>
void write_walls_vtu(const std::string& path, const std::vector<Wall<D>>& walls, const Vec<D>& lo,
                     const Vec<D>& hi, const std::vector<std::vector<Vec<D>>>* facet_forces) {
  // Each wall's corners (as 3D points) and VTK cell type.
  std::vector<Vec<3>> points;
  std::vector<int> offsets;
  std::vector<int> types;
  std::vector<std::size_t> cell_wall;  // the wall each cell draws (a mesh: one cell a facet)
  std::vector<Vec<D>> cell_force;      // the force on it, N
  std::vector<double> cell_stress;     // a facet's normal stress, Pa (0 for other walls)
  auto lift = [](const Vec<D>& x) {
    Vec<3> y = Vec<3>::Zero();
    for (int k = 0; k < D; ++k) y[k] = x[k];
    return y;
  };
  const Vec<D> middle = 0.5 * (lo + hi);
  const double half_size = 0.55 * (hi - lo).norm();
  for (std::size_t wi = 0; wi < walls.size(); ++wi) {
    const auto& w = walls[wi];
    if constexpr (D == 3) {
      if (w.is_mesh()) {
        // Its facets, one triangle each, where the wall stands now.
        const bool shared = facet_forces != nullptr && (*facet_forces)[wi].size() == w.mesh->triangle.size();
        for (std::size_t f = 0; f < w.mesh->triangle.size(); ++f) {
          const auto& t = w.mesh->triangle[f];
          for (auto v : t) points.push_back(Vec<3>(w.point + w.axes * w.mesh->vertex[v]));
          types.push_back(5);  // VTK_TRIANGLE
          offsets.push_back(static_cast<int>(points.size()));
          cell_wall.push_back(wi);
          cell_force.push_back(shared ? (*facet_forces)[wi][f] : w.force);
          cell_stress.push_back(shared ? std::abs(cell_force.back().dot(w.axes * w.mesh->facet_normal[f])) /
                                             w.mesh->facet_area(f)
                                       : 0.0);
        }
        continue;
      }
    }
    if (w.is_box()) {
      // Corners counter-clockwise about the box's third axis (in 2D, the
      // plane's normal), then (3D) the same on the far side, in its own axes.
      const double xs[4] = {-1.0, 1.0, 1.0, -1.0};
      const double ys[4] = {-1.0, -1.0, 1.0, 1.0};
      for (int layer = 0; layer < (D == 3 ? 2 : 1); ++layer) {
        for (int c = 0; c < 4; ++c) {
          Vec<D> local;
          local[0] = xs[c] * w.half[0];
          local[1] = ys[c] * w.half[1];
          if constexpr (D == 3) local[2] = (layer == 0 ? -1.0 : 1.0) * w.half[2];
          points.push_back(lift(Vec<D>(w.point + w.axes * local)));
        }
      }
      types.push_back(D == 3 ? 12 : 9);  // VTK_HEXAHEDRON, VTK_QUAD
    } else if (w.is_cylinder()) {
      // 64 sides: in 2D a closed line round the circle, in 3D a strip of
      // triangles between two rings across the view, as a plane is drawn.
      constexpr int sides = 64;
      Vec<3> u = Vec<3>::UnitX();
      Vec<3> v = Vec<3>::UnitY();
      Vec<3> along = Vec<3>::Zero();
      Vec<3> centre = lift(w.point);
      if constexpr (D == 3) {
        along = w.axis;
        centre += (middle - w.point).dot(w.axis) * w.axis;
        u = unit_across<3>(w.axis);
        v = along.cross(u);
      }
      for (int c = 0; c <= sides; ++c) {
        const double a = 2.0 * std::numbers::pi * c / sides;
        const Vec<3> rim = centre + w.radius * (std::cos(a) * u + std::sin(a) * v);
        if constexpr (D == 3) {
          points.push_back(rim - half_size * along);
          points.push_back(rim + half_size * along);
        } else {
          points.push_back(rim);
        }
      }
      types.push_back(D == 3 ? 6 : 4);  // VTK_TRIANGLE_STRIP, VTK_POLY_LINE
    } else {
      const Vec<D> centre = middle - (middle - w.point).dot(w.normal) * w.normal;
      if constexpr (D == 2) {
        const Vec<D> t(-w.normal[1], w.normal[0]);
        points.push_back(lift(centre - half_size * t));
        points.push_back(lift(centre + half_size * t));
        types.push_back(3);  // VTK_LINE
      } else {
        // Two directions in the plane: from the axis least along the normal.
        const Vec<3> n = lift(w.normal);
        const Vec<3> t1 = unit_across<3>(n);
        const Vec<3> t2 = cross(n, t1);
        const Vec<3> c = lift(centre);
        points.push_back(c - half_size * t1 - half_size * t2);
        points.push_back(c + half_size * t1 - half_size * t2);
        points.push_back(c + half_size * t1 + half_size * t2);
        points.push_back(c - half_size * t1 + half_size * t2);
        types.push_back(9);  // VTK_QUAD
      }
    }
    offsets.push_back(static_cast<int>(points.size()));
    cell_wall.push_back(wi);
    cell_force.push_back(w.force);
    cell_stress.push_back(0.0);
  }
  try {
    auto out = fmt::output_file(path);
    write_points_and_open_cells(out, points, cell_wall.size(), "wall_id");
    out.print("        <DataArray type=\"Int32\" Name=\"wall_id\" format=\"ascii\">\n");
    for (std::size_t w : cell_wall) out.print("{}\n", w);
    out.print("        </DataArray>\n");
    write_vector_array<D>(out, "force", cell_wall.size(), [&](std::size_t c) { return cell_force[c]; });
    out.print("        <DataArray type=\"Float64\" Name=\"normal_stress\" format=\"ascii\">\n");
    for (double x : cell_stress) out.print("{:.17g}\n", x);
    out.print("        </DataArray>\n");
    write_vector_array<D>(out, "velocity", cell_wall.size(),
                          [&](std::size_t c) { return walls[cell_wall[c]].translation_velocity(); });
    write_cells_and_close(out, points.size(), offsets, types);
    out.close();
  } catch (const std::system_error& e) {
    throw std::runtime_error(fmt::format("{}: cannot write the walls: {}", path, e.what()));
  }
}

template <int D>
void write_fluid_vti(const std::string& path, const PoreFluid<D>& f,
                     const std::vector<Eigen::Matrix<double, D, D>>* effective_stress) {
  try {
    auto out = fmt::output_file(path);
    const auto& g = f.grid;
    const int nz = D == 3 ? g.cells[D - 1] : 1;
    const double oz = D == 3 ? g.origin[2] : 0.0;
    const double hz = D == 3 ? g.spacing[2] : 1.0;
    const std::string extent = fmt::format("0 {} 0 {} 0 {}", g.cells[0], g.cells[1], nz);
    // Graded axes: a rectilinear grid (.vtr) with the faces' coordinates;
    // else image data (.vti).
    const bool rectilinear = g.any_graded();
    const char* type = rectilinear ? "RectilinearGrid" : "ImageData";
    out.print(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"{}\" version=\"0.1\" "
        "byte_order=\"LittleEndian\">\n",
        type);
    if (rectilinear) {
      out.print("  <RectilinearGrid WholeExtent=\"{}\">\n    <Piece Extent=\"{}\">\n      <Coordinates>\n",
                extent, extent);
      for (int k = 0; k < 3; ++k) {
        out.print("        <DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">\n", "xyz"[k]);
        if (k < D) {
          for (int i = 0; i <= g.cells[k]; ++i) out.print("{:.17g}\n", g.face_at(k, i));
        } else {
          out.print("0\n1\n");  // 2D: the cells' unit thickness
        }
        out.print("        </DataArray>\n");
      }
      out.print("      </Coordinates>\n      <CellData Scalars=\"pressure\">\n");
    } else {
      out.print(
          "  <ImageData WholeExtent=\"{}\" Origin=\"{:.17g} {:.17g} {:.17g}\" Spacing=\"{:.17g} {:.17g} "
          "{:.17g}\">\n",
          extent, g.origin[0], g.origin[1], oz, g.spacing[0], g.spacing[1], hz);
      out.print("    <Piece Extent=\"{}\">\n      <CellData Scalars=\"pressure\">\n", extent);
    }
    auto scalars = [&](const char* name, const std::vector<double>& v) {
      out.print("        <DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">\n", name);
      for (double x : v) out.print("{:.17g}\n", x);
      out.print("        </DataArray>\n");
    };
    scalars("pressure", f.pressure());
    scalars("porosity", f.porosity());
    write_vector_array<D>(out, "permeability", g.size(),
                          [&](std::size_t i) { return f.permeability_field()[i]; });
    const auto q = f.darcy_velocity();
    write_vector_array<D>(out, "darcy_velocity", g.size(), [&](std::size_t i) { return q[i]; });
    write_vector_array<D>(out, "solid_velocity", g.size(),
                          [&](std::size_t i) { return f.solid_velocity()[i]; });
    if (effective_stress != nullptr) {
      const auto& s = *effective_stress;
      out.print(
          "        <DataArray type=\"Float64\" Name=\"effective_stress\" NumberOfComponents=\"9\" "
          "format=\"ascii\">\n");
      for (const auto& m : s) {
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b)
            out.print("{:.17g}{}", a < D && b < D ? m(a, b) : 0.0, a * b == 4 ? "\n" : " ");
        }
      }
      out.print("        </DataArray>\n");
      std::vector<double> mean(s.size());
      for (std::size_t i = 0; i < s.size(); ++i) mean[i] = s[i].trace() / D;
      scalars("mean_effective_stress", mean);
    }
    out.print("      </CellData>\n    </Piece>\n  </{}>\n</VTKFile>\n", type);
    out.close();
  } catch (const std::system_error& e) {
    throw std::runtime_error(fmt::format("{}: cannot write the fluid snapshot: {}", path, e.what()));
  }
}

void PvdSeries::add(double time, const std::string& file) {
  entries_.emplace_back(time, file);
  const std::string tmp = path_ + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write the series file", path_));
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (const auto& [t, f] : entries_) {
      out << fmt::format("    <DataSet timestep=\"{:.17g}\" part=\"0\" file=\"{}\"/>\n", t, f);
    }
    out << "  </Collection>\n</VTKFile>\n";
  }
  std::rename(tmp.c_str(), path_.c_str());
}

template <int D>
void write_contacts_vtu(const std::string& path, const ParticleData<D>& p,
                        const std::vector<ContactRecord<D>>& contacts) {
  const std::size_t n = contacts.size();
  auto normal_force = [&](std::size_t c) { return -contacts[c].force.dot(contacts[c].normal); };
  try {
    auto out = fmt::output_file(path);
    out.print(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
        "byte_order=\"LittleEndian\">\n");
    out.print("  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", 2 * n, n);
    out.print("      <Points>\n");
    // Each contact's two ends: the first particle's centre and the other's
    // (its nearest periodic image) or the contact point on the wall.
    write_vector_array<D>(out, "position", 2 * n, [&](std::size_t e) {
      const auto& c = contacts[e / 2];
      return Vec<D>(e % 2 == 0 ? p.position[c.first] : Vec<D>(p.position[c.first] + c.branch));
    });
    out.print("      </Points>\n      <CellData Scalars=\"normal_force\">\n");
    write_scalar_array(out, "Float64", "normal_force", n, normal_force);
    write_scalar_array(out, "Float64", "tangential_force", n, [&](std::size_t c) {
      return (contacts[c].force + normal_force(c) * contacts[c].normal).norm();
    });
    write_vector_array<D>(out, "force", n, [&](std::size_t c) { return contacts[c].force; });
    write_scalar_array(out, "Float64", "overlap", n, [&](std::size_t c) { return contacts[c].overlap; });
    write_scalar_array(out, "Int64", "first_id", n, [&](std::size_t c) { return p.id[contacts[c].first]; });
    write_scalar_array(out, "Int64", "second_id", n, [&](std::size_t c) {
      return contacts[c].wall < 0 ? static_cast<std::int64_t>(p.id[contacts[c].second]) : std::int64_t{-1};
    });
    write_scalar_array(out, "Int32", "wall_id", n, [&](std::size_t c) { return contacts[c].wall; });
    write_scalar_array(out, "UInt8", "bonded", n,
                       [&](std::size_t c) { return static_cast<unsigned>(contacts[c].bonded ? 1 : 0); });
    write_scalar_array(out, "Float64", "bending_moment", n,
                       [&](std::size_t c) { return contacts[c].bending_moment; });
    if constexpr (D == 3) {
      write_scalar_array(out, "Float64", "twisting_moment", n,
                         [&](std::size_t c) { return contacts[c].twisting_moment; });
    }
    out.print("      </CellData>\n      <Cells>\n");
    write_scalar_array(out, "Int64", "connectivity", 2 * n, [](std::size_t e) { return e; });
    write_scalar_array(out, "Int64", "offsets", n, [](std::size_t c) { return 2 * (c + 1); });
    write_scalar_array(out, "UInt8", "types", n, [](std::size_t) { return 3; });  // VTK_LINE
    out.print("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    out.close();
  } catch (const std::system_error& e) {
    throw std::runtime_error(fmt::format("{}: cannot write the contacts: {}", path, e.what()));
  }
}

template <int D>
void write_sources_vtu(const std::string& path, const PoreFluid<D>& f) {
  std::vector<Vec<3>> points;
  std::vector<int> offsets;
  std::vector<int> types;
  for (const auto& source : f.sources) {
    Vec<3> x = Vec<3>::Zero();
    for (int k = 0; k < D; ++k) x[k] = source.position[k];
    if (source.screened()) {
      // From the screen's one end to its other, through the position.
      Vec<3> y = x;
      x[source.screen_axis] = source.screen[0];
      y[source.screen_axis] = source.screen[1];
      points.push_back(x);
      points.push_back(y);
      types.push_back(3);  // VTK_LINE
    } else {
      points.push_back(x);
      types.push_back(1);  // VTK_VERTEX
    }
    offsets.push_back(static_cast<int>(points.size()));
  }
  const std::size_t n = f.sources.size();
  try {
    auto out = fmt::output_file(path);
    write_points_and_open_cells(out, points, n, "inflow");
    write_scalar_array(out, "Int32", "source_id", n, [](std::size_t i) { return static_cast<int>(i); });
    write_scalar_array(out, "Float64", "inflow", n, [&](std::size_t i) { return f.source_inflow(i); });
    write_scalar_array(out, "Float64", "pressure", n, [&](std::size_t i) { return f.well_pressure(i); });
    write_scalar_array(out, "Float64", "radius", n, [&](std::size_t i) { return f.sources[i].radius; });
    write_scalar_array(out, "Int32", "held", n,
                       [&](std::size_t i) { return f.sources[i].type == FluidSourceType::pressure ? 1 : 0; });
    write_scalar_array(out, "Int32", "open", n,
                       [&](std::size_t i) { return !f.sources[i].drains() || f.drain_open(i) ? 1 : 0; });
    write_cells_and_close(out, points.size(), offsets, types);
    out.close();
  } catch (const std::system_error& e) {
    throw std::runtime_error(fmt::format("{}: cannot write the sources: {}", path, e.what()));
  }
}

template void write_sources_vtu<2>(const std::string&, const PoreFluid<2>&);
template void write_sources_vtu<3>(const std::string&, const PoreFluid<3>&);
template void write_particles_vtu<2>(const std::string&, const ParticleData<2>&, const std::vector<Vec<2>>*,
                                     const std::vector<std::int32_t>*);
template void write_particles_vtu<3>(const std::string&, const ParticleData<3>&, const std::vector<Vec<3>>*,
                                     const std::vector<std::int32_t>*);
template void write_contacts_vtu<2>(const std::string&, const ParticleData<2>&,
                                    const std::vector<ContactRecord<2>>&);
template void write_contacts_vtu<3>(const std::string&, const ParticleData<3>&,
                                    const std::vector<ContactRecord<3>>&);
template void write_walls_vtu<2>(const std::string&, const std::vector<Wall<2>>&, const Vec<2>&,
                                 const Vec<2>&, const std::vector<std::vector<Vec<2>>>*);
template void write_walls_vtu<3>(const std::string&, const std::vector<Wall<3>>&, const Vec<3>&,
                                 const Vec<3>&, const std::vector<std::vector<Vec<3>>>*);
template void write_fluid_vti<2>(const std::string&, const PoreFluid<2>&,
                                 const std::vector<Eigen::Matrix<double, 2, 2>>*);
template void write_fluid_vti<3>(const std::string&, const PoreFluid<3>&,
                                 const std::vector<Eigen::Matrix<double, 3, 3>>*);

}  // namespace darcydem
