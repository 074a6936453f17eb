#pragma once
// A string in double quotes, with `"` and `\` escaped and control characters
// as \uXXXX: the same text is a JSON string and a TOML basic string.
#include <string>

#include <fmt/format.h>

namespace darcydem {

inline std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<int>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace darcydem
