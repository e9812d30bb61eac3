// Sort-and-sweep over swept, grown boxes (see broad_phase.hpp).
//
// Boxes are sorted along the axis where the mesh spreads most, and cut into
// slabs along the second: a box scans only the boxes of its own slabs whose
// interval on the sweep axis starts inside its own. Without the slabs a
// sheet of N vertices costs N^1.5 box tests; with them about N. A pair
// found in several slabs is kept only in the slab holding the larger of the
// two boxes' low ends on the slab axis, a point both boxes cover.
//
// Pairs are packed into 64-bit keys in per-thread buffers and sorted at the
// end, so the output does not depend on the thread schedule.

#include "broad_phase.hpp"

#include "batchccd/candidates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

namespace batchccd::scenes {
namespace {

// One primitive's box; 64 bytes, one cache line, so a scan streams.
struct Box {
  std::array<double, 3> lo;
  std::array<double, 3> hi;
  std::array<int, 3> vertices;  // unused slots are -1
  int id;                       // vertex, edge or face id
};

using PairKey = std::uint64_t;  // first id in the high half, second in the low

PairKey pair_key(int first, int second) {
  return (static_cast<PairKey>(first) << 32) | static_cast<std::uint32_t>(second);
}
int first_of(PairKey key) { return static_cast<int>(key >> 32); }
int second_of(PairKey key) { return static_cast<int>(key & 0xffffffffu); }

void check_input(const MeshView& mesh, double margin) {
  if (!(margin >= 0) || !std::isfinite(margin))
    throw std::invalid_argument("broad phase: margin must be finite and >= 0, got " +
                                std::to_string(margin));
  const auto n = mesh.positions_t0.rows();
  if (mesh.positions_t0.cols() != 3 || mesh.positions_t1.cols() != 3 ||
      mesh.positions_t1.rows() != n || (mesh.faces.rows() > 0 && mesh.faces.cols() != 3))
    throw std::invalid_argument("broad phase: positions must be n x 3 at t0 and t1, faces m x 3");
  // NaN would break the sort's ordering.
  for (std::int64_t v = 0; v < n; ++v)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(mesh.positions_t0(v, c)) || !std::isfinite(mesh.positions_t1(v, c)))
        throw std::invalid_argument("broad phase: a vertex coordinate is not finite");
  for (std::int64_t f = 0; f < mesh.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (mesh.faces(f, c) < 0 || mesh.faces(f, c) >= n)
        throw std::invalid_argument("broad phase: a face index is out of range");
}

template <std::size_t N>
Box swept_box(const MeshView& mesh, const std::array<int, N>& vertices, int id, double margin) {
  Box box;
  box.id = id;
  box.vertices = {-1, -1, -1};
  for (int axis = 0; axis < 3; ++axis) {
    double lo = mesh.positions_t0(vertices[0], axis), hi = lo;
    for (std::size_t k = 0; k < N; ++k) {
      for (const PositionsView* positions : {&mesh.positions_t0, &mesh.positions_t1}) {
        const double x = (*positions)(vertices[k], axis);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    }
    box.lo[axis] = lo - margin;
    box.hi[axis] = hi + margin;
  }
  for (std::size_t k = 0; k < N; ++k) box.vertices[k] = vertices[k];
  return box;
}

// Axes by decreasing variance of the vertices (both positions): sweeping
// along the first and cutting slabs along the second leave the fewest
// false overlaps.
std::array<int, 3> axes_by_spread(const MeshView& mesh) {
  Eigen::Vector3d variance = Eigen::Vector3d::Zero();
  for (const PositionsView* positions : {&mesh.positions_t0, &mesh.positions_t1}) {
    const std::int64_t n = positions->rows();
    if (n == 0) continue;
    const auto at = [&](std::int64_t v) {
      return Eigen::Vector3d((*positions)(v, 0), (*positions)(v, 1), (*positions)(v, 2));
    };
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::int64_t v = 0; v < n; ++v) mean += at(v);
    mean /= static_cast<double>(n);
    for (std::int64_t v = 0; v < n; ++v) variance += (at(v) - mean).cwiseAbs2();
  }
  std::array<int, 3> axes{0, 1, 2};
  std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return variance[a] > variance[b]; });
  return axes;
}

