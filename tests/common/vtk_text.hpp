#pragma once
// Reads back the ASCII VTK XML files darcydem writes, as tests need them.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace darcydem::testing {

/// The numbers of the DataArray named `name` in a VTK XML file's text
/// (empty, and a test failure, if there is none).
inline std::vector<double> vtk_array(const std::string& text, const std::string& name) {
  const auto at = text.find("Name=\"" + name + "\"");
  if (at == std::string::npos) {
    ADD_FAILURE() << "no DataArray named " << name;
    return {};
  }
  const auto begin = text.find('>', at) + 1;
  const auto end = text.find("</DataArray>", begin);
  std::stringstream s(text.substr(begin, end - begin));
  std::vector<double> v;
  for (double x; s >> x;) v.push_back(x);
  return v;
}

}  // namespace darcydem::testing
