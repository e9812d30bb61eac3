// batchccd_make_candidates: dense candidate lists for benchmark scenes.
// Runs the swept-box broad phase on a scene directory's mesh or on a
// built-in scene and writes a scene directory with the dense vf.csv/ee.csv
// (no truth files), printing the counts and the broad phase's time; with
// --evaluate it also runs batchccd's conservative mode on the lists.

#include <charconv>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "batchccd/io.hpp"
#include "broad_phase.hpp"
#include "scene_writer.hpp"
#include "scenes.hpp"

namespace {

namespace fs = std::filesystem;
using namespace batchccd;

constexpr std::string_view usage =
    "usage: batchccd_make_candidates [options] SCENE_DIR...\n"
    "       batchccd_make_candidates [options] --builtin cloth|rigid --size N\n"
    "\n"
    "Runs a swept-box broad phase (boxes over t0 and t1, each grown by a margin)\n"
    "and writes OUT/NAME/{t0.ply,t1.ply,vf.csv,ee.csv}: the same meshes, every\n"
    "vertex-face and edge-edge pair whose grown boxes overlap, no truth files.\n"
    "SCENE_DIR is a scene directory (e.g. ../shared/data/scenes/cloth-funnel-227);\n"
    "NAME is its last component, or the built-in scene's name.\n"
    "\n"
    "Options:\n"
    "  --out DIR            where to write (default /tmp/batchccd-scenes)\n"
    "  --margin-factor F    margin in mean edge lengths at t0 (default 1)\n"
    "  --builtin KIND       cloth: a sheet that drapes, folds and twists onto\n"
    "                       itself; rigid: thin bodies moving far in one step\n"
    "  --size N             cloth: vertices per side (default 64); rigid: grid\n"
    "                       cells per body length (default 8)\n"
    "  --frame K            cloth: the step returned (default 76)\n"
    "  --frames K           cloth: steps in the whole motion (default 100)\n"
    "  --no-write           count and time only\n"
    "  --evaluate           also run batchccd::mesh_ccd (conservative mode, all\n"
    "                       threads) on the lists; print how many candidates\n"
    "                       its filters culled, how many went to the solver,\n"
    "                       the hits and the time\n"
    "  -h, --help           this text\n";

struct Settings {
  std::vector<fs::path> scene_directories;
  std::optional<std::string> builtin;
  std::optional<int> size;
  scenes::ClothOptions cloth;
  fs::path out = "/tmp/batchccd-scenes";
  double margin_factor = 1.0;
  bool write = true;
  bool evaluate = false;
};

struct UsageError {
  std::string message;
};

template <class Number>
Number parse_number(std::string_view option, std::string_view text) {
  Number value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size())
    throw UsageError{std::string(option) + ": not a number: " + std::string(text)};
  return value;
}

Settings parse(int argc, char** argv) {
  Settings settings;
  std::vector<std::string_view> arguments(argv + 1, argv + argc);
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    const std::string_view argument = arguments[i];
    auto value = [&]() -> std::string_view {
      if (i + 1 >= arguments.size()) throw UsageError{std::string(argument) + " needs a value"};
      return arguments[++i];
    };
    if (argument == "-h" || argument == "--help") {
      std::cout << usage;
      std::exit(0);
    } else if (argument == "--out") {
      settings.out = fs::path(value());
    } else if (argument == "--margin-factor") {
      settings.margin_factor = parse_number<double>(argument, value());
    } else if (argument == "--builtin") {
      settings.builtin = std::string(value());
      if (settings.builtin != "cloth" && settings.builtin != "rigid")
        throw UsageError{"--builtin: cloth or rigid, not " + *settings.builtin};
    } else if (argument == "--size") {
      settings.size = parse_number<int>(argument, value());
    } else if (argument == "--frame") {
      settings.cloth.frame = parse_number<int>(argument, value());
    } else if (argument == "--frames") {
      settings.cloth.frames = parse_number<int>(argument, value());
    } else if (argument == "--no-write") {
      settings.write = false;
    } else if (argument == "--evaluate") {
      settings.evaluate = true;
    } else if (argument.starts_with("-")) {
      throw UsageError{"unknown option " + std::string(argument)};
    } else {
      settings.scene_directories.emplace_back(argument);
    }
  }
  if (settings.builtin.has_value() == !settings.scene_directories.empty())
    throw UsageError{"give either scene directories or --builtin"};
  if (!(settings.margin_factor >= 0)) throw UsageError{"--margin-factor must be >= 0"};
  return settings;
}

