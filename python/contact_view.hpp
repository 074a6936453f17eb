#pragma once
// The contacts of the last force evaluation as numpy arrays, one row per
// contact (YADE's O.interactions, PFC's contact iteration): the pair by
// particle number, the wall, the contact point, normal, overlap and force.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cstdint>
#include <tuple>
#include <vector>

#include "darcydem/simulation/simulation.hpp"

namespace darcydem::python {

namespace py = pybind11;

/// One row: the record as seen from the particle with the lower number
/// (for a wall contact, from the particle).
template <int D>
struct ContactRow {
  std::int64_t first = 0;
  std::int64_t second = -1;
  std::int64_t wall = -1;
  Vec<D> point;
  Vec<D> normal;
  double overlap = 0.0;
  Vec<D> force;
  bool bonded = false;
  double bending_moment = 0.0;
  double twisting_moment = 0.0;
};

/// Rows sorted by (first, second, wall): the same whatever the order the
/// simulation keeps its particles in, or the number of threads.
template <int D>
std::vector<ContactRow<D>> contact_rows(const Simulation<D>& sim) {
  const auto& p = sim.particles;
  std::vector<ContactRow<D>> rows;
  for (const ContactRecord<D>& c : sim.contact_forces()) {
    ContactRow<D> row;
    row.point = p.position[c.first] + c.arm_first * c.normal;
    row.normal = c.normal;
    row.overlap = c.overlap;
    row.force = c.force;
    row.bonded = c.bonded;
    row.bending_moment = c.bending_moment;
    row.twisting_moment = c.twisting_moment;
    row.first = p.id[c.first];
    if (c.wall >= 0) {
      row.wall = c.wall;
    } else {
      row.second = p.id[c.second];
      if (row.second < row.first) {
        // Seen from the other grain: its normal and the force on it are
        // the opposite; the point is the same (nearest image: its own
        // centre plus its arm along the reversed normal).
        std::swap(row.first, row.second);
        row.point = p.position[c.second] - c.arm_second * c.normal;
        row.normal = -c.normal;
        row.force = -c.force;
      }
    }
    rows.push_back(row);
  }
  std::sort(rows.begin(), rows.end(), [](const ContactRow<D>& a, const ContactRow<D>& b) {
    return std::tie(a.first, a.second, a.wall) < std::tie(b.first, b.second, b.wall);
  });
  return rows;
}

/// The dict model.contacts returns.
template <int D>
py::dict contact_arrays(const Simulation<D>& sim) {
  const auto rows = contact_rows(sim);
  const auto m = static_cast<py::ssize_t>(rows.size());
  py::array_t<std::int64_t> particles({m, py::ssize_t{2}});
  py::array_t<std::int64_t> wall(m);
  py::array_t<double> point({m, py::ssize_t{D}});
  py::array_t<double> normal({m, py::ssize_t{D}});
  py::array_t<double> overlap(m);
  py::array_t<double> force({m, py::ssize_t{D}});
  py::array_t<double> normal_force(m);
  py::array_t<double> shear_force({m, py::ssize_t{D}});
  py::array_t<bool> bonded(m);
  py::array_t<double> bending(m);
  py::array_t<double> twisting(m);
  auto pa = particles.mutable_unchecked<2>();
  auto wa = wall.mutable_unchecked<1>();
  auto xa = point.mutable_unchecked<2>();
  auto na = normal.mutable_unchecked<2>();
  auto oa = overlap.mutable_unchecked<1>();
  auto fa = force.mutable_unchecked<2>();
  auto fna = normal_force.mutable_unchecked<1>();
  auto fsa = shear_force.mutable_unchecked<2>();
  auto ba = bonded.mutable_unchecked<1>();
  auto bma = bending.mutable_unchecked<1>();
  auto tma = twisting.mutable_unchecked<1>();
  for (py::ssize_t r = 0; r < m; ++r) {
    const ContactRow<D>& c = rows[static_cast<std::size_t>(r)];
    pa(r, 0) = c.first;
    pa(r, 1) = c.second;
    wa(r) = c.wall;
    const double fn = -c.force.dot(c.normal);  // compression positive
    const Vec<D> shear = c.force + fn * c.normal;
    for (int k = 0; k < D; ++k) {
      xa(r, k) = c.point[k];
      na(r, k) = c.normal[k];
      fa(r, k) = c.force[k];
      fsa(r, k) = shear[k];
    }
    oa(r) = c.overlap;
    fna(r) = fn;
    ba(r) = c.bonded;
    bma(r) = c.bending_moment;
    tma(r) = c.twisting_moment;
  }
  py::dict d;
  d["particles"] = particles;
  d["wall"] = wall;
  d["point"] = point;
  d["normal"] = normal;
  d["overlap"] = overlap;
  d["force"] = force;
  d["normal_force"] = normal_force;
  d["shear_force"] = shear_force;
  d["bonded"] = bonded;
  d["bending_moment"] = bending;
  d["twisting_moment"] = twisting;
  return d;
}

}  // namespace darcydem::python