bool overlap(const Box& a, const Box& b) {
  for (int axis = 0; axis < 3; ++axis)
    if (a.lo[axis] > b.hi[axis] || b.lo[axis] > a.hi[axis]) return false;
  return true;
}

bool vertex_in_face(const Box& vertex, const Box& face) {
  const int v = vertex.vertices[0];
  return face.vertices[0] == v || face.vertices[1] == v || face.vertices[2] == v;
}

bool edges_share_vertex(const Box& a, const Box& b) {
  return a.vertices[0] == b.vertices[0] || a.vertices[0] == b.vertices[1] ||
         a.vertices[1] == b.vertices[0] || a.vertices[1] == b.vertices[1];
}

// Equal-width slabs along one axis. index() is monotonic in x, which is
// all the deduplication needs.
struct Slabs {
  int axis = 0;
  double origin = 0;
  double width = 1;
  int count = 1;

  int index(double x) const {
    const double slab = std::floor((x - origin) / width);
    return slab <= 0 ? 0 : slab >= count - 1 ? count - 1 : static_cast<int>(slab);
  }
};

// About two slabs per box on average: narrower slabs copy boxes into more
// slabs, wider ones let a box see more boxes it cannot overlap.
Slabs choose_slabs(int axis, const std::vector<const std::vector<Box>*>& groups) {
  Slabs slabs;
  slabs.axis = axis;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, extent = 0;
  std::size_t boxes = 0;
  for (const auto* group : groups)
    for (const Box& box : *group) {
      lo = std::min(lo, box.lo[axis]);
      hi = std::max(hi, box.hi[axis]);
      extent += box.hi[axis] - box.lo[axis];
      ++boxes;
    }
  constexpr int kMaxSlabs = 4096;
  if (boxes == 0 || !(hi > lo) || !std::isfinite(hi - lo)) return slabs;  // one slab
  slabs.origin = lo;
  slabs.width = std::max(extent / static_cast<double>(boxes), (hi - lo) / kMaxSlabs);
  slabs.count = std::clamp(static_cast<int>((hi - lo) / slabs.width) + 1, 1, kMaxSlabs);
  return slabs;
}

// The boxes of each slab, keeping the order of `sorted` (along the sweep axis).
std::vector<std::vector<Box>> cut(const std::vector<Box>& sorted, const Slabs& slabs) {
  std::vector<std::vector<Box>> cut_boxes(static_cast<std::size_t>(slabs.count));
  for (const Box& box : sorted)
    for (int s = slabs.index(box.lo[slabs.axis]); s <= slabs.index(box.hi[slabs.axis]); ++s)
      cut_boxes[static_cast<std::size_t>(s)].push_back(box);
  return cut_boxes;
}

void sort_along(std::vector<Box>& boxes, int axis) {
  tbb::parallel_sort(boxes.begin(), boxes.end(), [axis](const Box& a, const Box& b) {
    return a.lo[axis] < b.lo[axis] || (a.lo[axis] == b.lo[axis] && a.id < b.id);
  });
}

// Per-thread key buffers, merged and sorted once.
class PairBuffers {
 public:
  std::vector<PairKey>& local() { return buffers_.local(); }

  // All keys in increasing order: a counting sort on the first id (below
  // first_id_count), then each first id's few keys sorted in place.
  std::vector<PairKey> sorted(std::size_t first_id_count) {
    std::vector<std::size_t> start(first_id_count + 1, 0);
    for (const auto& buffer : buffers_)
      for (PairKey key : buffer) ++start[static_cast<std::size_t>(first_of(key)) + 1];
    for (std::size_t i = 0; i < first_id_count; ++i) start[i + 1] += start[i];
    std::vector<PairKey> keys(start.back());
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (auto& buffer : buffers_) {
      for (PairKey key : buffer) keys[next[static_cast<std::size_t>(first_of(key))]++] = key;
      std::vector<PairKey>().swap(buffer);  // free as we go: the lists can be large
    }
    tbb::parallel_for(std::size_t{0}, first_id_count, [&](std::size_t i) {
      std::sort(keys.begin() + static_cast<std::ptrdiff_t>(start[i]),
                keys.begin() + static_cast<std::ptrdiff_t>(start[i + 1]));
    });
    return keys;
  }

