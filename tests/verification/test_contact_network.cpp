// The contact network: Simulation::contact_forces and the contacts_NNNNN.vtu
// files the runner writes with every snapshot, read back as ParaView would.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "../common/vtk_text.hpp"
#include "darcydem/output/vtk.hpp"
#include "darcydem/simulation/runner.hpp"
#include "dem_setup.hpp"
#include "scene_loading.hpp"

namespace darcydem {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("darcydem_contacts_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  return dir;
}

/// The data files a .pvd series lists, in order.
std::vector<std::string> series_files(const fs::path& pvd) {
  const std::string text = testing::file_contents(pvd.string());
  std::vector<std::string> files;
  for (auto at = text.find("file=\""); at != std::string::npos; at = text.find("file=\"", at + 1)) {
    const auto begin = at + 6;
    files.push_back(text.substr(begin, text.find('"', begin) - begin));
  }
  return files;
}

// examples/column_settling/column.toml through the runner: 50 frictionless
// discs (r = 0.5 mm, k_n = 1e5 N/m) settled on the floor. The last
// snapshot's network has the 49 contacts between neighbours and the one with
// the floor; the contact below disc k carries the weight of the discs from k
// up, (50 - k) m g, and is compressed by that over k_n (the linear law), so
// its line, centre to centre, is 2r less that. Tolerance 1e-5 of the floor's
// force: the run stops at an unbalanced-force ratio of 1e-6 while the column
// still compresses slowly, its dashpots adding about 9e-5 of a disc's weight
// at every contact (ContactStress.OfTheSettledColumnDiscByDisc). With
// `contacts = false` the run writes no network.
TEST(ContactNetwork, SettledColumnCarriesTheWeightAboveEachContact) {
  auto scene = testing::load_scene<2>("examples/column_settling/column.toml");
  ASSERT_TRUE(scene.output.contacts) << "written by default";
  RunOptions options;
  const fs::path out = fresh_dir("column");
  options.out_dir = out.string();
  run_scene(scene, options);
  const auto files = series_files(out / "contacts.pvd");
  ASSERT_EQ(files.size(), series_files(out / "particles.pvd").size()) << "one network per snapshot";
  const std::string text = testing::file_contents((out / files.back()).string());
  const auto normal = testing::vtk_array(text, "normal_force");
  const auto tangential = testing::vtk_array(text, "tangential_force");
  const auto overlap = testing::vtk_array(text, "overlap");
  const auto first = testing::vtk_array(text, "first_id");
  const auto second = testing::vtk_array(text, "second_id");
  const auto wall = testing::vtk_array(text, "wall_id");
  const auto points = testing::vtk_array(text, "position");
  ASSERT_EQ(normal.size(), 50U);
  ASSERT_EQ(points.size(), 6U * normal.size()) << "two 3D points per contact";
  const double r = 5e-4;
  const double k_n = 1e5;
  const double w = 2650.0 * std::numbers::pi * r * r * 9.80665;
  const double tolerance = 1e-5 * 50.0 * w;
  int floor_contacts = 0;
  std::vector<int> seen(50, 0);
  double worst = 0.0;  // of the normal forces, in disc weights
  for (std::size_t c = 0; c < normal.size(); ++c) {
    const double length =
        std::hypot(points[6 * c + 3] - points[6 * c], points[6 * c + 4] - points[6 * c + 1]);
    EXPECT_EQ(tangential[c], 0.0) << "frictionless";
    EXPECT_NEAR(overlap[c], normal[c] / k_n, tolerance / k_n) << "contact " << c;
    if (wall[c] >= 0) {
      ++floor_contacts;
      EXPECT_EQ(first[c], 0.0) << "the bottom disc stands on the floor";
      EXPECT_EQ(second[c], -1.0);
      EXPECT_NEAR(normal[c], 50.0 * w, tolerance);
      worst = std::max(worst, std::abs(normal[c] - 50.0 * w) / w);
      EXPECT_NEAR(length, r - 50.0 * w / k_n, tolerance / k_n) << "centre to the point on the floor";
      continue;
    }
    const int below = static_cast<int>(std::min(first[c], second[c]));
    ASSERT_EQ(std::abs(first[c] - second[c]), 1.0) << "only neighbours touch";
    ++seen[static_cast<std::size_t>(below)];
    const double carried = (49.0 - below) * w;
    EXPECT_NEAR(normal[c], carried, tolerance) << "above disc " << below;
    worst = std::max(worst, std::abs(normal[c] - carried) / w);
    EXPECT_NEAR(length, 2.0 * r - carried / k_n, tolerance / k_n) << "above disc " << below;
  }
  EXPECT_EQ(floor_contacts, 1);
  std::printf("settled column: 50 contacts, normal forces within %.2e disc weights of the weight above\n",
              worst);
  for (int k = 0; k < 49; ++k) EXPECT_EQ(seen[static_cast<std::size_t>(k)], 1) << "disc " << k;

  auto quiet = testing::load_scene<2>("examples/column_settling/column.toml");
  quiet.output.contacts = false;
  const fs::path none = fresh_dir("column_none");
  options.out_dir = none.string();
  run_scene(quiet, options);
  EXPECT_FALSE(fs::exists(none / "contacts.pvd"));
  EXPECT_FALSE(series_files(none / "particles.pvd").empty());
  fs::remove_all(out);
  fs::remove_all(none);
}

// A square lattice of 12 x 12 discs compressed by delta, filling a period
// along x and y: each disc touches 4, each pair listed once (2 per disc),
// every force k_n delta, and every line as long as the spacing 2r - delta,
// drawn to the partner's nearest image, also across the boundary (a line
// to the far copy would be 11 spacings long). Bounds 1e-9: round-off
// (forces to 1e-11 of k_n delta in test_periodic.cpp).
TEST(ContactNetwork, PeriodicLatticeIsDrawnToTheNearestImages) {
  ContactSpec spec;
  spec.normal_stiffness = 1e5;
  auto sim = testing::single_material<2>(2650.0, spec);
  const double r = 5e-4;
  const double delta = 1e-6;
  const double s = 2.0 * r - delta;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) sim.particles.add(Vec<2>((i + 0.3) * s, (j + 0.3) * s), r, 2650.0, 0, false);
  }
  sim.periodic.set_axis(0, 0.0, n * s);
  sim.periodic.set_axis(1, 0.0, n * s);
  sim.time_step = 0.1 * sim.critical_time_step();
  sim.prepare();
  const auto contacts = sim.contact_forces();
  ASSERT_EQ(contacts.size(), static_cast<std::size_t>(2 * n * n));
  const fs::path dir = fresh_dir("lattice");
  fs::create_directories(dir);
  const std::string path = (dir / "contacts.vtu").string();
  write_contacts_vtu<2>(path, sim.particles, contacts);
  const std::string text = testing::file_contents(path);
  const auto normal = testing::vtk_array(text, "normal_force");
  const auto points = testing::vtk_array(text, "position");
  ASSERT_EQ(normal.size(), contacts.size());
  int across = 0;
  for (std::size_t c = 0; c < normal.size(); ++c) {
    EXPECT_NEAR(normal[c], spec.normal_stiffness * delta, 1e-9 * spec.normal_stiffness * delta);
    const double dx = points[6 * c + 3] - points[6 * c];
    const double dy = points[6 * c + 4] - points[6 * c + 1];
    EXPECT_NEAR(std::hypot(dx, dy), s, 1e-9 * s) << "contact " << c;
    const double x_end = points[6 * c + 3];
    const double y_end = points[6 * c + 4];
    across += (x_end < 0.0 || x_end >= n * s || y_end < 0.0 || y_end >= n * s) ? 1 : 0;
  }
  EXPECT_EQ(across, 2 * n) << "the contacts across the boundary end at images outside the period";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace darcydem