// The directory's last component, also for "a/b/" and ".".
std::string scene_name(const fs::path& directory) {
  fs::path path = fs::absolute(directory).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();
  return path.filename().string();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void evaluate(const MeshView& mesh, const Candidates& candidates) {
  Options options;  // conservative mode, all threads
  options.per_candidate_results = false;
  const auto start = std::chrono::steady_clock::now();
  const Counters c = mesh_ccd(mesh, candidates, options).counters;
  const double seconds = seconds_since(start);
  const double all = c.candidates > 0 ? static_cast<double>(c.candidates) : 1.0;
  std::printf("  conservative: culled %lld (%.2f %%), solved %lld (%.2f %%), hits %lld, "
              "undecided %lld; %.3f s, %.3g candidates/s\n",
              static_cast<long long>(c.culled), 100 * static_cast<double>(c.culled) / all,
              static_cast<long long>(c.solved), 100 * static_cast<double>(c.solved) / all,
              static_cast<long long>(c.hits), static_cast<long long>(c.undecided), seconds,
              static_cast<double>(c.candidates) / seconds);
}

// `source`: the scene directory read, which must never be overwritten.
void process(const std::string& name, const MeshView& mesh, const Settings& settings,
             const fs::path& source = {}) {
  const double edge = scenes::mean_edge_length(mesh);
  const double margin = settings.margin_factor * edge;
  const auto start = std::chrono::steady_clock::now();
  const Candidates candidates = scenes::swept_box_candidates(mesh, margin);
  const double broad_phase_seconds = seconds_since(start);
  std::printf("%s: %lld vertices, %lld faces, mean edge %.4g, margin %.4g; %zu vf + %zu ee = %zu "
              "candidates; broad phase %.3f s\n",
              name.c_str(), static_cast<long long>(mesh.positions_t0.rows()),
              static_cast<long long>(mesh.faces.rows()), edge, margin, candidates.vertex_face.size(),
              candidates.edge_edge.size(),
              candidates.vertex_face.size() + candidates.edge_edge.size(), broad_phase_seconds);
  if (settings.evaluate) evaluate(mesh, candidates);
  if (!settings.write) return;
  const fs::path directory = settings.out / name;
  std::error_code ignored;
  if (!source.empty() && fs::equivalent(directory, source, ignored))
    throw std::runtime_error("refusing to overwrite the input " + source.string() + "; pick another --out");
  const auto write_start = std::chrono::steady_clock::now();
  scenes::write_scene_directory(directory, mesh, candidates);
  std::printf("  written to %s in %.2f s\n", directory.c_str(), seconds_since(write_start));
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  try {
    settings = parse(argc, argv);
  } catch (const UsageError& error) {
    std::cerr << "batchccd_make_candidates: " << error.message << "\n\n" << usage;
    return 2;
  }
  try {
    if (settings.builtin == "cloth") {
      if (settings.size) settings.cloth.resolution = *settings.size;
      const scenes::MovingMesh mesh = scenes::cloth_scene(settings.cloth);
      process(mesh.name, mesh.view(), settings);
    } else if (settings.builtin == "rigid") {
      scenes::RigidOptions options;
      if (settings.size) options.resolution = *settings.size;
      const scenes::MovingMesh mesh = scenes::rigid_scene(options);
      process(mesh.name, mesh.view(), settings);
    }
    for (const fs::path& directory : settings.scene_directories) {
      const Scene scene = read_scene(directory);
      const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
      process(scene_name(directory), mesh, settings, directory);
    }
  } catch (const std::exception& error) {
    std::cerr << "batchccd_make_candidates: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