 private:
  tbb::enumerable_thread_specific<std::vector<PairKey>> buffers_;
};

// Within one slab: for every box `a` of `drivers`, scans the boxes of
// `others` whose interval on the sweep axis starts at or after a's
// (strictly after when `strictly_after`) and inside a's, and hands pairs
// that overlap and belong to this slab to emit(a, b, buffer). Both vectors
// are sorted along the sweep axis.
template <class Emit>
void sweep(const std::vector<Box>& drivers, const std::vector<Box>& others, int sweep_axis,
           const Slabs& slabs, int slab, bool strictly_after, PairBuffers& buffers,
           const Emit& emit) {
  const int axis = sweep_axis;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, drivers.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::vector<PairKey>& buffer = buffers.local();
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const Box& a = drivers[i];
                        const double start = a.lo[axis];
                        const auto first =
                            strictly_after
                                ? std::upper_bound(others.begin(), others.end(), start,
                                                   [axis](double x, const Box& b) { return x < b.lo[axis]; })
                                : std::lower_bound(others.begin(), others.end(), start,
                                                   [axis](const Box& b, double x) { return b.lo[axis] < x; });
                        for (auto b = first; b != others.end() && b->lo[axis] <= a.hi[axis]; ++b)
                          if (overlap(a, *b) &&
                              slabs.index(std::max(a.lo[slabs.axis], b->lo[slabs.axis])) == slab)
                            emit(a, *b, buffer);
                      }
                    });
}

// The mesh's unique edges (batchccd::unique_edges) as the sweeps use them.
std::vector<std::array<int, 2>> edges_of(const IdsView& faces) {
  const Eigen::MatrixXi matrix = unique_edges(faces);
  std::vector<std::array<int, 2>> edges(static_cast<std::size_t>(matrix.rows()));
  for (Eigen::Index e = 0; e < matrix.rows(); ++e)
    edges[static_cast<std::size_t>(e)] = {matrix(e, 0), matrix(e, 1)};
  return edges;
}

}  // namespace

double mean_edge_length(const MeshView& mesh) {
  const std::vector<std::array<int, 2>> edges = edges_of(mesh.faces);
  if (edges.empty()) return 0;
  double sum = 0;
  for (const auto& [a, b] : edges)
    sum += std::hypot(mesh.positions_t0(a, 0) - mesh.positions_t0(b, 0), mesh.positions_t0(a, 1) - mesh.positions_t0(b, 1),
                      mesh.positions_t0(a, 2) - mesh.positions_t0(b, 2));
  return sum / static_cast<double>(edges.size());
}

