#include "demo.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "broad_phase.hpp"
#include "compare.hpp"
#include "comparison_format.hpp"
#include "extreme_suite.hpp"
#include "peers/fcl_peer.hpp"
#include "plot.hpp"
#include "scenes.hpp"
#include "text_output.hpp"
#include "workload.hpp"

namespace batchccd::bench {
namespace {

using cli::FoundInput;
using cli::TableColumn;
using cli::fixed;
using cli::print_aligned;
using cli::write_file_atomically;

// The demo's default sizes: the cloth's steps from just before its first
// contact (step 73) through the fold, about 4 M candidates each. The whole
// demo costs about 55 CPU seconds (README, "The two commands").
constexpr int kClothResolution = 128;
constexpr int kClothSteps = 100;
constexpr int kClothFirstFrame = 68;
constexpr int kClothFrames = 12;
constexpr int kRigidResolution = 12;
// Every time reported is the best of 3 runs: other work on the machine only
// ever adds time, and one run of a fraction of a second moves by 10 to 25 %
// on a busy or shared machine. A method's step that took 50 ms or more (the
// baselines and FCL, at 5 to 20 times the modes' time) runs once: repeating
// those tripled most of the demo's run time for a disturbance that is a
// smaller share of them.
constexpr Timing kTiming{.runs = 3, .repeat_below_seconds = 0.05};

// One line that rewrites itself on a terminal; nothing elsewhere.
class Progress {
 public:
  explicit Progress(std::ostream* terminal) : terminal_(terminal) {}
  ~Progress() { clear(); }
  void show(const std::string& text) {
    if (terminal_) *terminal_ << "\r\033[K" << text << std::flush;
  }
  void clear() {
    if (terminal_) *terminal_ << "\r\033[K" << std::flush;
  }

 private:
  std::ostream* terminal_;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Every method on one workload: exact mode first, as the TOI reference and,
// without ground truth in the workload, as the truth.
void compare_on(const Workload& workload, int threads, std::vector<MethodTally>& tallies,
                Progress& progress, const std::string& where) {
  progress.show(where + ": exact");
  const MethodRun exact = run_method(Method::exact, workload, threads, kTiming);
  const std::vector<bool> truth = workload.truth ? *workload.truth : decisions(exact);
  for (MethodTally& tally : tallies) {
    if (tally.method == Method::exact) {
      tally.add(exact, truth, exact.results);
      continue;
    }
    progress.show(where + ": " + std::string(name_of(tally.method)));
    tally.add(run_method(tally.method, workload, threads, kTiming), truth, exact.results);
  }
}

std::vector<MethodTally> empty_tallies() {
  std::vector<MethodTally> tallies;
  for (const Method method : compared_methods()) tallies.push_back({.method = method});
  return tallies;
}

// ---- what a call pays for ---------------------------------------------------

struct CostVariant {
  CostVariant(std::string_view what, std::function<void(Options&)> asks, bool into_last = false)
      : name(what), ask(std::move(asks)), into_last_result(into_last) {}

