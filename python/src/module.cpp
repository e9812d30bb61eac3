// The Python module batchccd._batchccd (re-exported by batchccd/__init__.py):
// the library's calls over NumPy arrays. Arrays are read in place through
// the library's views whenever their layout allows, copied once otherwise;
// the GIL is released while the library works.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <batchccd/batchccd.hpp>

namespace py = pybind11;
using namespace pybind11::literals;

namespace batchccd::python {
namespace {

// ---------------------------------------------------------------- messages

// The library's messages name things as C++ does; Python's calls name them
// otherwise. Every library error reaches Python through in_python_names
// (the exception translator in PYBIND11_MODULE), so a rename is one row here.
constexpr std::pair<std::string_view, std::string_view> kPythonNames[] = {
    {"Options::", "option "},               // Options::min_distance: the keyword min_distance
    {"positions_t0", "x0"},                 // MeshView's positions: mesh_ccd's x0, x1
    {"positions_t1", "x1"},
    {"batchccd::ipc::", "batchccd.ipc."},  // ipc.hpp's calls: this module's batchccd.ipc
};

// A per-candidate separation is one value of the argument min_distances;
// the library names it "<list> candidate <i>: min_distance must be ...".
// Elsewhere min_distance is Python's name too (the keyword, ipc's argument).
void name_candidate_separations(std::string& message) {
  constexpr std::string_view library_name = ": min_distance must be";
  constexpr std::string_view python_name = ": its value in min_distances must be";
  constexpr std::string_view candidate = "candidate ";
  for (std::size_t at = message.find(library_name); at != std::string::npos;
       at = message.find(library_name, at + 1)) {
    std::size_t digits = at;
    while (digits > 0 && message[digits - 1] >= '0' && message[digits - 1] <= '9') --digits;
    if (digits == at || digits < candidate.size() ||
        message.compare(digits - candidate.size(), candidate.size(), candidate) != 0)
      continue;
    message.replace(at, library_name.size(), python_name);
  }
}

std::string in_python_names(std::string message) {
  constexpr std::string_view library_prefix = "batchccd: ";
  if (message.starts_with(library_prefix)) message.erase(0, library_prefix.size());
  for (const auto& [library_name, python_name] : kPythonNames)
    for (std::size_t at = message.find(library_name); at != std::string::npos;
         at = message.find(library_name, at + python_name.size()))
      message.replace(at, library_name.size(), python_name);
  name_candidate_separations(message);
  return message;
}

// ---------------------------------------------------------------- options

// The one place that maps Python keywords to Options: parse_options reads
// them, default_options lists them. Fields left out here (lab switches) keep
// their C++ defaults.
template <class T>
T cast_field(py::handle value, const char* name, const char* expected) {
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    throw py::type_error(std::string("option ") + name + " must be " + expected + ", got " +
                         py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
  }
}

bool cast_bool(py::handle value, const char* name) {
  // int 0/1 are refused: a misspelt number for a switch is a mistake.
  if (!PyBool_Check(value.ptr()) && !py::isinstance(value, py::module_::import("numpy").attr("bool_")))
    throw py::type_error(std::string("option ") + name + " must be a bool, got " +
                         py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
  return value.cast<bool>();
}

template <class Enum>
std::string names_of(std::span<const EnumName<Enum>> table) {
  std::string names;
  for (const auto& entry : table) names += (names.empty() ? "" : ", ") + std::string(entry.name);
  return names;
}

struct OptionField {
  const char* name;
  void (*set)(Options&, py::handle);
  py::object (*get)(const Options&);
};

#define BATCHCCD_BOOL_FIELD_AS(name, field)                                         \
  OptionField {                                                                     \
    #name, [](Options& o, py::handle v) { o.field = cast_bool(v, #name); },         \
        [](const Options& o) -> py::object { return py::bool_(o.field); }           \
  }
#define BATCHCCD_BOOL_FIELD(field) BATCHCCD_BOOL_FIELD_AS(field, field)
#define BATCHCCD_NUMBER_FIELD(field, type, expected)                                           \
  OptionField {                                                                                \
    #field, [](Options& o, py::handle v) { o.field = cast_field<type>(v, #field, expected); }, \
        [](const Options& o) -> py::object { return py::cast(o.field); }                       \
  }

const std::vector<OptionField>& option_fields() {
  static const std::vector<OptionField> fields = {
      {"mode",
       [](Options& o, py::handle v) {
         const auto name = cast_field<std::string>(v, "mode", "a str");
         const std::optional<Mode> mode = mode_from_string(name);
         if (!mode) throw py::value_error("option mode: unknown mode '" + name + "' (one of " + names_of(mode_names()) + ")");
         o.mode = *mode;
       },
       [](const Options& o) -> py::object { return py::str(to_string(o.mode)); }},
      BATCHCCD_NUMBER_FIELD(min_distance, double, "a float"),
      BATCHCCD_NUMBER_FIELD(tmax, double, "a float"),
      BATCHCCD_BOOL_FIELD(need_toi),
      // mesh_ccd's candidate lists hold the fields' own names.
      BATCHCCD_BOOL_FIELD_AS(evaluate_vertex_face, vertex_face),
      BATCHCCD_BOOL_FIELD_AS(evaluate_edge_edge, edge_edge),
      BATCHCCD_BOOL_FIELD_AS(evaluate_vertex_edge, vertex_edge),
      BATCHCCD_BOOL_FIELD_AS(evaluate_vertex_vertex, vertex_vertex),
      BATCHCCD_BOOL_FIELD(per_candidate_results),
      BATCHCCD_BOOL_FIELD(hit_list),
      {"isa",
       [](Options& o, py::handle v) {
         const auto name = cast_field<std::string>(v, "isa", "a str");
         const std::optional<Isa> isa = isa_from_string(name);
         if (!isa) throw py::value_error("option isa: unknown instruction set '" + name + "' (one of " + names_of(isa_names()) + ")");
         o.isa = *isa;
       },
       [](const Options& o) -> py::object { return py::str(to_string(o.isa)); }},
      BATCHCCD_NUMBER_FIELD(threads, int, "an int"),
      BATCHCCD_NUMBER_FIELD(tolerance, double, "a float"),
      BATCHCCD_NUMBER_FIELD(toi_tolerance, double, "a float"),
      BATCHCCD_NUMBER_FIELD(max_iterations, std::int64_t, "an int"),
      BATCHCCD_NUMBER_FIELD(exact_stage_iterations, std::int64_t, "an int"),
  };
  return fields;
}
#undef BATCHCCD_BOOL_FIELD
#undef BATCHCCD_BOOL_FIELD_AS
#undef BATCHCCD_NUMBER_FIELD

Options parse_options(const py::dict& keywords) {
  Options options;
  for (const auto& [key, value] : keywords) {
    const std::string name = py::str(key);
    bool known = false;
    for (const OptionField& field : option_fields())
      if (name == field.name) {
        field.set(options, value);
        known = true;
        break;
      }
    if (!known) throw py::type_error("unexpected keyword argument '" + name + "'");
  }
  return options;
}

py::dict default_options() {
  py::dict defaults;
  const Options options;
  for (const OptionField& field : option_fields()) defaults[field.name] = field.get(options);
  return defaults;
}

// ---------------------------------------------------------------- arrays

constexpr int kAligned = py::detail::npy_api::NPY_ARRAY_ALIGNED_;
constexpr int kCContiguous = py::detail::npy_api::NPY_ARRAY_C_CONTIGUOUS_;

std::string dtype_name(const py::array& array) { return py::str(array.dtype()).cast<std::string>(); }

py::array ensure_array(py::handle object, const char* name) {
  py::array array = py::array::ensure(object);
  if (!array) {
    PyErr_Clear();
    throw py::type_error(std::string(name) + ": expected an array, got " +
                         py::str(py::type::handle_of(object).attr("__name__")).cast<std::string>());
  }
  return array;
}

// An array of T in native byte order, aligned, its strides whole elements:
// what a view can read in place.
template <class T>
bool readable_in_place(const py::array& array) {
  if (!py::isinstance<py::array_t<T>>(array) || (array.flags() & kAligned) == 0) return false;
  for (py::ssize_t d = 0; d < array.ndim(); ++d)
    if (array.strides(d) % static_cast<py::ssize_t>(sizeof(T)) != 0) return false;
  return true;
}

// `array` converted once into a C-ordered array of T.
template <class T>
py::array_t<T> copy_as(const py::array& array) {
  return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
}

void check_matrix_shape(const py::array& array, const char* name) {
  if (array.ndim() != 2)
    throw py::value_error(std::string(name) + ": expected a 2-D array (rows x columns), got " +
                          std::to_string(array.ndim()) + " dimensions");
}

// Positions n x 3 as the library's view: float64 or float32 in place, the
// array (or its copy) kept alive in `keep`.
PositionsView positions_view(py::handle object, const char* name, py::array& keep) {
  py::array array = ensure_array(object, name);
  check_matrix_shape(array, name);
  const char kind = array.dtype().kind();
  const auto itemsize = array.itemsize();
  if (kind != 'f' || (itemsize != 8 && itemsize != 4))
    throw py::type_error(std::string(name) + ": positions must be float64 or float32, got " + dtype_name(array));
  if (itemsize == 4 && !readable_in_place<float>(array)) array = copy_as<float>(array);
  if (itemsize == 8 && !readable_in_place<double>(array)) array = copy_as<double>(array);
  keep = array;
  const auto row = array.strides(0) / itemsize, column = array.strides(1) / itemsize;
  if (itemsize == 4)
    return MatrixView<float>(static_cast<const float*>(array.data()), array.shape(0), array.shape(1), row, column);
  return MatrixView<double>(static_cast<const double*>(array.data()), array.shape(0), array.shape(1), row, column);
}

// An integer array as int32: int32 itself in place when its layout allows
// (C order too when need_c_contiguous: a span of rows), any other integer
// dtype copied once, each value checked to fit.
py::array int32_array(py::handle object, const char* name, bool need_c_contiguous) {
  py::array array = ensure_array(object, name);
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::type_error(std::string(name) + ": ids must be an integer array, got " + dtype_name(array));
  const bool in_place = readable_in_place<int>(array) && (!need_c_contiguous || (array.flags() & kCContiguous) != 0);
  if (in_place) return array;
  if (array.itemsize() <= 2 || (kind == 'i' && array.itemsize() == 4))
    return copy_as<int>(array);  // every value fits
  // Wider types: check the range before narrowing, naming the extreme value that does not fit.
  if (array.size() > 0) {
    const py::object low = array.attr("min")(), high = array.attr("max")();
    const auto too_big = [](py::handle v) { return v.cast<py::int_>() > py::int_(std::numeric_limits<int>::max()); };
    const auto too_small = [](py::handle v) { return v.cast<py::int_>() < py::int_(std::numeric_limits<int>::min()); };
    if (too_big(high) || too_small(low))
      throw py::value_error(std::string(name) + ": id " + py::str(too_big(high) ? high : low).cast<std::string>() +
                            " does not fit in a 32-bit int");
  }
  return copy_as<int>(array);
}

IdsView ids_view(py::handle object, const char* name, py::array& keep) {
  if (object.is_none()) return {};
  py::array array = int32_array(object, name, false);
  check_matrix_shape(array, name);
  keep = array;
  const auto itemsize = static_cast<py::ssize_t>(sizeof(int));
  return IdsView(static_cast<const int*>(array.data()), array.shape(0), array.shape(1), array.strides(0) / itemsize,
                 array.strides(1) / itemsize);
}

// A candidate list: rows of N ids, C-contiguous int32 read in place.
template <std::size_t N>
std::span<const std::array<int, N>> candidate_span(const py::array& array) {
  static_assert(sizeof(std::array<int, N>) == N * sizeof(int));
  return {static_cast<const std::array<int, N>*>(array.data()), static_cast<std::size_t>(array.shape(0))};
}

py::array candidate_array(py::handle object, const char* name, std::initializer_list<py::ssize_t> columns) {
  py::array array = int32_array(object, name, true);
  check_matrix_shape(array, name);
  bool ok = false;
  std::string expected;
  for (const py::ssize_t c : columns) {
    ok = ok || array.shape(1) == c;
    expected += (expected.empty() ? "" : " or ") + std::to_string(c);
  }
  if (!ok)
    throw py::value_error(std::string(name) + ": expected " + expected + " columns, got " +
                          std::to_string(array.shape(1)));
  return array;
}

// A 1-D float64 array read in place when contiguous, copied once otherwise.
py::array double_vector(py::handle object, const char* name) {
  py::array array = ensure_array(object, name);
  if (array.dtype().kind() != 'f' && array.dtype().kind() != 'i' && array.dtype().kind() != 'u')
    throw py::type_error(std::string(name) + ": expected a float array, got " + dtype_name(array));
  if (array.ndim() != 1)
    throw py::value_error(std::string(name) + ": expected a 1-D array, got " + std::to_string(array.ndim()) +
                          " dimensions");
  if (!readable_in_place<double>(array) || (array.flags() & kCContiguous) == 0) array = copy_as<double>(array);
  return array;
}

std::span<const double> double_span(const py::array& array) {
  return {static_cast<const double*>(array.data()), static_cast<std::size_t>(array.size())};
}

// Queries N x 8 x 3 or N x 24 (Query's layout), float64 C-ordered in place.
// Queries, N x 8 x 3 (or N x 24) or, of a 2D scene, N x 8 x 2 (or N x 16):
// the rows in place when they are C-ordered float64, else a copy in `keep`.
struct QueryRows {
  std::span<const Query> spatial;
  std::span<const Query2D> planar;  // when the queries are 2D
  bool in_2d = false;
};

QueryRows query_rows(py::handle object, const char* name, py::array& keep) {
  static_assert(sizeof(Query) == 24 * sizeof(double), "Query is 24 doubles, no padding");
  static_assert(sizeof(Query2D) == 16 * sizeof(double), "Query2D is 16 doubles, no padding");
  py::array array = ensure_array(object, name);
  if (array.dtype().kind() != 'f')
    throw py::type_error(std::string(name) + ": queries must be float64 or float32, got " + dtype_name(array));
  const auto shaped = [&](py::ssize_t dimension) {
    return (array.ndim() == 3 && array.shape(1) == 8 && array.shape(2) == dimension) ||
           (array.ndim() == 2 && array.shape(1) == 8 * dimension);
  };
  const bool in_2d = shaped(2);
  if (!in_2d && !shaped(3)) {
    std::string shape;
    for (py::ssize_t d = 0; d < array.ndim(); ++d) shape += (d ? " x " : "") + std::to_string(array.shape(d));
    throw py::value_error(std::string(name) + ": expected N x 8 x 3 or N x 24 (2D: N x 8 x 2 or N x 16), got " +
                          (shape.empty() ? "a scalar" : shape));
  }
  if (!readable_in_place<double>(array) || (array.flags() & kCContiguous) == 0) array = copy_as<double>(array);
  keep = array;
  const auto count = static_cast<std::size_t>(array.shape(0));
  if (in_2d) return {{}, {static_cast<const Query2D*>(array.data()), count}, true};
  return {{static_cast<const Query*>(array.data()), count}, {}, false};
}

// One query, 8 x 3 (or 24) coordinates, or 8 x 2 (or 16) of a 2D scene
// (lifted to z = 0); integers are taken as the doubles they are.
Query one_query(py::handle object, const char* name) {
  py::array array = ensure_array(object, name);
  if (array.size() != 24 && array.size() != 16)
    throw py::value_error(std::string(name) + ": expected 8 x 3 coordinates (2D: 8 x 2), got " +
                          std::to_string(array.size()));
  const char kind = array.dtype().kind();
  if (kind == 'i' || kind == 'u') array = copy_as<double>(array);
  py::array keep;
  const QueryRows rows = query_rows(array.attr("reshape")(1, array.size()), name, keep);
  return rows.in_2d ? lifted(rows.planar[0]) : rows.spatial[0];
}

// The long names, as Python spells the keyword arguments, beside the
// library's short ones ("vf").
const char* long_name(Kind kind) {
  switch (kind) {
    case Kind::vertex_face: return "vertex_face";
    case Kind::edge_edge: return "edge_edge";
    case Kind::vertex_edge: return "vertex_edge";
    case Kind::vertex_vertex: return "vertex_vertex";
  }
  return "?";
}

Kind kind_from(const std::string& name) {
  if (const std::optional<Kind> kind = kind_from_string(name)) return *kind;
  for (const auto& entry : kind_names())
    if (name == long_name(entry.value)) return entry.value;
  throw py::value_error("unknown kind '" + name + "' (one of " + names_of(kind_names()) +
                        ", or vertex_face, edge_edge, vertex_edge, vertex_vertex)");
}

// ---------------------------------------------------------------- results

// A batch call's answers. The arrays are read-only views of the C++ result
// (no copy); each holds the storage alive. A call given out=result reuses
// its storage only when no view of it is alive, so a view never changes
// under its holder.
struct Result {
  std::shared_ptr<BatchResult> storage = std::make_shared<BatchResult>();
  bool has_results = false;  // the options asked for per-candidate results
  bool has_hits = false;     // and for the hit list
};

py::array view_of(const std::shared_ptr<BatchResult>& storage, const py::dtype& dtype, const void* first,
                  std::size_t count, std::size_t stride) {
  py::capsule owner(new std::shared_ptr<BatchResult>(storage),
                    [](void* p) { delete static_cast<std::shared_ptr<BatchResult>*>(p); });
  py::array array(dtype, {static_cast<py::ssize_t>(count)}, {static_cast<py::ssize_t>(stride)},
                  count ? first : nullptr, owner);
  array.attr("setflags")("write"_a = false);
  return array;
}

static_assert(std::is_standard_layout_v<QueryResult> && std::is_standard_layout_v<Hit>);
static_assert(sizeof(Status) == sizeof(std::int32_t) && sizeof(std::size_t) == sizeof(std::int64_t));

template <class Record, class Field>
py::object field_view(const Result& result, const std::vector<Record>& records, std::size_t offset, bool present) {
  if (!present) return py::none();
  const char* base = reinterpret_cast<const char*>(records.data());
  return view_of(result.storage, py::dtype::of<Field>(), base + offset, records.size(), sizeof(Record));
}

// Counters' times are left out: they need Options::time_queries, which the
// module does not take, and would always read 0.
py::dict counters_dict(const Counters& c) {
  return py::dict("candidates"_a = c.candidates, "culled"_a = c.culled, "culled_by_sign"_a = c.culled_by_sign,
                  "culled_by_separation"_a = c.culled_by_separation, "culled_by_pieces"_a = c.culled_by_pieces,
                  "culled_by_swept_box"_a = c.culled_by_swept_box, "solved"_a = c.solved, "hits"_a = c.hits,
                  "undecided"_a = c.undecided, "invalid"_a = c.invalid, "exact_escalations"_a = c.exact_escalations);
}

// The storage the call writes into: out's own when nothing else holds it.
// Decided under the GIL, so two threads passing the same out never share it.
std::shared_ptr<BatchResult> storage_for(Result& out, const Options& options) {
  if (out.storage.use_count() != 1) out.storage = std::make_shared<BatchResult>();
  out.has_results = options.per_candidate_results;
  out.has_hits = options.hit_list;
  return out.storage;
}

Result& result_for(py::object& out_object, py::object& holder) {
  if (out_object.is_none()) {
    holder = py::cast(Result{});
  } else {
    if (!py::isinstance<Result>(out_object))
      throw py::type_error("out: expected a batchccd.BatchResult from an earlier call");
    holder = out_object;
  }
  return holder.cast<Result&>();
}

// ---------------------------------------------------------------- calls

py::object mesh_ccd_py(py::object x0, py::object x1, py::object faces, py::object edges, py::object vertex_face,
                       py::object edge_edge, py::object vertex_edge, py::object vertex_vertex,
                       py::object min_distances, py::object out, const py::kwargs& keywords) {
  const Options options = parse_options(keywords);
  py::array keep[12];
  MeshView mesh{positions_view(x0, "x0", keep[0]), positions_view(x1, "x1", keep[1]),
                ids_view(faces, "faces", keep[2]), ids_view(edges, "edges", keep[3])};
  const auto list = [&](py::object object, const char* name, std::initializer_list<py::ssize_t> columns,
                        py::array& slot) -> bool {
    if (object.is_none()) return false;
    slot = candidate_array(object, name, columns);
    return true;
  };
  const bool has_vf = list(vertex_face, "vertex_face", {2}, keep[4]);
  const bool has_ee = list(edge_edge, "edge_edge", {4, 2}, keep[5]);
  const bool has_ve = list(vertex_edge, "vertex_edge", {3, 2}, keep[6]);
  const bool has_vv = list(vertex_vertex, "vertex_vertex", {2}, keep[7]);
  const bool ee_by_id = has_ee && keep[5].shape(1) == 2, ve_by_id = has_ve && keep[6].shape(1) == 2;
  const bool by_edge_id = ee_by_id || ve_by_id;
  if (by_edge_id) {
    if ((has_ee && !ee_by_id) || (has_ve && !ve_by_id))
      throw py::value_error("edge_edge and vertex_edge must both name edges by id (2 columns) or both by vertex "
                            "ids (4 and 3 columns)");
    if (edges.is_none())
      throw py::value_error(std::string(ee_by_id ? "edge_edge" : "vertex_edge") +
                            " names edges by id (2 columns): pass the edges matrix");
  }
  const auto span2 = [&](bool has, int i) { return has ? candidate_span<2>(keep[i]) : std::span<const std::array<int, 2>>{}; };

  MinDistances separations;
  const bool per_candidate = !min_distances.is_none();
  if (per_candidate) {
    if (by_edge_id)
      throw py::value_error("min_distances: per-candidate separations take candidates by vertex id "
                            "(edge_edge 4 columns, vertex_edge 3)");
    const std::size_t lengths[4] = {has_vf ? static_cast<std::size_t>(keep[4].shape(0)) : 0,
                                    has_ee ? static_cast<std::size_t>(keep[5].shape(0)) : 0,
                                    has_ve ? static_cast<std::size_t>(keep[6].shape(0)) : 0,
                                    has_vv ? static_cast<std::size_t>(keep[7].shape(0)) : 0};
    std::span<const double>* spans[4] = {&separations.vertex_face, &separations.edge_edge, &separations.vertex_edge,
                                         &separations.vertex_vertex};
    const char* names[4] = {"vertex_face", "edge_edge", "vertex_edge", "vertex_vertex"};
    if (py::isinstance<py::dict>(min_distances)) {
      const py::dict by_list = min_distances.cast<py::dict>();
      for (const auto& [key, value] : by_list) {
        const std::string name = py::str(key);
        int i = 0;
        while (i < 4 && name != names[i]) ++i;
        if (i == 4) throw py::value_error("min_distances: unknown list '" + name + "'");
        keep[8 + i] = double_vector(value, ("min_distances['" + name + "']").c_str());
        *spans[i] = double_span(keep[8 + i]);
      }
    } else {
      keep[8] = double_vector(min_distances, "min_distances");
      const std::size_t total = lengths[0] + lengths[1] + lengths[2] + lengths[3];
      if (static_cast<std::size_t>(keep[8].size()) != total)
        throw py::value_error("min_distances: " + std::to_string(keep[8].size()) + " values for " +
                              std::to_string(total) + " candidates");
      std::size_t start = 0;
      for (int i = 0; i < 4; ++i) {
        *spans[i] = double_span(keep[8]).subspan(start, lengths[i]);
        start += lengths[i];
      }
    }
  }

  py::object holder;
  Result& result = result_for(out, holder);
  const std::shared_ptr<BatchResult> storage = storage_for(result, options);
  if (by_edge_id) {
    const EdgeIdCandidates candidates{span2(has_vf, 4), span2(ee_by_id, 5), span2(ve_by_id, 6), span2(has_vv, 7)};
    py::gil_scoped_release release;
    mesh_ccd(mesh, candidates, options, *storage);
  } else {
    const CandidateLists candidates{span2(has_vf, 4), has_ee ? candidate_span<4>(keep[5]) : std::span<const std::array<int, 4>>{},
                                    has_ve ? candidate_span<3>(keep[6]) : std::span<const std::array<int, 3>>{},
                                    span2(has_vv, 7)};
    py::gil_scoped_release release;
    if (per_candidate)
      mesh_ccd(mesh, candidates, separations, options, *storage);
    else
      mesh_ccd(mesh, candidates, options, *storage);
  }
  return holder;
}

py::object batch_ccd_py(const std::string& kind_name, py::object queries, py::object min_distances, py::object out,
                        const py::kwargs& keywords) {
  const Kind kind = kind_from(kind_name);
  const Options options = parse_options(keywords);
  py::array keep_queries, keep_separations;
  const QueryRows rows = query_rows(queries, "queries", keep_queries);
  const bool per_query = !min_distances.is_none();
  if (per_query) keep_separations = double_vector(min_distances, "min_distances");
  const std::span<const double> separations = per_query ? double_span(keep_separations) : std::span<const double>{};
  py::object holder;
  Result& result = result_for(out, holder);
  const std::shared_ptr<BatchResult> storage = storage_for(result, options);
  py::gil_scoped_release release;
  if (rows.in_2d)
    batch_ccd(kind, rows.planar, separations, options, *storage);
  else
    batch_ccd(kind, rows.spatial, separations, options, *storage);
  return holder;
}

template <std::size_t Points>
QueryResult single_query(Kind kind, const std::array<py::object, Points>& points,
                         const std::array<const char*, Points>& names, const py::kwargs& keywords) {
  const Options options = parse_options(keywords);
  // The library's reading of point arguments: its lengths (2D for the point
  // kinds) and its messages, which name the call and the argument.
  std::array<detail::PointArgument, Points> arguments;
  for (std::size_t i = 0; i < Points; ++i) {
    const py::array array = double_vector(points[i], names[i]);
    arguments[i] = detail::read_point(names[i], Eigen::Map<const Eigen::VectorXd>(
                                                    static_cast<const double*>(array.data()), array.size()));
  }
  const std::string call = std::string("batchccd.") + long_name(kind) + "_ccd";
  const Query query = detail::query_from_points(call.c_str(), kind, arguments);
  py::gil_scoped_release release;
  return query_ccd(kind, query, options);
}

// A query as an 8 x 3 array (Query), or 8 x 2 (Query2D).
template <class QueryType>
py::array_t<double> query_array(const QueryType& query) {
  constexpr py::ssize_t dimension = std::tuple_element_t<0, decltype(QueryType::points)>::SizeAtCompileTime;
  py::array_t<double> array({py::ssize_t{8}, dimension});
  auto a = array.mutable_unchecked<2>();
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < dimension; ++j) a(i, j) = query.points[i](j);
  return array;
}

template <std::size_t N>
py::array_t<int> ids_array(const std::vector<std::array<int, N>>& rows) {
  py::array_t<int> array({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(N)});
  if (!rows.empty()) std::memcpy(array.mutable_data(), rows.data(), rows.size() * sizeof(rows[0]));
  return array;
}

template <class Matrix>
py::array_t<typename Matrix::Scalar> matrix_array(const Matrix& m) {
  py::array_t<typename Matrix::Scalar> array({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto a = array.template mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) a(i, j) = m(i, j);
  return array;
}

py::object truth_array(const std::optional<std::vector<bool>>& truth) {
  if (!truth) return py::none();
  py::array_t<bool> array(static_cast<py::ssize_t>(truth->size()));
  for (std::size_t i = 0; i < truth->size(); ++i) array.mutable_at(i) = (*truth)[i];
  return array;
}

py::dict read_scene_py(const std::string& path) {
  Scene scene;
  {
    py::gil_scoped_release release;
    scene = read_scene(path);
  }
  return py::dict("x0"_a = matrix_array(scene.positions_t0), "x1"_a = matrix_array(scene.positions_t1),
                  "faces"_a = matrix_array(scene.faces), "vertex_face"_a = ids_array(scene.candidates.vertex_face),
                  "edge_edge"_a = ids_array(scene.candidates.edge_edge),
                  "vertex_edge"_a = ids_array(scene.candidates.vertex_edge),
                  "vertex_vertex"_a = ids_array(scene.candidates.vertex_vertex),
                  "vertex_face_truth"_a = truth_array(scene.vertex_face_truth),
                  "edge_edge_truth"_a = truth_array(scene.edge_edge_truth),
                  "vertex_edge_truth"_a = truth_array(scene.vertex_edge_truth),
                  "vertex_vertex_truth"_a = truth_array(scene.vertex_vertex_truth));
}

template <class Enum>
py::list names_list(std::span<const EnumName<Enum>> table) {
  py::list names;
  for (const auto& entry : table) names.append(std::string(entry.name));
  return names;
}

// ---------------------------------------------------------------- docs

constexpr const char* kOptionsDoc = R"(
Options (keyword-only; defaults in default_options()):
  mode="conservative"   "conservative": certified, never a false negative on
                        finite input; "exact": decisions equal to exact
                        arithmetic (modes() lists the names this build takes).
  min_distance=0.0      the separation that counts as a contact, absolute, in
                        the positions' length unit; >= 0 and finite.
  tmax=1.0              end of the time window, in (0, 1].
  need_toi=True         False: hit/no-hit only; a hit's toi is then only a
                        lower bound (possibly 0).
  evaluate_vertex_face, evaluate_edge_edge, evaluate_vertex_edge,
  evaluate_vertex_vertex=True
                        mesh calls: which candidate lists to evaluate (a
                        list left out is still checked; Options::vertex_face
                        etc.).
  per_candidate_results=True
                        batch calls: hit, toi, status per candidate.
  hit_list=False        batch calls: the candidates that hit, in order.
  isa="auto"            instruction set of the batch kernels (available_isas()).
  threads=0             worker threads; 0: all the machine has.
  tolerance=1e-9        conservative: contact tolerance relative to the
                        query's size.
  toi_tolerance=1e-7    width of the time interval locating the first contact.
  max_iterations, exact_stage_iterations
                        search budgets (batchccd/options.hpp).
)";

std::string doc(const char* text) { return std::string(text) + kOptionsDoc; }

// ---------------------------------------------------------------- ipc

// batchccd.ipc: ipc.hpp's calls and NarrowPhase under the names, arguments
// and defaults of ipctk (ipc-toolkit's Python module), answering as it does
// with a tuple (hit, toi).

// The points of one call as the library's vectors: 1-D arrays, float64 read
// in place, other numbers copied once. Their lengths are the library's to
// check: its message names the call and the argument.
template <std::size_t N>
class IpcPoints {
 public:
  IpcPoints(const std::array<py::object, N>& objects, const std::array<const char*, N>& names) {
    for (std::size_t i = 0; i < N; ++i) arrays_[i] = double_vector(objects[i], names[i]);
  }
  Eigen::Map<const Eigen::VectorXd> operator[](std::size_t i) const {
    return {static_cast<const double*>(arrays_[i].data()), static_cast<Eigen::Index>(arrays_[i].size())};
  }