Candidates swept_box_candidates(const MeshView& mesh, double margin) {
  check_input(mesh, margin);
  const std::array<int, 3> axes = axes_by_spread(mesh);
  const int axis = axes[0];
  const std::vector<std::array<int, 2>> edges = edges_of(mesh.faces);
  const auto vertex_count = static_cast<std::size_t>(mesh.positions_t0.rows());
  const auto face_count = static_cast<std::size_t>(mesh.faces.rows());

  std::vector<Box> vertices(vertex_count), faces(face_count), edge_boxes(edges.size());
  tbb::parallel_for(std::size_t{0}, vertex_count, [&](std::size_t v) {
    vertices[v] = swept_box(mesh, std::array<int, 1>{static_cast<int>(v)}, static_cast<int>(v), margin);
  });
  tbb::parallel_for(std::size_t{0}, face_count, [&](std::size_t f) {
    const auto i = static_cast<std::int64_t>(f);
    faces[f] = swept_box(mesh, std::array<int, 3>{mesh.faces(i, 0), mesh.faces(i, 1), mesh.faces(i, 2)},
                         static_cast<int>(f), margin);
  });
  tbb::parallel_for(std::size_t{0}, edges.size(), [&](std::size_t e) {
    edge_boxes[e] = swept_box(mesh, edges[e], static_cast<int>(e), margin);
  });
  sort_along(vertices, axis);
  sort_along(faces, axis);
  sort_along(edge_boxes, axis);
  const Slabs slabs = choose_slabs(axes[1], {&vertices, &faces, &edge_boxes});
  const auto slab_vertices = cut(vertices, slabs);
  const auto slab_faces = cut(faces, slabs);
  const auto slab_edges = cut(edge_boxes, slabs);
  // The cut copies are all the sweeps need.
  std::vector<Box>().swap(vertices);
  std::vector<Box>().swap(faces);
  std::vector<Box>().swap(edge_boxes);

  PairBuffers vertex_face_keys, edge_edge_keys;
  tbb::parallel_for(0, slabs.count, [&](int slab) {
    const auto s = static_cast<std::size_t>(slab);
    // Vertex-face: a pair is found from the box whose interval starts first
    // (the vertex on ties), so once.
    auto vertex_face = [](const Box& vertex, const Box& face, std::vector<PairKey>& out) {
      if (!vertex_in_face(vertex, face)) out.push_back(pair_key(vertex.id, face.id));
    };
    sweep(slab_vertices[s], slab_faces[s], axis, slabs, slab, false, vertex_face_keys, vertex_face);
    sweep(slab_faces[s], slab_vertices[s], axis, slabs, slab, true, vertex_face_keys,
          [&](const Box& face, const Box& vertex, std::vector<PairKey>& out) {
            vertex_face(vertex, face, out);
          });
    // Edge-edge: each edge scans the edges after it in sorted order (the
    // strict bound skips the edge itself and every earlier one with its
    // start), so each pair once; the key holds the smaller edge id first.
    const std::vector<Box>& edge_list = slab_edges[s];
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, edge_list.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        std::vector<PairKey>& out = edge_edge_keys.local();
                        for (std::size_t p = range.begin(); p != range.end(); ++p) {
                          const Box& a = edge_list[p];
                          for (std::size_t q = p + 1;
                               q < edge_list.size() && edge_list[q].lo[axis] <= a.hi[axis]; ++q) {
                            const Box& b = edge_list[q];
                            if (overlap(a, b) && !edges_share_vertex(a, b) &&
                                slabs.index(std::max(a.lo[slabs.axis], b.lo[slabs.axis])) == slab)
                              out.push_back(pair_key(std::min(a.id, b.id), std::max(a.id, b.id)));
                          }
                        }
                      });
  });

  Candidates candidates;
  const std::vector<PairKey> vertex_face = vertex_face_keys.sorted(vertex_count);
  candidates.vertex_face.resize(vertex_face.size());
  tbb::parallel_for(std::size_t{0}, vertex_face.size(), [&](std::size_t i) {
    candidates.vertex_face[i] = {first_of(vertex_face[i]), second_of(vertex_face[i])};
  });
  // Edge ids follow the lexicographic order of (i, j), so sorted edge-id
  // pairs are sorted vertex quadruples.
  const std::vector<PairKey> edge_edge = edge_edge_keys.sorted(edges.size());
  candidates.edge_edge.resize(edge_edge.size());
  tbb::parallel_for(std::size_t{0}, edge_edge.size(), [&](std::size_t i) {
    const auto& a = edges[static_cast<std::size_t>(first_of(edge_edge[i]))];
    const auto& b = edges[static_cast<std::size_t>(second_of(edge_edge[i]))];
    candidates.edge_edge[i] = {a[0], a[1], b[0], b[1]};
  });
  return candidates;
}

}  // namespace batchccd::scenes