  std::string_view name;
  std::function<void(Options&)> ask;
  bool into_last_result;  // the call writes into the previous step's BatchResult
  double seconds = 0;
  BatchResult last;
};

// Each against the first: a call that asks for everything.
std::vector<CostVariant> cost_variants() {
  return {
      {"everything: TOI, vf + ee, a result per candidate", [](Options&) {}},
      {"the same into the last step's BatchResult", [](Options&) {}, true},
      {"hit/no-hit only (need_toi = false)", [](Options& o) { o.need_toi = false; }},
      {"vf only", [](Options& o) { o.edge_edge = false; }},
      {"ee only", [](Options& o) { o.vertex_face = false; }},
      {"the hits only (hit_list, no per-candidate results)",
       [](Options& o) {
         o.per_candidate_results = false;
         o.hit_list = true;
       }},
      {"earliest TOI only (per_candidate_results = false)",
       [](Options& o) { o.per_candidate_results = false; }},
  };
}

// Each variant's best of 3 runs on the step, the runs in rounds of every
// variant in turn: a variant's runs spread over the same stretch of the
// machine's load as the others' (timed one after another, the row after
// "everything" read 104 to 106 % of it though it asks for less).
void time_costs(const Workload& workload, int threads, std::vector<CostVariant>& variants,
                Progress& progress, const std::string& where) {
  std::vector<double> fastest(variants.size(), std::numeric_limits<double>::infinity());
  for (int round = 0; round < kTiming.runs; ++round) {
    for (std::size_t v = 0; v < variants.size(); ++v) {
      CostVariant& variant = variants[v];
      progress.show(where + ": " + std::string(variant.name));
      Options options;
      options.threads = threads;
      variant.ask(options);
      fastest[v] = std::min(fastest[v], fastest_of({}, [&] {
                              if (variant.into_last_result) {
                                workload.run(options, variant.last);
                              } else {
                                workload.run(options);
                              }
                            }));
    }
  }
  for (std::size_t v = 0; v < variants.size(); ++v) variants[v].seconds += fastest[v];
}

void print_costs(std::ostream& out, const std::vector<CostVariant>& variants) {
  constexpr TableColumn columns[] = {{"asked for", false}, {"seconds", true}, {"of everything", true}};
  const double everything = variants.front().seconds;
  std::vector<std::vector<std::string>> rows;
  for (const CostVariant& v : variants)
    rows.push_back({std::string(v.name), fixed(v.seconds, 3),
                    everything > 0 ? fixed(100 * v.seconds / everything, 0) + " %" : "-"});
  print_aligned(out, columns, rows);
}

// ---- scenes -------------------------------------------------------------------

Workload workload_of(scenes::MovingMesh mesh) {
  MeshWorkload source;
  source.positions_t0 = std::move(mesh.positions_t0);
  source.positions_t1 = std::move(mesh.positions_t1);
  source.faces = std::move(mesh.faces);
  source.candidates = scenes::swept_box_candidates(source.view(), scenes::mean_edge_length(source.view()));
  return {mesh.name, std::move(source), std::nullopt};
}

// The scene's steps, each made when it is needed (one step's candidates in
// memory at a time).
struct SceneSteps {
  std::string description;
  std::vector<std::function<scenes::MovingMesh()>> steps;
};

SceneSteps scene_steps(const DemoSettings& settings) {
  SceneSteps scene;
  if (settings.scene == BuiltinScene::rigid) {
    const int resolution = settings.resolution > 0 ? settings.resolution : kRigidResolution;
    scene.description = "rigid bodies (thin plates and rods moving far within one step), resolution " +
                        std::to_string(resolution);
    scene.steps.push_back([resolution] { return scenes::rigid_scene({.resolution = resolution}); });
    return scene;
  }
  const int resolution = settings.resolution > 0 ? settings.resolution : kClothResolution;
  scene.description = "cloth (a sheet that drapes, folds and twists onto itself), " +
                      std::to_string(resolution) + " x " + std::to_string(resolution) +
                      " vertices, steps " + std::to_string(kClothFirstFrame) + "-" +
                      std::to_string(kClothFirstFrame + kClothFrames - 1) + " of " +
                      std::to_string(kClothSteps);
  for (int frame = kClothFirstFrame; frame < kClothFirstFrame + kClothFrames; ++frame)
    scene.steps.push_back([resolution, frame] {
      return scenes::cloth_scene({.resolution = resolution, .frames = kClothSteps, .frame = frame});
    });
  return scene;
}

std::string millions(std::int64_t count) { return fixed(static_cast<double>(count) / 1e6, 2) + " M"; }

// Prints a finished section and keeps it for report.txt.
class Report {
 public:
  explicit Report(std::ostream& out) : out_(out) {}
  void add(const std::string& section) {
    out_ << section << std::flush;
    text_ += section;
  }
  const std::string& text() const { return text_; }

