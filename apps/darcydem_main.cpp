// darcydem: the command-line program, a thin layer over the library.
//   darcydem run SCENE --out DIR [--force | --resume] [--checkpoint-every S] [--threads N] [--set
//   PATH=VALUE]... darcydem check SCENE [--set PATH=VALUE]... darcydem --version
#include <omp.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "darcydem/output/checkpoint_archive.hpp"
#include "darcydem/particles/grading.hpp"
#include "darcydem/scene/scene.hpp"
#include "darcydem/scene/scene_cell.hpp"
#include "darcydem/scene/scene_overrides.hpp"
#include "darcydem/scene/toml_reader.hpp"
#include "darcydem/simulation/describe_walls.hpp"
#include "darcydem/simulation/runner.hpp"
#include "darcydem/version.hpp"

namespace {

// The one piece of process-wide state: set by SIGINT/SIGTERM, read by the run loop.
std::atomic<bool> g_interrupt{false};

void on_signal(int) { g_interrupt.store(true); }

struct RunFlags {
  std::string out;
  bool check_only = false;
  bool resume = false;
  double checkpoint_every = 0.0;
  std::vector<std::string> overrides;  ///< --set PATH=VALUE
};

template <int D>
int run(const toml::table& root, const std::string& file, const std::string& text, const RunFlags& flags) {
  const std::string& out = flags.out;
  const bool check_only = flags.check_only;
  auto scene = darcydem::build_scene<D>(root, file, text);
  scene.overrides = flags.overrides;
  if (check_only) {
    // The stages' durations in steps: at most, as a stage may stop early.
    double duration = 0.0;
    for (const auto& stage : scene.stages) duration += stage.duration;
    std::cout << fmt::format(
        "{}: OK ({}D, {} particles, {} wall{}, {} stage{}, time step {:.4g} s, at most {:.0f} steps)\n", file,
        D, scene.simulation.particles.size(), scene.simulation.walls.size(),
        scene.simulation.walls.size() == 1 ? "" : "s", scene.stages.size(),
        scene.stages.size() == 1 ? "" : "s", scene.simulation.time_step,
        std::ceil(duration / scene.simulation.time_step));
    if (scene.simulation.particles.size() > 0) {
      std::cout << "  " << darcydem::describe_grading<D>(scene.simulation.particles.radius);
    }
    for (const auto& set : scene.overrides) std::cout << "  set: " << set << '\n';
    for (const auto& note : scene.notes) std::cout << "  note: " << note << '\n';
    {
      std::istringstream lines(darcydem::describe_wall_motions(scene) +
                               darcydem::describe_cell_motions(scene));
      for (std::string line; std::getline(lines, line);) std::cout << "  " << line << '\n';
    }
    if (scene.fluid) {
      const auto& f = *scene.fluid;
      const double dry = scene.simulation.critical_time_step();
      const double wet = f.critical_time_step(scene.simulation.particles, dry);
      std::cout << fmt::format(
          "  pore fluid: {} cells, K_f = {:.4g} Pa, {} solver, fluid step every {} DEM steps{}; "
          "critical step {}\n",
          f.grid.size(), f.fluid.bulk_modulus, darcydem::to_string(f.solver().kind()), f.steps_per_update,
          f.hold_forces ? " (forces held)" : "",
          std::isinf(wet) ? darcydem::describe_critical_step(wet)
                          : fmt::format("{} (dry {})", darcydem::describe_critical_step(wet),
                                        darcydem::describe_critical_step(dry)));
      std::cout << "  " << darcydem::describe_grid(f.grid);
      std::istringstream lines(darcydem::describe_permeability(f, scene.simulation.particles) +
                               darcydem::describe_patches_and_barriers(f, scene.simulation.walls));
      for (std::string line; std::getline(lines, line);) std::cout << "  " << line << '\n';
    }
    return 0;
  }
  darcydem::RunOptions options;
  options.out_dir = out;
  options.interrupt = &g_interrupt;
  options.log = &std::cerr;
  options.terminal = isatty(STDERR_FILENO) != 0;
  options.resume = flags.resume;
  options.checkpoint_every = flags.checkpoint_every;
  const auto summary = darcydem::run_scene<D>(scene, options);
  std::cerr << fmt::format("{}: {} steps, {:.6g} s simulated in {:.2f} s wall time; output in {}\n",
                           summary.interrupted ? "interrupted" : "done", summary.steps,
                           summary.simulated_time, summary.wall_time, out);
  if (summary.interrupted && summary.checkpoint_written) {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(std::filesystem::path(out) / "checkpoint.bin", ec);
    std::cerr << fmt::format("checkpoint: {}/checkpoint.bin ({:.3g} MB)\n", out,
                             ec ? 0.0 : static_cast<double>(bytes) / 1e6);
    std::string sets;
    for (const auto& set : flags.overrides) sets += fmt::format(" --set '{}'", set);
    std::cerr << fmt::format("to go on from here: darcydem run {} --out {} --resume{}\n", file, out, sets);
  }
  return summary.interrupted ? 130 : 0;
}

int dispatch(const std::string& file, const RunFlags& flags) {
  std::string text;
  toml::table root = darcydem::parse_toml_file(file, text);
  darcydem::apply_scene_overrides(root, flags.overrides, file, text);
  const int dim = darcydem::scene_dimension(root, file);
  return dim == 2 ? run<2>(root, file, text, flags) : run<3>(root, file, text, flags);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"darcydem: DEM of discs and spheres coupled with Darcy pore-fluid flow"};
  app.set_version_flag("--version", std::string("darcydem ") + darcydem::version_string);
  app.require_subcommand(1);