 private:
  std::array<py::array, N> arrays_;
};

// (hit, toi) from call(toi). Without a hit toi is inf, as ipctk's Tight
// Inclusion calls say (its ccd calls leave it unset).
template <class Call>
py::tuple ipc_answer(const Call& call) {
  double toi = std::numeric_limits<double>::infinity();
  bool hit = false;
  {
    py::gil_scoped_release release;
    hit = call(toi);
  }
  return py::make_tuple(hit, toi);
}

constexpr std::array<const char*, 4> kPointPointNames = {"p0_t0", "p1_t0", "p0_t1", "p1_t1"};
constexpr std::array<const char*, 6> kPointEdgeNames = {"p_t0", "e0_t0", "e1_t0", "p_t1", "e0_t1", "e1_t1"};
constexpr std::array<const char*, 8> kEdgeEdgeNames = {"ea0_t0", "ea1_t0", "eb0_t0", "eb1_t0",
                                                       "ea0_t1", "ea1_t1", "eb0_t1", "eb1_t1"};
constexpr std::array<const char*, 8> kPointTriangleNames = {"p_t0", "t0_t0", "t1_t0", "t2_t0",
                                                            "p_t1", "t0_t1", "t1_t1", "t2_t1"};

constexpr const char* kIpcCallsDoc = R"(
Points are 1-D arrays (or sequences) of numbers: 2 or 3 coordinates for
point_point_ccd and point_edge_ccd (all of one length; 2D is read as
z = 0), 3 for edge_edge_ccd and point_triangle_ccd. Returns (hit, toi):
hit when the primitives come within min_distance in [0, tmax], toi then a
lower bound of that time (0 when they start within it); toi is inf without
a hit. ValueError with the library's message for points of another length
or a bad min_distance, tmax, tolerance or conservative_rescaling.
)";

std::string ipc_doc(const char* text) { return std::string(text) + kIpcCallsDoc; }

void define_ipc(py::module_ module) {
  module.attr("DEFAULT_CCD_TOLERANCE") = ipc::DEFAULT_CCD_TOLERANCE;
  module.attr("DEFAULT_CCD_MAX_ITERATIONS") = ipc::DEFAULT_CCD_MAX_ITERATIONS;
  module.attr("DEFAULT_CCD_CONSERVATIVE_RESCALING") = ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING;

  module.def(
      "point_point_ccd",
      [](py::object p0_t0, py::object p1_t0, py::object p0_t1, py::object p1_t1, double min_distance, double tmax,
         double tolerance, long max_iterations, double conservative_rescaling) {
        const IpcPoints<4> x({p0_t0, p1_t0, p0_t1, p1_t1}, kPointPointNames);
        return ipc_answer([&](double& toi) {
          return ipc::point_point_ccd(x[0], x[1], x[2], x[3], toi, min_distance, tmax, tolerance, max_iterations,
                                      conservative_rescaling);
        });
      },
      "p0_t0"_a, "p1_t0"_a, "p0_t1"_a, "p1_t1"_a, "min_distance"_a = 0.0, "tmax"_a = 1.0,
      "tolerance"_a = ipc::DEFAULT_CCD_TOLERANCE, "max_iterations"_a = ipc::DEFAULT_CCD_MAX_ITERATIONS,
      "conservative_rescaling"_a = ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING,
      ipc_doc(R"(point_point_ccd(p0_t0, p1_t0, p0_t1, p1_t1, min_distance=0.0, tmax=1.0, tolerance=1e-6, max_iterations=10000000, conservative_rescaling=0.8) -> (bool, float)

Point p0 against point p1, as ipctk.point_point_ccd (ipc.hpp).
)").c_str());
  module.def(
      "point_edge_ccd",
      [](py::object p_t0, py::object e0_t0, py::object e1_t0, py::object p_t1, py::object e0_t1, py::object e1_t1,
         double min_distance, double tmax, double tolerance, long max_iterations, double conservative_rescaling) {
        const IpcPoints<6> x({p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1}, kPointEdgeNames);
        return ipc_answer([&](double& toi) {
          return ipc::point_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], toi, min_distance, tmax, tolerance,
                                     max_iterations, conservative_rescaling);
        });
      },
      "p_t0"_a, "e0_t0"_a, "e1_t0"_a, "p_t1"_a, "e0_t1"_a, "e1_t1"_a, "min_distance"_a = 0.0, "tmax"_a = 1.0,
      "tolerance"_a = ipc::DEFAULT_CCD_TOLERANCE, "max_iterations"_a = ipc::DEFAULT_CCD_MAX_ITERATIONS,
      "conservative_rescaling"_a = ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING,
      ipc_doc(R"(point_edge_ccd(p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1, min_distance=0.0, tmax=1.0, tolerance=1e-6, max_iterations=10000000, conservative_rescaling=0.8) -> (bool, float)

Point p against edge (e0, e1), as ipctk.point_edge_ccd (ipc.hpp).
)").c_str());
  module.def(
      "edge_edge_ccd",
      [](py::object ea0_t0, py::object ea1_t0, py::object eb0_t0, py::object eb1_t0, py::object ea0_t1,
         py::object ea1_t1, py::object eb0_t1, py::object eb1_t1, double min_distance, double tmax, double tolerance,
         long max_iterations, double conservative_rescaling) {
        const IpcPoints<8> x({ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1}, kEdgeEdgeNames);
        return ipc_answer([&](double& toi) {
          return ipc::edge_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, min_distance, tmax,
                                    tolerance, max_iterations, conservative_rescaling);
        });
      },
      "ea0_t0"_a, "ea1_t0"_a, "eb0_t0"_a, "eb1_t0"_a, "ea0_t1"_a, "ea1_t1"_a, "eb0_t1"_a, "eb1_t1"_a,
      "min_distance"_a = 0.0, "tmax"_a = 1.0, "tolerance"_a = ipc::DEFAULT_CCD_TOLERANCE,
      "max_iterations"_a = ipc::DEFAULT_CCD_MAX_ITERATIONS,
      "conservative_rescaling"_a = ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING,
      ipc_doc(R"(edge_edge_ccd(ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1, min_distance=0.0, tmax=1.0, tolerance=1e-6, max_iterations=10000000, conservative_rescaling=0.8) -> (bool, float)

Edge (ea0, ea1) against edge (eb0, eb1), as ipctk.edge_edge_ccd (ipc.hpp).
)").c_str());
  module.def(
      "point_triangle_ccd",
      [](py::object p_t0, py::object t0_t0, py::object t1_t0, py::object t2_t0, py::object p_t1, py::object t0_t1,
         py::object t1_t1, py::object t2_t1, double min_distance, double tmax, double tolerance, long max_iterations,
         double conservative_rescaling) {
        const IpcPoints<8> x({p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1}, kPointTriangleNames);
        return ipc_answer([&](double& toi) {
          return ipc::point_triangle_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, min_distance, tmax,
                                         tolerance, max_iterations, conservative_rescaling);
        });
      },
      "p_t0"_a, "t0_t0"_a, "t1_t0"_a, "t2_t0"_a, "p_t1"_a, "t0_t1"_a, "t1_t1"_a, "t2_t1"_a, "min_distance"_a = 0.0,
      "tmax"_a = 1.0, "tolerance"_a = ipc::DEFAULT_CCD_TOLERANCE, "max_iterations"_a = ipc::DEFAULT_CCD_MAX_ITERATIONS,
      "conservative_rescaling"_a = ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING,
      ipc_doc(R"(point_triangle_ccd(p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1, min_distance=0.0, tmax=1.0, tolerance=1e-6, max_iterations=10000000, conservative_rescaling=0.8) -> (bool, float)

Point p against triangle (t0, t1, t2), as ipctk.point_triangle_ccd (ipc.hpp).
)").c_str());

  // The class's methods forward to ipc::NarrowPhase's, which forward its members.
  py::class_<ipc::NarrowPhase>(module, "NarrowPhase",
                               R"(NarrowPhase(tolerance=1e-6, max_iterations=10000000, conservative_rescaling=0.8)

ipctk.TightInclusionCCD's settings and calls (ipc.hpp's NarrowPhase): the
four calls take the points, min_distance=0.0 and tmax=1.0, and answer as
the functions of this module given the object's attributes. ValueError for
a tolerance that is not positive and finite or a conservative_rescaling
outside (0, 1]; max_iterations < 0: no limit.)")
      .def(py::init<double, long, double>(), "tolerance"_a = ipc::DEFAULT_CCD_TOLERANCE,
           "max_iterations"_a = ipc::DEFAULT_CCD_MAX_ITERATIONS,
           "conservative_rescaling"_a = ipc::DEFAULT_CCD_CONSERVATIVE_RESCALING)
      .def_readwrite("tolerance", &ipc::NarrowPhase::tolerance,
                     "The distance tolerance, in the points' length unit (checked by each call).")
      .def_readwrite("max_iterations", &ipc::NarrowPhase::max_iterations,
                     "The solver's budget; a query that exhausts it counts as a contact. < 0: none.")
      .def_readwrite("conservative_rescaling", &ipc::NarrowPhase::conservative_rescaling,
                     "The part of the gap a step may close, in (0, 1] (checked by each call).")
      .def(
          "point_point_ccd",
          [](const ipc::NarrowPhase& self, py::object p0_t0, py::object p1_t0, py::object p0_t1, py::object p1_t1,
             double min_distance, double tmax) {
            const IpcPoints<4> x({p0_t0, p1_t0, p0_t1, p1_t1}, kPointPointNames);
            return ipc_answer(
                [&](double& toi) { return self.point_point_ccd(x[0], x[1], x[2], x[3], toi, min_distance, tmax); });
          },
          "p0_t0"_a, "p1_t0"_a, "p0_t1"_a, "p1_t1"_a, "min_distance"_a = 0.0, "tmax"_a = 1.0,
          "point_point_ccd(p0_t0, p1_t0, p0_t1, p1_t1, min_distance=0.0, tmax=1.0) -> (bool, float)")
      .def(
          "point_edge_ccd",
          [](const ipc::NarrowPhase& self, py::object p_t0, py::object e0_t0, py::object e1_t0, py::object p_t1,
             py::object e0_t1, py::object e1_t1, double min_distance, double tmax) {
            const IpcPoints<6> x({p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1}, kPointEdgeNames);
            return ipc_answer([&](double& toi) {
              return self.point_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], toi, min_distance, tmax);
            });
          },
          "p_t0"_a, "e0_t0"_a, "e1_t0"_a, "p_t1"_a, "e0_t1"_a, "e1_t1"_a, "min_distance"_a = 0.0, "tmax"_a = 1.0,
          "point_edge_ccd(p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1, min_distance=0.0, tmax=1.0) -> (bool, float)")
      .def(
          "edge_edge_ccd",
          [](const ipc::NarrowPhase& self, py::object ea0_t0, py::object ea1_t0, py::object eb0_t0, py::object eb1_t0,
             py::object ea0_t1, py::object ea1_t1, py::object eb0_t1, py::object eb1_t1, double min_distance,
             double tmax) {
            const IpcPoints<8> x({ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1}, kEdgeEdgeNames);
            return ipc_answer([&](double& toi) {
              return self.edge_edge_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, min_distance, tmax);
            });
          },
          "ea0_t0"_a, "ea1_t0"_a, "eb0_t0"_a, "eb1_t0"_a, "ea0_t1"_a, "ea1_t1"_a, "eb0_t1"_a, "eb1_t1"_a,
          "min_distance"_a = 0.0, "tmax"_a = 1.0,
          "edge_edge_ccd(ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1, min_distance=0.0, "
          "tmax=1.0) -> (bool, float)")
      .def(
          "point_triangle_ccd",
          [](const ipc::NarrowPhase& self, py::object p_t0, py::object t0_t0, py::object t1_t0, py::object t2_t0,
             py::object p_t1, py::object t0_t1, py::object t1_t1, py::object t2_t1, double min_distance,
             double tmax) {
            const IpcPoints<8> x({p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1}, kPointTriangleNames);
            return ipc_answer([&](double& toi) {
              return self.point_triangle_ccd(x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], toi, min_distance,
                                             tmax);
            });
          },
          "p_t0"_a, "t0_t0"_a, "t1_t0"_a, "t2_t0"_a, "p_t1"_a, "t0_t1"_a, "t1_t1"_a, "t2_t1"_a,
          "min_distance"_a = 0.0, "tmax"_a = 1.0,
          "point_triangle_ccd(p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1, min_distance=0.0, tmax=1.0) "
          "-> (bool, float)")
      .def("__repr__", [](const ipc::NarrowPhase& self) {
        return "NarrowPhase(tolerance=" + py::repr(py::float_(self.tolerance)).cast<std::string>() +
               ", max_iterations=" + std::to_string(self.max_iterations) + ", conservative_rescaling=" +
               py::repr(py::float_(self.conservative_rescaling)).cast<std::string>() + ")";
      });

  module.def(
      "collision_free_stepsize",
      [](py::object x0, py::object x1, py::object faces, py::object vertex_face, py::object edge_edge,
         py::object vertex_edge, py::object vertex_vertex, double min_distance, py::object narrow_phase,
         int threads) {
        py::array keep[7];
        const MeshView mesh{positions_view(x0, "x0", keep[0]), positions_view(x1, "x1", keep[1]),
                            ids_view(faces, "faces", keep[2])};
        const auto rows = [&](py::object object, const char* name, py::ssize_t columns, py::array& slot) {
          if (!object.is_none()) slot = candidate_array(object, name, {columns});
          return !object.is_none();
        };
        CandidateLists candidates;
        if (rows(vertex_face, "vertex_face", 2, keep[3])) candidates.vertex_face = candidate_span<2>(keep[3]);
        if (rows(edge_edge, "edge_edge", 4, keep[4])) candidates.edge_edge = candidate_span<4>(keep[4]);
        if (rows(vertex_edge, "vertex_edge", 3, keep[5])) candidates.vertex_edge = candidate_span<3>(keep[5]);
        if (rows(vertex_vertex, "vertex_vertex", 2, keep[6])) candidates.vertex_vertex = candidate_span<2>(keep[6]);
        const ipc::NarrowPhase settings =
            narrow_phase.is_none() ? ipc::NarrowPhase{} : narrow_phase.cast<ipc::NarrowPhase>();
        py::gil_scoped_release release;
        return ipc::collision_free_stepsize(mesh, candidates, min_distance, settings, threads);
      },
      "x0"_a, "x1"_a, "faces"_a = py::none(), "vertex_face"_a = py::none(), "edge_edge"_a = py::none(),
      "vertex_edge"_a = py::none(), "vertex_vertex"_a = py::none(), py::kw_only(), "min_distance"_a = 0.0,
      "narrow_phase"_a = py::none(), "threads"_a = 0,
      R"(collision_free_stepsize(x0, x1, faces=None, vertex_face=None, edge_edge=None, vertex_edge=None, vertex_vertex=None, *, min_distance=0.0, narrow_phase=None, threads=0) -> float

ipctk.compute_collision_free_stepsize over a broad phase's candidates, in
one call (ipc_stepsize.hpp): the largest step in [0, 1] that keeps every
candidate pair as the narrow phase's calls of this module would (each
asked with tmax the earliest toi so far), 1 when nothing is in the way.
x0, x1 are n x 3 or n x 2 (a 2D mesh) positions; the candidate lists are
rows of vertex ids as in batchccd.mesh_ccd; narrow_phase a NarrowPhase
(its tolerance, max_iterations and conservative_rescaling; None: the
defaults). The same step for any thread count. ValueError names a bad
argument or id.)");
}

}  // namespace
}  // namespace batchccd::python