 private:
  std::ostream& out_;
  std::string text_;
};

// methods.csv, plot.gp and (gnuplot permitting) plot.png; report.txt when
// there is a text. A missing gnuplot is said, not an error.
void write_outputs(const std::filesystem::path& directory, const std::string& title,
                   const std::vector<std::pair<std::string, MethodTally>>& csv_rows,
                   const std::string* text, std::ostream& out) {
  std::filesystem::create_directories(directory);
  std::vector<std::filesystem::path> written;
  if (text) {
    write_file_atomically(directory / "report.txt", [&](std::ostream& o) { o << *text; });
    written.push_back(directory / "report.txt");
  }
  write_file_atomically(directory / "methods.csv",
                        [&](std::ostream& o) { write_comparison_csv(o, csv_rows); });
  written.push_back(directory / "methods.csv");
  // The script names the files relative to the directory gnuplot runs in.
  write_file_atomically(directory / "plot.gp", [&](std::ostream& o) {
    std::vector<std::string> methods;
    for (const Method method : compared_methods()) methods.emplace_back(name_of(method));
    o << plot_script(title, "methods.csv", "plot.png", methods);
  });
  std::string note;
  if (const std::optional<std::filesystem::path> gnuplot = find_gnuplot()) {
    run_gnuplot(*gnuplot, directory, "plot.gp");
    written.push_back(directory / "plot.png");
  } else {
    note = "plot.png not drawn: gnuplot not found (apt-get install gnuplot-nox); "
           "plot.gp draws it from methods.csv\n";
  }
  written.push_back(directory / "plot.gp");
  out << "wrote";
  for (std::size_t i = 0; i < written.size(); ++i) out << (i ? ", " : " ") << written[i].string();
  out << '\n' << note;
}

std::string method_legend() {
  std::ostringstream legend;
  for (const Method method : compared_methods())
    legend << "  " << std::left << std::setw(13) << name_of(method) << description_of(method) << '\n';
  if (!peers::fcl_available())
    legend << "  " << std::left << std::setw(13) << "fcl" << "not available: built without FCL (libfcl-dev)\n";
  return legend.str();
}

}  // namespace

void run_demo(const DemoSettings& settings, std::ostream& out, std::ostream* terminal) {
  Progress progress(terminal);
  Report report(out);
  const SceneSteps scene = scene_steps(settings);
  std::vector<MethodTally> tallies = empty_tallies();
  std::vector<CostVariant> costs = cost_variants();
  std::int64_t vertex_face = 0, edge_edge = 0;
  double broad_phase_seconds = 0;
  for (std::size_t k = 0; k < scene.steps.size(); ++k) {
    const std::string where = "step " + std::to_string(k + 1) + "/" + std::to_string(scene.steps.size());
    progress.show(where + ": scene and broad phase");
    const auto start = std::chrono::steady_clock::now();
    const Workload workload = workload_of(scene.steps[k]());
    broad_phase_seconds += seconds_since(start);
    const auto& candidates = std::get<MeshWorkload>(workload.source).candidates;
    vertex_face += static_cast<std::int64_t>(candidates.vertex_face.size());
    edge_edge += static_cast<std::int64_t>(candidates.edge_edge.size());
    compare_on(workload, settings.threads, tallies, progress, where);
    if (settings.sections) time_costs(workload, settings.threads, costs, progress, where);
  }
  progress.clear();

  std::ostringstream header;
  header << "batchccd_report demo: built-in " << scene.description << '\n'
         << "  " << millions(vertex_face + edge_edge) << " candidates (vf " << millions(vertex_face)
         << ", ee " << millions(edge_edge) << ") from a swept-box broad phase ("
         << fixed(broad_phase_seconds, 1) << " s with the scene, not counted below)\n"
         << "  isa " << to_string(resolve_isa(Isa::automatic)) << ", threads "
         << (settings.threads > 0 ? std::to_string(settings.threads) : "all") << "; ground truth and TOI reference: exact mode\n\n"
         << "Methods\n" << method_legend() << '\n';
  std::ostringstream methods;
  print_comparison(methods, tallies);
  methods << "Every method hands back its hits only (Options::hit_list), as a simulator would ask.\n"
          << "Seconds: the sum over the steps of each step's best of 3 runs, or of its one run where\n"
          << "that took 50 ms or more.\n";
  report.add(header.str() + methods.str() + '\n');

  if (settings.sections) {
    std::int64_t to_solver = 0;
    for (const MethodTally& t : tallies)
      if (t.method == Method::conservative) to_solver = t.candidates - t.culled;
    std::ostringstream section;
    section << "What a call pays for (conservative mode, the same candidates)\n";
    print_costs(section, costs);
    section << "The first five rows ask for a result per candidate (" << millions(vertex_face + edge_edge)
            << ", 24 bytes each):\n"
            << "writing those costs more than the filters, which is why \"everything\" takes longer than\n"
            << "conservative mode in the methods table above, where every method asks for its hits alone\n"
            << "(the row \"the hits only\"). need_toi = false changes only what the solver does with the\n"
            << "candidates the filters leave, " << to_solver << " of them here ("
            << fixed(100 * static_cast<double>(to_solver) / static_cast<double>(std::max<std::int64_t>(1, vertex_face + edge_edge)), 3)
            << " %): its row is \"everything\"\n"
            << "to within the machine's noise. The row after \"everything\" saves allocating the results.\n";
    report.add(section.str() + '\n');

    progress.show("stiff and extreme suite");
    const auto rows = scenes::evaluate_extreme(scenes::extreme_categories(), {.threads = settings.threads});
    progress.clear();
    std::ostringstream extreme;
    extreme << "Stiff and extreme inputs (each mode and baseline against exact mode)\n";
    scenes::write_extreme_table(extreme, rows);
    extreme << "agree, false-, false+: decisions against exact mode's. NaN, bad toi: TOIs that are NaN, or\n"
            << "neither in [0, 1] on a hit nor +inf on a miss. late toi: hits reported after the first\n"
            << "contact. truth wrong a/b: of the b queries whose answer their construction proves (integer\n"
            << "coordinates, exact in double), a decided otherwise; exact mode's 0 shows that its decisions,\n"
            << "the truth of the other columns, are right there. escalated: queries exact arithmetic\n"
            << "settled. undecided: queries whose search ran out of Options::max_iterations boxes and\n"
            << "were reported as hits, each after up to about a second (max ms).\n";
    report.add(extreme.str() + '\n');
  }

  std::vector<std::pair<std::string, MethodTally>> csv_rows;
  for (const MethodTally& t : tallies) csv_rows.emplace_back("total", t);  // one workload: the total
  write_outputs(settings.out, "batchccd_report demo: " + scene.description, csv_rows, &report.text(), out);
}

bool run_report(const ReportSettings& settings, std::ostream& out, std::ostream& errors,
                std::ostream* terminal) {
  Progress progress(terminal);
  std::vector<MethodTally> totals = empty_tallies();
  std::vector<std::pair<std::string, MethodTally>> csv_rows;
  std::int64_t candidates = 0, without_truth = 0;
  bool all_read = true;
  for (const auto& input : settings.inputs) {
    std::vector<FoundInput> found;
    try {
      found = cli::find_inputs(input, settings.kind, errors);
    } catch (const std::exception& error) {
      errors << "batchccd: error: " << error.what() << '\n';
      all_read = false;
    }
    for (const FoundInput& item : found) {
      try {
        progress.show(item.path.string() + ": reading");
        const Workload workload = read_workload(item, settings.kind);
        std::vector<MethodTally> tallies = empty_tallies();
        compare_on(workload, settings.threads, tallies, progress, item.path.string());
        candidates += static_cast<std::int64_t>(workload.size());
        if (!workload.truth) without_truth += static_cast<std::int64_t>(workload.size());
        for (std::size_t m = 0; m < tallies.size(); ++m) {
          totals[m] += tallies[m];
          csv_rows.emplace_back(workload.name, tallies[m]);
        }
      } catch (const std::exception& error) {
        progress.clear();
        errors << "batchccd: error: " << error.what() << '\n';
        all_read = false;
      }
    }
  }
  progress.clear();
  // The plot's title says what was compared, as the text's first line does.
  const std::string compared = "batchccd_report report: " +
                               std::to_string(csv_rows.size() / std::max<std::size_t>(1, totals.size())) +
                               " inputs, " + std::to_string(candidates) + " candidates";
  out << compared << "; ground truth from the files"
      << (without_truth > 0 ? " (exact mode's decisions for " + std::to_string(without_truth) +
                                  " candidates without)"
                            : "")
      << "; TOI reference: exact mode\n\nMethods\n"
      << method_legend() << '\n';
  print_comparison(out, totals);
  for (const MethodTally& t : totals) csv_rows.emplace_back("total", t);
  if (settings.out) write_outputs(*settings.out, compared, csv_rows, nullptr, out);
  return all_read;
}

}  // namespace batchccd::bench
