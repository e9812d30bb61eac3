// libFuzzer target: the query CSV reader (7 columns with truth, 6 without).
// The contract (io.hpp): any bytes either parse into finite queries, with one
// truth per query when the file has the truth column, or throw InputError.
// Any other exception escapes and is reported as a crash.

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "batchccd/io.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input_file.hpp"

// Every kind reads the same bytes: the point kinds have other row counts
// (ve 6, vv 4) and fill Query's repeated slots (query.hpp).
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using batchccd::fuzz::require;
  using batchccd::Kind;
  for (const Kind kind : {Kind::vertex_face, Kind::edge_edge, Kind::vertex_edge, Kind::vertex_vertex}) {
    try {
      const batchccd::QueryFile file = batchccd::read_query_csv(batchccd::fuzz::as_input_file(data, size), kind);
      require(file.kind == kind, "the kind asked for is kept");
      if (file.truth) require(file.truth->size() == file.queries.size(), "one truth per query");
      for (const batchccd::Query& query : file.queries) {
        for (const batchccd::Vec3& point : query.points) require(point.allFinite(), "every coordinate read is finite");
        if (kind == Kind::vertex_edge || kind == Kind::vertex_vertex)
          require(query.points[0] == query.points[1] && query.points[4] == query.points[5],
                  "the point is a zero-length edge");
        if (kind == Kind::vertex_vertex)
          require(query.points[2] == query.points[3] && query.points[6] == query.points[7],
                  "the other point too");
      }
    } catch (const batchccd::InputError&) {
      // refused clearly: the documented outcome for bad input
    }
  }
  return 0;
}