  std::string scene_file;
  std::string out_dir;
  bool force = false;
  bool resume = false;
  double checkpoint_every = 0.0;
  int threads = 0;
  auto* run_cmd = app.add_subcommand("run", "run a scene and write its output directory");
  run_cmd->add_option("scene", scene_file, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  run_cmd->add_option("--out,-o", out_dir, "output directory")->required();
  auto* force_flag = run_cmd->add_flag("--force", force, "write into a non-empty output directory");
  run_cmd
      ->add_flag(
          "--resume", resume,
          "go on with the interrupted run in the output directory, from its checkpoint.bin (same scene "
          "file)")
      ->excludes(force_flag);
  run_cmd
      ->add_option("--checkpoint-every", checkpoint_every,
                   "seconds of wall time between checkpoints (default 0: only when interrupted)")
      ->check(CLI::Validator(
          [](const std::string& value) {
            double s = -1.0;
            return CLI::detail::lexical_cast(value, s) && s >= 0.0 && std::isfinite(s)
                       ? std::string()
                       : "'" + value +
                             "' is not allowed: a number of seconds >= 0 (0: only when interrupted)";
          },
          "SECONDS >= 0"));
  run_cmd->add_option("--threads,-j", threads, "OpenMP threads (default 0: all cores)")
      ->check(CLI::Validator(
          [](const std::string& value) {
            int n = -1;
            return CLI::detail::lexical_cast(value, n) && n >= 0
                       ? std::string()
                       : "'" + value + "' is not allowed: a whole number of threads >= 0 (0: all cores)";
          },
          "N >= 0"));

  std::vector<std::string> overrides;
  const std::string set_help =
      "change the scene before it is built, as if the file said so (repeatable): PATH=VALUE, PATH dotted "
      "keys "
      "through its tables, an array's element by its name or number from 1 (fluid.bulk_modulus=1e5, "
      "wall.floor.velocity=[0.0,-0.1], stage.shear.duration=0.2, contact.1.friction=0.3), VALUE in TOML";
  run_cmd->add_option("--set", overrides, set_help)
      ->type_name("PATH=VALUE")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);

  std::string check_file;
  auto* check_cmd = app.add_subcommand("check", "validate a scene without running it");
  check_cmd->add_option("scene", check_file, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  check_cmd->add_option("--set", overrides, set_help)
      ->type_name("PATH=VALUE")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);

  CLI11_PARSE(app, argc, argv);
  try {
    if (*check_cmd) return dispatch(check_file, RunFlags{"", true, false, 0.0, overrides});
    if (std::error_code ec;
        std::filesystem::exists(out_dir, ec) && !std::filesystem::is_directory(out_dir, ec)) {
      std::cerr << fmt::format("error: --out '{}' is a file; give a directory (it is made if absent)\n",
                               out_dir);
      return 2;
    }
    if (!force && !resume && !darcydem::output_dir_is_free(out_dir)) {
      std::cerr << fmt::format("error: output directory '{}' is not empty; use --force to write into it\n",
                               out_dir);
      return 2;
    }
    if (threads > 0) omp_set_num_threads(threads);
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    // A reader of the log that goes away (`darcydem run ... | head`) stops
    // the run as Ctrl-C does, with its output kept, instead of killing it.
    std::signal(SIGPIPE, on_signal);
    return dispatch(scene_file, RunFlags{out_dir, false, resume, checkpoint_every, overrides});
  } catch (const darcydem::SceneError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const darcydem::CheckpointError& e) {
    std::cerr << "error: cannot resume: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
