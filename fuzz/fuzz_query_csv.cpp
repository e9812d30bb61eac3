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

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using batchccd::fuzz::require;
  try {
    const batchccd::QueryFile file =
        batchccd::read_query_csv(batchccd::fuzz::as_input_file(data, size), batchccd::Kind::edge_edge);
    require(file.kind == batchccd::Kind::edge_edge, "the kind asked for is kept");
    if (file.truth) require(file.truth->size() == file.queries.size(), "one truth per query");
    for (const batchccd::Query& query : file.queries)
      for (const batchccd::Vec3& point : query.points)
        require(point.allFinite(), "every coordinate read is finite");
  } catch (const batchccd::InputError&) {
    // refused clearly: the documented outcome for bad input
  }
  return 0;
}
