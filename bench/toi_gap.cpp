// The gap between conservative mode's TOI and the first contact (exact
// mode's TOI, within 2^-40 of it) over ../shared/data (sample queries and
// scenes) and the stiff and extreme suite: per input the hits, the largest
// gap, how many gaps exceed toi_tolerance, conservative hits exact mode
// calls misses (within tolerance), TOIs after the contact; then the worst
// queries. Prints; asserts nothing. Usage: batchccd_toi_gap [shared-data-dir]
#include <algorithm>
#include <chrono>
#include <utility>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "batchccd/batchccd.hpp"
#include "extreme_suite.hpp"
#include "shared_data_inputs.hpp"

namespace {

using namespace batchccd;
namespace fs = std::filesystem;

struct Worst {
  double gap;
  std::string input;
  Kind kind;
  std::size_t index;
  double exact_toi, conservative_toi;
};

struct Totals {
  std::int64_t hits = 0, over = 0, within_tolerance_only = 0, late = 0, escalations = 0;
  double max_gap = 0, seconds = 0;
};

struct Listed {
  std::string input;
  Kind kind;
  std::size_t index;
  double conservative_toi;
};
std::vector<Listed> within_tolerance_hits;

std::vector<Worst> worst;
Totals all;

// The conservative call's exact-stage count and time go with its results.
void compare(const std::string& input, Kind kind, const std::vector<QueryResult>& exact,
             const BatchResult& conservative_batch, double seconds, double toi_tolerance) {
  const std::vector<QueryResult>& conservative = conservative_batch.results;
  Totals here;
  here.escalations = conservative_batch.counters.exact_escalations;
  here.seconds = seconds;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    const QueryResult &e = exact[i], &c = conservative[i];
    if (c.hit && !e.hit) {
      ++here.within_tolerance_only;
      within_tolerance_hits.push_back({input, kind, i, c.toi});
    }
    if (!e.hit || !c.hit) continue;
    ++here.hits;
    const double gap = e.toi - c.toi;
    if (gap < -0x1p-40) ++here.late;
    if (gap > toi_tolerance) {
      ++here.over;
      worst.push_back({gap, input, kind, i, e.toi, c.toi});
    }
    here.max_gap = std::max(here.max_gap, gap);
  }
  std::printf("%-60s %-3s hits %7lld  max gap %.3e  gaps > tol %5lld  c-hit/e-miss %4lld  late %lld"
              "  exact stage %5lld  %.3f s\n",
              input.c_str(), to_string(kind), static_cast<long long>(here.hits), here.max_gap,
              static_cast<long long>(here.over), static_cast<long long>(here.within_tolerance_only),
              static_cast<long long>(here.late), static_cast<long long>(here.escalations), here.seconds);
  all.hits += here.hits;
  all.over += here.over;
  all.within_tolerance_only += here.within_tolerance_only;
  all.late += here.late;
  all.max_gap = std::max(all.max_gap, here.max_gap);
  all.escalations += here.escalations;
  all.seconds += here.seconds;
}

template <class Call>
std::pair<BatchResult, double> timed(Call call) {
  const auto start = std::chrono::steady_clock::now();
  BatchResult result = call();
  return {std::move(result), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

Options with_mode(Mode mode) {
  Options options;
  options.mode = mode;
  options.threads = 1;
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path data = argc > 1 ? fs::path(argv[1]) : fs::path(BATCHCCD_SHARED_DATA);
  const double toi_tolerance = Options{}.toi_tolerance;
  const scenes::SharedDataInputs shared = scenes::shared_data_inputs(data);
  for (const fs::path& file : shared.query_files) {
    const std::optional<Kind> kind = kind_from_path(file);
    const QueryFile queries = read_query_csv(file, *kind);
    const BatchResult exact = batch_ccd(*kind, queries.queries, with_mode(Mode::exact));
    const auto [conservative, seconds] =
        timed([&] { return batch_ccd(*kind, queries.queries, with_mode(Mode::conservative)); });
    compare(fs::relative(file, data).string(), *kind, exact.results, conservative, seconds, toi_tolerance);
  }
  for (const fs::path& directory : shared.scenes) {
    const Scene scene = read_scene(directory);
    const MeshView mesh{scene.positions_t0, scene.positions_t1, scene.faces};
    for (const Kind kind : {Kind::vertex_face, Kind::edge_edge}) {
      Options exact_options = with_mode(Mode::exact), conservative_options = with_mode(Mode::conservative);
      for (Options* o : {&exact_options, &conservative_options}) {
        o->vertex_face = kind == Kind::vertex_face;
        o->edge_edge = kind == Kind::edge_edge;
        o->vertex_edge = o->vertex_vertex = false;
      }
      const BatchResult exact = mesh_ccd(mesh, scene.candidates, exact_options);
      const auto [conservative, seconds] =
          timed([&] { return mesh_ccd(mesh, scene.candidates, conservative_options); });
      compare(fs::relative(directory, data).string(), kind, exact.results, conservative, seconds, toi_tolerance);
    }
  }
  for (const scenes::ExtremeCategory& category : scenes::extreme_categories()) {
    const BatchResult exact = batch_ccd(category.kind, category.queries, with_mode(Mode::exact));
    const auto [conservative, seconds] =
        timed([&] { return batch_ccd(category.kind, category.queries, with_mode(Mode::conservative)); });
    compare("extreme: " + category.name, category.kind, exact.results, conservative, seconds, toi_tolerance);
  }
  std::printf("\nall: hits %lld  max gap %.3e  gaps > toi_tolerance (%.0e) %lld  c-hit/e-miss %lld  late %lld"
              "  exact stage %lld  conservative %.3f s (one thread)\n",
              static_cast<long long>(all.hits), all.max_gap, toi_tolerance, static_cast<long long>(all.over),
              static_cast<long long>(all.within_tolerance_only), static_cast<long long>(all.late),
              static_cast<long long>(all.escalations), all.seconds);
  std::sort(worst.begin(), worst.end(), [](const Worst& a, const Worst& b) { return a.gap > b.gap; });
  std::printf("worst:\n");
  for (std::size_t i = 0; i < std::min<std::size_t>(worst.size(), 15); ++i)
    std::printf("  gap %.3e  exact %.17g  conservative %.17g  %s %s #%zu\n", worst[i].gap, worst[i].exact_toi,
                worst[i].conservative_toi, worst[i].input.c_str(), to_string(worst[i].kind), worst[i].index);
  std::printf("conservative hits exact mode calls misses (within tolerance), first 15:\n");
  for (std::size_t i = 0; i < std::min<std::size_t>(within_tolerance_hits.size(), 15); ++i)
    std::printf("  toi %.17g  %s %s #%zu\n", within_tolerance_hits[i].conservative_toi,
                within_tolerance_hits[i].input.c_str(), to_string(within_tolerance_hits[i].kind),
                within_tolerance_hits[i].index);
  return 0;
}
