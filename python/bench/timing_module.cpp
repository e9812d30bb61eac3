// The C++ side of the overhead benchmark (overhead.py), as a module loaded
// into the same process as batchccd: the same arrays, memory and threads
// for both sides, the calls alternated one by one. Not installed.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <chrono>
#include <span>
#include <string>

#include <batchccd/batchccd.hpp>

#include "broad_phase.hpp"
#include "scene_writer.hpp"
#include "scenes.hpp"

namespace py = pybind11;

namespace {

// The built-in cloth scene (resolution 64, its step 76) with the first
// `count` of its swept-box candidates, vertex-face first, as a scene directory.
py::tuple write_cloth_scene(const std::string& directory, std::size_t count) {
  const batchccd::scenes::MovingMesh mesh = batchccd::scenes::cloth_scene({.resolution = 64, .frame = 76});
  batchccd::Candidates candidates =
      batchccd::scenes::swept_box_candidates(mesh.view(), batchccd::scenes::mean_edge_length(mesh.view()));
  if (candidates.vertex_face.size() + candidates.edge_edge.size() < count)
    throw std::invalid_argument("the scene has fewer candidates than asked for");
  candidates.vertex_face.resize(std::min(count, candidates.vertex_face.size()));
  candidates.edge_edge.resize(count - candidates.vertex_face.size());
  batchccd::scenes::write_scene_directory(directory, mesh.view(), candidates);
  return py::make_tuple(candidates.vertex_face.size(), candidates.edge_edge.size());
}

// The C++ call on views of the given arrays (column-major float64 positions,
// C-ordered int32 faces and lists), into one BatchResult kept across calls
// as a frame loop keeps it; returns the seconds of each call.
class CppCaller {
 public:
  CppCaller(py::array_t<double, py::array::f_style> x0, py::array_t<double, py::array::f_style> x1,
            py::array_t<int, py::array::c_style> faces, py::array_t<int, py::array::c_style> vertex_face,
            py::array_t<int, py::array::c_style> edge_edge, int threads)
      : x0_(x0), x1_(x1), faces_(faces), vertex_face_(vertex_face), edge_edge_(edge_edge) {
    options_.threads = threads;
  }

  double call() {
    const auto n = x0_.shape(0);
    const batchccd::MeshView mesh{batchccd::MatrixView<double>(x0_.data(), n, 3, 1, n),
                                  batchccd::MatrixView<double>(x1_.data(), n, 3, 1, n),
                                  batchccd::IdsView(faces_.data(), faces_.shape(0), 3, 3, 1)};
    const batchccd::CandidateLists lists{
        {reinterpret_cast<const std::array<int, 2>*>(vertex_face_.data()), static_cast<std::size_t>(vertex_face_.shape(0))},
        {reinterpret_cast<const std::array<int, 4>*>(edge_edge_.data()), static_cast<std::size_t>(edge_edge_.shape(0))}};
    py::gil_scoped_release release;  // as the module does
    const auto start = std::chrono::steady_clock::now();
    batchccd::mesh_ccd(mesh, lists, options_, result_);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  double earliest_toi() const { return result_.earliest_toi; }
  std::int64_t hits() const { return result_.counters.hits; }

 private:
  py::array_t<double, py::array::f_style> x0_, x1_;
  py::array_t<int, py::array::c_style> faces_, vertex_face_, edge_edge_;
  batchccd::Options options_;
  batchccd::BatchResult result_;
};

}  // namespace

PYBIND11_MODULE(batchccd_timing, m) {
  m.def("write_cloth_scene", &write_cloth_scene, py::arg("directory"), py::arg("count"));
  py::class_<CppCaller>(m, "CppCaller")
      .def(py::init<py::array_t<double, py::array::f_style>, py::array_t<double, py::array::f_style>,
                    py::array_t<int, py::array::c_style>, py::array_t<int, py::array::c_style>,
                    py::array_t<int, py::array::c_style>, int>())
      .def("call", &CppCaller::call)
      .def("earliest_toi", &CppCaller::earliest_toi)
      .def("hits", &CppCaller::hits);
}