PYBIND11_MODULE(_batchccd, m) {
  using namespace batchccd;
  using namespace batchccd::python;
  // The docstrings open with the Python signature; pybind11's own, all
  // `object`, would only add noise.
  py::options signatures;
  signatures.disable_function_signatures();
  m.doc() = "batchccd: narrow-phase continuous collision detection over NumPy arrays.";
  m.attr("__version__") = BATCHCCD_VERSION;
  // Library errors (std::invalid_argument) as ValueError, in Python's names.
  py::register_local_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const std::invalid_argument& error) {
      PyErr_SetString(PyExc_ValueError, in_python_names(error.what()).c_str());
    }
  });
  // Status as an IntEnum: it prints its name and compares, indexes and
  // stores as the int it is (the result arrays hold the ints).
  const py::object status_enum = py::module_::import("enum").attr("IntEnum")(
      "Status",
      py::make_tuple(py::make_tuple("OK", static_cast<int>(Status::ok)),
                     py::make_tuple("INVALID_INPUT", static_cast<int>(Status::invalid_input))),
      "module"_a = "batchccd");
  status_enum.attr("__doc__") =
      "A query's status: OK (evaluated), INVALID_INPUT (a NaN or infinite coordinate: not evaluated, "
      "hit True, toi 0).";
  m.attr("Status") = status_enum;
  m.attr("STATUS_OK") = status_enum.attr("OK");
  m.attr("STATUS_INVALID_INPUT") = status_enum.attr("INVALID_INPUT");
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError).attr("__doc__") =
      "What read_scene raises on a missing, unreadable or malformed file: \"file:line: problem\" (io.hpp).";

  py::class_<QueryResult>(m, "QueryResult", "The answer to one query: hit, toi (+inf without a hit), status.")
      .def_readonly("hit", &QueryResult::hit, "The primitives come within min_distance at some t in [0, tmax].")
      .def_readonly("toi", &QueryResult::toi, "Time of impact in [0, tmax]; +inf when there is none.")
      .def_property_readonly(
          "status", [status_enum](const QueryResult& r) { return status_enum(static_cast<int>(r.status)); },
          "Status.OK, or Status.INVALID_INPUT for a NaN or infinite coordinate (then hit, toi 0).")
      .def("__repr__", [status_enum](const QueryResult& r) {
        const py::object status = status_enum(static_cast<int>(r.status));
        return "QueryResult(hit=" + std::string(r.hit ? "True" : "False") + ", toi=" +
               py::repr(py::float_(r.toi)).cast<std::string>() + ", status=Status." +
               status.attr("name").cast<std::string>() + ")";
      });

  py::class_<Result>(m, "BatchResult",
                     "What a batch or mesh call returns. The arrays are read-only views of the result "
                     "(no copy); pass the object back as out= to reuse its storage.")
      .def_property_readonly(
          "earliest_toi", [](const Result& r) { return r.storage->earliest_toi; },
          "Earliest TOI over all candidates; inf when nothing collides (0 with an invalid coordinate).")
      .def_property_readonly(
          "counters", [](const Result& r) { return counters_dict(r.storage->counters); },
          "Counts summed over the call: candidates, culled, solved, hits, undecided, invalid, "
          "exact_escalations, ...")
      .def_property_readonly(
          "hit", [](const Result& r) { return field_view<QueryResult, bool>(r, r.storage->results, offsetof(QueryResult, hit), r.has_results); },
          "bool per candidate (vertex-face, edge-edge, vertex-edge, vertex-vertex order); None without "
          "per_candidate_results.")
      .def_property_readonly(
          "toi", [](const Result& r) { return field_view<QueryResult, double>(r, r.storage->results, offsetof(QueryResult, toi), r.has_results); },
          "float64 TOI per candidate, inf without a hit; None without per_candidate_results.")
      .def_property_readonly(
          "status", [](const Result& r) { return field_view<QueryResult, std::int32_t>(r, r.storage->results, offsetof(QueryResult, status), r.has_results); },
          "int32 status per candidate (the values of Status); None without per_candidate_results.")
      .def_property_readonly(
          "hit_candidates", [](const Result& r) { return field_view<Hit, std::int64_t>(r, r.storage->hits, offsetof(Hit, candidate), r.has_hits); },
          "int64 indices of the candidates that hit, increasing; None without hit_list.")
      .def_property_readonly(
          "hit_tois", [](const Result& r) { return field_view<Hit, double>(r, r.storage->hits, offsetof(Hit, toi), r.has_hits); },
          "float64 TOI of each listed hit; None without hit_list.")
      .def_property_readonly(
          "hit_statuses", [](const Result& r) { return field_view<Hit, std::int32_t>(r, r.storage->hits, offsetof(Hit, status), r.has_hits); },
          "int32 status of each listed hit (the values of Status); None without hit_list.")
      .def("__repr__", [](const Result& r) {
        return "BatchResult(earliest_toi=" + py::repr(py::float_(r.storage->earliest_toi)).cast<std::string>() +
               ", candidates=" + std::to_string(r.storage->counters.candidates) + ", hits=" +
               std::to_string(r.storage->counters.hits) + ")";
      });

  m.def("mesh_ccd", &mesh_ccd_py, py::arg("x0"), py::arg("x1"), py::arg("faces") = py::none(),
        py::arg("edges") = py::none(), py::arg("vertex_face") = py::none(), py::arg("edge_edge") = py::none(),
        py::arg("vertex_edge") = py::none(), py::arg("vertex_vertex") = py::none(), py::kw_only(),
        py::arg("min_distances") = py::none(), py::arg("out") = py::none(),
        doc(R"(mesh_ccd(x0, x1, faces=None, edges=None, vertex_face=None, edge_edge=None, vertex_edge=None, vertex_vertex=None, *, min_distances=None, out=None, **options) -> BatchResult

Broad-phase candidates over a mesh, evaluated in parallel (batch.hpp).

x0, x1       vertex positions at t0 and t1, n x 3 (or n x 2 at both: a 2D
             mesh, read as z = 0), float64 or float32, any order or strides
             (read in place; copied once when the strides are not whole
             elements or the array is misaligned).
faces        triangles, m x 3 vertex ids (int32 in place; other integer
             dtypes copied once, each value checked to fit).
edges        k x 2 vertex ids, for candidates that name edges by id.
vertex_face  rows (vertex, face).
edge_edge    rows (a0, a1, b0, b1) of vertex ids, or (edge, edge) ids into
             `edges` (2 columns).
vertex_edge  rows (vertex, e0, e1), or (vertex, edge id) (2 columns).
vertex_vertex
             rows (p, q).
             Candidate lists are read in place when C-ordered int32.
min_distances
             one separation per candidate replacing min_distance: a 1-D
             array over all candidates in result order, or a dict
             {"edge_edge": array, ...} of lists (the others take min_distance).
out          a BatchResult of an earlier call whose storage is reused.

Returns a BatchResult: earliest_toi, counters, and per candidate (order
vertex-face, edge-edge, vertex-edge, vertex-vertex) hit, toi and status,
or the hit list (hit_candidates, hit_tois, hit_statuses).

Bad input: ValueError with the library's message (in this module's
names: x0, x1, min_distance), before anything is evaluated, for position arrays of different row counts, a wrong column
count, an id out of range (also in a list the options switch off), bad
options or separations; TypeError for a non-numeric dtype. A NaN or
infinite coordinate is no error: exactly the candidates that read that
vertex get status Status.INVALID_INPUT, hit True, toi 0. The GIL is
released during the evaluation.
)").c_str());

  m.def("batch_ccd", &batch_ccd_py, py::arg("kind"), py::arg("queries"), py::arg("min_distances") = py::none(),
        py::kw_only(), py::arg("out") = py::none(),
        doc(R"(batch_ccd(kind, queries, min_distances=None, *, out=None, **options) -> BatchResult

Raw queries, all of one kind, evaluated in parallel (batch.hpp).

kind       "vf", "ee", "ve", "vv" (or "vertex_face", "edge_edge",
           "vertex_edge", "vertex_vertex").
queries    N x 8 x 3 (or N x 24) float64, eight points a query, t0 first, in
           Query's order: vertex_face p, a, b, c; edge_edge ea0, ea1, eb0,
           eb1; vertex_edge p, p, e0, e1; vertex_vertex p, p, q, q
           (make_query builds them). C-ordered float64 is read in place,
           anything else copied once. A 2D scene's: N x 8 x 2 (or N x 16),
           the queries lifted to the plane z = 0.
min_distances
           one separation per query (1-D, length N), replacing min_distance.
out        a BatchResult of an earlier call whose storage is reused.

Returns a BatchResult. A query with a NaN or infinite coordinate gets
Status.INVALID_INPUT (hit True, toi 0); the others are unaffected.
)").c_str());

  m.def(
      "vertex_face_ccd",
      [](py::object p_t0, py::object a_t0, py::object b_t0, py::object c_t0, py::object p_t1, py::object a_t1,
         py::object b_t1, py::object c_t1, const py::kwargs& keywords) {
        return single_query<8>(Kind::vertex_face, {p_t0, a_t0, b_t0, c_t0, p_t1, a_t1, b_t1, c_t1},
                               {"p_t0", "a_t0", "b_t0", "c_t0", "p_t1", "a_t1", "b_t1", "c_t1"}, keywords);
      },
      py::arg("p_t0"), py::arg("a_t0"), py::arg("b_t0"), py::arg("c_t0"), py::arg("p_t1"), py::arg("a_t1"),
      py::arg("b_t1"), py::arg("c_t1"),
      doc(R"(vertex_face_ccd(p_t0, a_t0, b_t0, c_t0, p_t1, a_t1, b_t1, c_t1, **options) -> QueryResult

Vertex p against triangle (a, b, c) (ccd.hpp); each point 3 coordinates,
moving linearly from its _t0 to its _t1 position. hit when the vertex
comes within min_distance of the triangle (edges and corners included) at
some t in [0, tmax]. A NaN or infinite coordinate: status
Status.INVALID_INPUT, hit True, toi 0. Degenerate geometry is valid input.
)").c_str());
  m.def(
      "edge_edge_ccd",
      [](py::object ea0_t0, py::object ea1_t0, py::object eb0_t0, py::object eb1_t0, py::object ea0_t1,
         py::object ea1_t1, py::object eb0_t1, py::object eb1_t1, const py::kwargs& keywords) {
        return single_query<8>(Kind::edge_edge, {ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1},
                               {"ea0_t0", "ea1_t0", "eb0_t0", "eb1_t0", "ea0_t1", "ea1_t1", "eb0_t1", "eb1_t1"},
                               keywords);
      },
      py::arg("ea0_t0"), py::arg("ea1_t0"), py::arg("eb0_t0"), py::arg("eb1_t0"), py::arg("ea0_t1"),
      py::arg("ea1_t1"), py::arg("eb0_t1"), py::arg("eb1_t1"),
      doc(R"(edge_edge_ccd(ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, eb1_t1, **options) -> QueryResult

Edge (ea0, ea1) against edge (eb0, eb1), moving as in vertex_face_ccd:
hit when the segments (end points included) come within min_distance at
some t in [0, tmax]. Zero-length and parallel edges are valid input.
)").c_str());
  m.def(
      "vertex_edge_ccd",
      [](py::object p_t0, py::object e0_t0, py::object e1_t0, py::object p_t1, py::object e0_t1, py::object e1_t1,
         const py::kwargs& keywords) {
        return single_query<6>(Kind::vertex_edge, {p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1},
                               {"p_t0", "e0_t0", "e1_t0", "p_t1", "e0_t1", "e1_t1"}, keywords);
      },
      py::arg("p_t0"), py::arg("e0_t0"), py::arg("e1_t0"), py::arg("p_t1"), py::arg("e0_t1"), py::arg("e1_t1"),
      doc(R"(vertex_edge_ccd(p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1, **options) -> QueryResult

Point p against segment (e0, e1): hit when the point comes within
min_distance of the segment (end points included). Points of 2 or 3
coordinates, all of one length (2D is read as z = 0).
)").c_str());
  m.def(
      "vertex_vertex_ccd",
      [](py::object p_t0, py::object q_t0, py::object p_t1, py::object q_t1, const py::kwargs& keywords) {
        return single_query<4>(Kind::vertex_vertex, {p_t0, q_t0, p_t1, q_t1}, {"p_t0", "q_t0", "p_t1", "q_t1"},
                               keywords);
      },
      py::arg("p_t0"), py::arg("q_t0"), py::arg("p_t1"), py::arg("q_t1"),
      doc(R"(vertex_vertex_ccd(p_t0, q_t0, p_t1, q_t1, **options) -> QueryResult

Point p against point q: hit when they come within min_distance. Points
of 2 or 3 coordinates, all of one length (2D is read as z = 0).
)").c_str());
  m.def(
      "query_ccd",
      [](const std::string& kind, py::object query, const py::kwargs& keywords) {
        const Kind k = kind_from(kind);
        const Options options = parse_options(keywords);
        const Query q = one_query(query, "query");
        py::gil_scoped_release release;
        return query_ccd(k, q, options);
      },
      py::arg("kind"), py::arg("query"),
      doc(R"(query_ccd(kind, query, **options) -> QueryResult

One query of any kind: 8 x 3 (or 24) coordinates in Query's order, as a
row of batch_ccd's queries (2D: 8 x 2, lifted to z = 0). The same answer as
the calls above.
)").c_str());
  m.def(
      "squared_distance",
      [](const std::string& kind, py::object query, double t) {
        return squared_distance(kind_from(kind), one_query(query, "query"), t);
      },
      py::arg("kind"), py::arg("query"), py::arg("t") = 0.0,
      R"(squared_distance(kind, query, t=0.0) -> float

The squared Euclidean distance between the query's closed primitives at
time t in [0, 1], in plain double arithmetic (not certified): what a
simulator takes a per-pair separation from.)");
  m.def(
      "make_query",
      [](const std::string& kind, py::object points_t0, py::object points_t1) {
        const Kind k = kind_from(kind);
        const auto values = [](py::object object, const char* name) {
          py::array array = ensure_array(object, name);
          if (array.ndim() != 2 || (array.shape(1) != 3 && array.shape(1) != 2))
            throw py::value_error(std::string(name) + ": expected k x 3 points (2D: k x 2)");
          return py::array_t<double>(copy_as<double>(array));
        };
        const py::array_t<double> start = values(points_t0, "points_t0"), end = values(points_t1, "points_t1");
        if (start.shape(1) != end.shape(1))
          throw py::value_error("points_t0 and points_t1: 2D and 3D points mixed");
        const auto points = [](const py::array_t<double>& array, auto point) {
          std::vector<decltype(point)> result(static_cast<std::size_t>(array.shape(0)));
          for (std::size_t i = 0; i < result.size(); ++i)
            for (int j = 0; j < point.size(); ++j) result[i](j) = array.at(static_cast<py::ssize_t>(i), j);
          return result;
        };
        if (start.shape(1) == 2) return query_array(make_query(k, points(start, Vec2()), points(end, Vec2())));
        return query_array(make_query(k, points(start, Vec3()), points(end, Vec3())));
      },
      py::arg("kind"), py::arg("points_t0"), py::arg("points_t1"),
      R"(make_query(kind, points_t0, points_t1) -> ndarray (8 x 3, or 8 x 2)

The query of `kind` whose points at t0 are points_t0 and at t1 points_t1
(4, 4, 3 or 2 points each: vertex_edge p, e0, e1; vertex_vertex p, q),
in Query's layout with the repetitions; 2D points (k x 2) give a 2D query.
ValueError for another count.)");
  m.def(
      "unique_edges",
      [](py::object faces) {
        py::array keep;
        const IdsView view = ids_view(faces, "faces", keep);
        Eigen::MatrixXi edges;
        {
          py::gil_scoped_release release;
          edges = unique_edges(view);
        }
        return matrix_array(edges);
      },
      py::arg("faces"),
      R"(unique_edges(faces) -> ndarray (k x 2, int32)

The undirected edges of the triangles, each once, (i, j) with i < j, rows
sorted: ready for mesh_ccd's edges.)");
  m.def("read_scene", &read_scene_py, py::arg("path"),
        R"(read_scene(path) -> dict

A scene directory (t0.ply, t1.ply, vf.csv, ee.csv, optional ve.csv,
vv.csv and *_truth.txt; docs/design.md §9): a dict with x0, x1 (float64
n x 3), faces (int32), the candidate lists vertex_face, edge_edge,
vertex_edge, vertex_vertex (int32, by vertex id) and their truth
(<list>_truth: bool arrays, or None). InputError (a ValueError) names the
file, line and problem.)");
  m.def("default_options", &default_options,
        "default_options() -> dict\n\nEvery option the calls take, with its default.");
  m.def("modes", [] { return names_list(mode_names()); }, "modes() -> list[str]\n\nThe modes this build takes.");
  m.def("kinds", [] { return names_list(kind_names()); }, "kinds() -> list[str]\n\nThe kinds' short names.");
  m.def(
      "available_isas",
      [] {
        py::list names;
        for (const Isa isa : available_isas()) names.append(to_string(isa));
        return names;
      },
      "available_isas() -> list[str]\n\nThe instruction sets a batch call can be forced to here, scalar first.");
  m.def(
      "resolve_isa", [](const std::string& name) {
        Options options = parse_options(py::dict("isa"_a = name));
        return std::string(to_string(resolve_isa(options.isa)));
      },
      py::arg("isa") = "auto",
      "resolve_isa(isa='auto') -> str\n\nThe instruction set a batch call with `isa` runs; ValueError when "
      "a forced one is not available.");

  define_ipc(m.def_submodule("ipc", "ipc-toolkit's CCD calls, as ipctk names and answers them (ipc.hpp)."));
}
