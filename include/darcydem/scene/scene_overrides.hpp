#pragma once
// Changes to a scene given on the command line (`darcydem run SCENE --set
// fluid.bulk_modulus=1e5`) or from Python (`darcydem.load(scene, set={...})`):
// a parameter sweep without a copy of the scene file per value.
#include <string>
#include <vector>

#include <toml++/toml.h>

namespace darcydem {

/// Sets each `PATH=VALUE` in the parsed scene `root` (from `file`) before it
/// is built. PATH is dotted keys through the scene's tables, e.g.
/// `fluid.bulk_modulus`, `fluid.boundary.y_max`; an array of tables
/// (`[[wall]]`, `[[stage]]`, `[[contact]]` ...) is entered by an element's
/// `name` or its number from 1, as the scene's messages count them:
/// `wall.floor.velocity`, `stage.shear.duration`, `contact.1.friction`.
/// The tables on the way must be in the scene; the last key may be new.
/// VALUE is a TOML value (`1e5`, `"cg"`, `[0.0, -0.1]`, `{ type =
/// "drained", pressure = 0.0 }`, `true`), which the scene reader then checks
/// as if it were in the file; its messages name the `--set PATH=VALUE`.
/// Appends each override to `text` (as a comment line), so that the scene's
/// hash, which a checkpoint keeps, tells one set of overrides from another.
/// Throws SceneError naming the override on a bad path or value.
void apply_scene_overrides(toml::table& root, const std::vector<std::string>& overrides,
                           const std::string& file, std::string& text);

}  // namespace darcydem
