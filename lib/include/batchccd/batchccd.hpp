#pragma once

// The whole public API of batchccd: include this one header and link the
// CMake target batchccd::batchccd (or `pkg-config --cflags --libs batchccd`).
// C++20. Calls share no mutable state, so they may run concurrently from
// several threads; batch calls also run in parallel on their own
// (Options::threads). No SIMD or threading type appears in these headers.
#include "batchccd/batch.hpp"       // mesh_ccd, batch_ccd: many candidates in one call
#include "batchccd/candidates.hpp"  // unique_edges, a mesh candidate as a Query
#include "batchccd/ccd.hpp"         // vertex_face_ccd, edge_edge_ccd, ...: one query
#include "batchccd/ipc.hpp"         // one query, called as in ipc-toolkit (min_distance, tmax)
#include "batchccd/ipc_stepsize.hpp"  // ipc-toolkit's collision-free step over a mesh, one call
#include "batchccd/io.hpp"          // readers for query files, PLY meshes, scenes
#include "batchccd/mesh_edges.hpp"  // mesh_ccd with an edges matrix and edge-id candidates
#include "batchccd/names.hpp"       // the enums' names, both ways
#include "batchccd/options.hpp"     // Options, Mode, Isa
#include "batchccd/query.hpp"       // Query, QueryResult, Status, Kind
#include "batchccd/tight_inclusion.hpp"  // one query, called as in Tight Inclusion
#include "batchccd/version.hpp"     // BATCHCCD_VERSION
