#pragma once
// Where a test's scene run writes its files, and how the test reads back
// its probes.csv.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace darcydem::testing {

/// Where temp_dir(name) puts its folder.
inline std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("darcydem_test_" + name + "_" + std::to_string(getpid())))
      .string();
}

/// A fresh folder for a test's output.
inline std::string temp_dir(const std::string& name) {
  const auto dir = temp_path(name);
  std::filesystem::remove_all(dir);
  return dir;
}

/// Columns of a probes.csv by name.
inline std::map<std::string, std::vector<double>> read_probes(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (const auto& name : names) {
      std::getline(row, cell, ',');
      columns[name].push_back(std::stod(cell));
    }
  }
  return columns;
}

/// When a rising series (a probe's column against `time`) first reached
/// `value`, linear between the rows; NaN if it never did.
inline double time_reaching(const std::vector<double>& time, const std::vector<double>& series,
                            double value) {
  for (std::size_t k = 1; k < series.size(); ++k) {
    if (series[k] >= value)
      return time[k - 1] + (time[k] - time[k - 1]) * (value - series[k - 1]) / (series[k] - series[k - 1]);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace darcydem::testing
