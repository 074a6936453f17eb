// Scene overrides: `--set PATH=VALUE` (scene/scene_overrides.hpp).
#include "darcydem/scene/scene_overrides.hpp"

#include <charconv>
#include <string_view>

#include <fmt/format.h>

#include "darcydem/scene/toml_reader.hpp"

namespace darcydem {
namespace {

std::vector<std::string> split_path(std::string_view path) {
  std::vector<std::string> keys;
  std::size_t from = 0;
  while (true) {
    const std::size_t dot = path.find('.', from);
    keys.emplace_back(path.substr(from, dot == std::string_view::npos ? std::string_view::npos : dot - from));
    if (dot == std::string_view::npos) return keys;
    from = dot + 1;
  }
}

/// The element of an array of tables that `key` names: its `name`, or its
/// number from 1; nullptr (with `known` listing what there is) if none.
toml::table* element(toml::array& array, const std::string& key, std::string& known) {
  std::size_t number = 0;
  const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), number);
  const bool is_number = ec == std::errc() && end == key.data() + key.size();
  for (std::size_t k = 0; k < array.size(); ++k) {
    toml::table* t = array.get(k)->as_table();
    if (t == nullptr) continue;
    const auto name = (*t)["name"].value<std::string>();
    known +=
        fmt::format("{}{}", known.empty() ? "" : ", ", name ? "'" + *name + "'" : fmt::format("#{}", k + 1));
    if ((is_number && number == k + 1) || (!is_number && name && *name == key)) return t;
  }
  return nullptr;
}

/// Refuses an override: the message names it, `--set PATH=VALUE`.
[[noreturn]] void refuse(const std::string& source, const std::string& message) {
  throw SceneError(fmt::format("{}: error: {}", source, message));
}

}  // namespace

void apply_scene_overrides(toml::table& root, const std::vector<std::string>& overrides,
                           const std::string& file, std::string& text) {
  for (const auto& given : overrides) {
    const std::string source = "--set " + given;
    const std::size_t eq = given.find('=');
    if (eq == std::string::npos || eq == 0) {
      refuse(source,
             "give PATH=VALUE, e.g. fluid.bulk_modulus=1e5, wall.floor.velocity=[0.0, -0.1] or "
             "stage.shear.duration=0.2");
    }
    const std::string path = given.substr(0, eq);
    const auto keys = split_path(path);
    for (const auto& k : keys) {
      if (k.empty()) refuse(source, fmt::format("'{}' has an empty key between its dots", path));
      if (k.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-") !=
          std::string::npos) {
        refuse(source, fmt::format("'{}' in '{}' is not a key: keys are letters, digits, _ and -", k, path));
      }
    }
    // Down the tables the scene has; the first key it lacks and those after
    // it are made, as the file would make them.
    toml::table* table = &root;
    std::string walked;
    std::size_t i = 0;
    for (; i + 1 < keys.size(); ++i) {
      const std::string& key = keys[i];
      toml::node* next = table->get(key);
      if (next == nullptr) break;
      const std::string here = walked.empty() ? key : walked + "." + key;
      if (toml::array* array = next->as_array(); array != nullptr && array->is_array_of_tables()) {
        ++i;
        std::string known;
        table = element(*array, keys[i], known);
        if (table == nullptr) {
          refuse(source,
                 fmt::format("{} has no [[{}]] named or numbered '{}' (there are: {}; number them from 1)",
                             file, here, keys[i], known.empty() ? "none" : known));
        }
        walked = here + "." + keys[i];
        if (i + 1 == keys.size()) {
          refuse(source,
                 fmt::format("'{}' is a whole [[{}]]; name one of its keys, e.g. {}.name", path, key, path));
        }
        continue;
      }
      table = next->as_table();
      if (table == nullptr) refuse(source, fmt::format("'{}' in {} is a value, not a table", here, file));
      walked = here;
    }
    std::string dotted;
    for (std::size_t k = i; k < keys.size(); ++k) dotted += (k == i ? "" : ".") + keys[k];
    toml::table parsed;
    try {
      parsed = toml::parse(dotted + " = " + given.substr(eq + 1), source);
    } catch (const toml::parse_error& e) {
      refuse(source,
             fmt::format("'{}' is not a TOML value ({}): give a number, \"text\", true or false, [...] or "
                         "{{ key = ... }}",
                         given.substr(eq + 1), e.description()));
    }
    if (parsed.size() != 1)
      refuse(source, fmt::format("'{}' is more than one TOML value", given.substr(eq + 1)));
    // Moved, not copied: the nodes keep their source, `--set PATH=VALUE`,
    // which the scene reader's messages name.
    parsed.get(keys[i])->visit([&](auto&& node) { table->insert_or_assign(keys[i], std::move(node)); });
    text += "\n# " + source;
  }
}

}  // namespace darcydem
