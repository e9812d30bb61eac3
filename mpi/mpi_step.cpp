// One simulation step shared across MPI ranks, the way a distributed
// simulator uses batchccd: every rank evaluates its own share of the
// broad phase's candidates with one mesh_ccd call, and one MPI_Allreduce
// gives every rank the step's earliest TOI and summed counters. Nothing
// is shared between ranks but that reduction.
//
// The scene: the built-in cloth scene (bench/scenes.hpp) at a step where
// its flap passes through the layer below, candidates from the swept-box
// broad phase; each rank takes a contiguous slice of every list. With
// --check each rank also makes the single-process call over the whole
// lists and exits with status 1 unless the reduced earliest TOI equals it
// bit for bit, and the candidates counted too (and it has contacts, so that
// the comparison means something). Every mode of the library is run in turn.
//
//   mpirun -np 2 build/mpi/batchccd_mpi_step [--check] [--resolution N]
// (on one machine without an ssh client: OMPI_MCA_plm=isolated mpirun ...)
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <span>
#include <string>
#include <vector>

#include <batchccd/batchccd.hpp>

#include "broad_phase.hpp"
#include "scenes.hpp"

namespace {

// What the ranks agree on: one MPI_Allreduce of this struct.
struct StepSummary {
  double earliest_toi;
  batchccd::Counters counters;
};

// The reduction: the earlier TOI, the counters added (Counters::operator+=,
// so a counter the library adds is reduced too).
void combine(void* in, void* inout, int* count, MPI_Datatype*) {
  const auto* a = static_cast<const StepSummary*>(in);
  auto* b = static_cast<StepSummary*>(inout);
  for (int i = 0; i < *count; ++i) {
    b[i].earliest_toi = std::min(b[i].earliest_toi, a[i].earliest_toi);
    b[i].counters += a[i].counters;
  }
}

// This rank's contiguous share of a list: [size * rank / ranks, size * (rank + 1) / ranks).
template <class T>
std::span<const T> share(const std::vector<T>& list, int rank, int ranks) {
  const std::size_t begin = list.size() * static_cast<std::size_t>(rank) / static_cast<std::size_t>(ranks);
  const std::size_t end = list.size() * static_cast<std::size_t>(rank + 1) / static_cast<std::size_t>(ranks);
  return std::span<const T>(list).subspan(begin, end - begin);
}

// The earliest TOI bit for bit, and the candidates counted. The other
// counters are not compared: an earliest-TOI-only call filters and asks its
// candidates in a shrinking window (batch.hpp), so its culls and solver
// counts follow what each rank's window let through.
bool same_bits(const StepSummary& a, const StepSummary& b) {
  return std::memcmp(&a.earliest_toi, &b.earliest_toi, sizeof(double)) == 0 &&
         a.counters.candidates == b.counters.candidates;
}

int run(int argc, char** argv) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  bool check = false;
  int resolution = 24;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--check") check = true;
    else if (arg == "--resolution" && i + 1 < argc) resolution = std::atoi(argv[++i]);
    else {
      if (rank == 0) std::fprintf(stderr, "usage: batchccd_mpi_step [--check] [--resolution N]\n");
      return 2;
    }
  }

  // Every rank builds the same scene here; a simulator would hold its own part.
  const batchccd::scenes::MovingMesh mesh = batchccd::scenes::cloth_scene({.resolution = resolution, .frame = 76});
  const batchccd::Candidates all =
      batchccd::scenes::swept_box_candidates(mesh.view(), batchccd::scenes::mean_edge_length(mesh.view()));
  const batchccd::CandidateLists mine{share(all.vertex_face, rank, ranks), share(all.edge_edge, rank, ranks),
                                      share(all.vertex_edge, rank, ranks), share(all.vertex_vertex, rank, ranks)};

  MPI_Datatype summary_type;
  MPI_Type_contiguous(sizeof(StepSummary), MPI_BYTE, &summary_type);
  MPI_Type_commit(&summary_type);
  MPI_Op earliest_and_sum;
  MPI_Op_create(&combine, /*commute=*/1, &earliest_and_sum);

  int failures = 0;
  for (const auto& [mode_name, mode] : batchccd::mode_names()) {
    batchccd::Options options;
    options.mode = mode;
    options.per_candidate_results = false;  // the step needs the earliest TOI and the counts
    batchccd::BatchResult result;
    batchccd::mesh_ccd(mesh.view(), mine, options, result);

    const StepSummary local{result.earliest_toi, result.counters};
    StepSummary step{};
    MPI_Allreduce(&local, &step, 1, summary_type, earliest_and_sum, MPI_COMM_WORLD);

    bool agrees = true;
    if (check) {
      batchccd::BatchResult whole;
      batchccd::mesh_ccd(mesh.view(), all, options, whole);
      // A step without contact would make the comparison vacuous (inf = inf).
      agrees = same_bits(step, {whole.earliest_toi, whole.counters}) && whole.counters.hits > 0;
      if (!agrees)
        std::fprintf(stderr, "rank %d, %s: %d ranks give earliest TOI %.17g, %lld hits; one process %.17g, %lld\n",
                     rank, std::string(mode_name).c_str(), ranks, step.earliest_toi,
                     static_cast<long long>(step.counters.hits), whole.earliest_toi,
                     static_cast<long long>(whole.counters.hits));
    }
    failures += agrees ? 0 : 1;
    if (rank == 0)
      std::printf("%-12s %d ranks: %lld candidates, %lld culled, %lld hits, earliest TOI %.17g%s\n",
                  std::string(mode_name).c_str(), ranks, static_cast<long long>(step.counters.candidates),
                  static_cast<long long>(step.counters.culled), static_cast<long long>(step.counters.hits),
                  step.earliest_toi, check ? (agrees ? " (= one process, bit for bit)" : " (DIFFERS)") : "");
  }
  MPI_Op_free(&earliest_and_sum);
  MPI_Type_free(&summary_type);
  return failures == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int status = 0;
  try {
    status = run(argc, argv);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "batchccd_mpi_step: %s\n", error.what());
    status = 1;
  }
  MPI_Finalize();
  return status;
}
