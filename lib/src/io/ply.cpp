// PLY meshes in the three standard encodings (ascii, binary little- and
// big-endian). The header is parsed into a description of the elements; one
// body reader, written once over a value source per encoding, then reads the
// vertex and face elements and skips every other element.

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "batchccd/io.hpp"
#include "io/text_input.hpp"

namespace batchccd {

namespace {

using io_detail::in_quotes;

// ---------------------------------------------------------------- types

enum class ScalarType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

struct ScalarTypeName {
  std::string_view name;
  ScalarType type;
};

// Both spellings of the PLY specification.
constexpr std::array<ScalarTypeName, 16> scalar_type_names{{
    {"char", ScalarType::int8},
    {"int8", ScalarType::int8},
    {"uchar", ScalarType::uint8},
    {"uint8", ScalarType::uint8},
    {"short", ScalarType::int16},
    {"int16", ScalarType::int16},
    {"ushort", ScalarType::uint16},
    {"uint16", ScalarType::uint16},
    {"int", ScalarType::int32},
    {"int32", ScalarType::int32},
    {"uint", ScalarType::uint32},
    {"uint32", ScalarType::uint32},
    {"float", ScalarType::float32},
    {"float32", ScalarType::float32},
    {"double", ScalarType::float64},
    {"float64", ScalarType::float64},
}};

std::optional<ScalarType> scalar_type_named(std::string_view name) {
  for (const ScalarTypeName& entry : scalar_type_names)
    if (entry.name == name) return entry.type;
  return std::nullopt;
}

std::size_t byte_size(ScalarType type) {
  switch (type) {
    case ScalarType::int8:
    case ScalarType::uint8:
      return 1;
    case ScalarType::int16:
    case ScalarType::uint16:
      return 2;
    case ScalarType::int32:
    case ScalarType::uint32:
    case ScalarType::float32:
      return 4;
    case ScalarType::float64:
      return 8;
  }
  return 8;
}

bool is_integer(ScalarType type) { return type != ScalarType::float32 && type != ScalarType::float64; }

std::int64_t lowest_value(ScalarType type) {
  switch (type) {
    case ScalarType::int8:
      return INT8_MIN;
    case ScalarType::int16:
      return INT16_MIN;
    case ScalarType::int32:
      return INT32_MIN;
    default:
      return 0;
  }
}

std::int64_t highest_value(ScalarType type) {
  switch (type) {
    case ScalarType::int8:
      return INT8_MAX;
    case ScalarType::uint8:
      return UINT8_MAX;
    case ScalarType::int16:
      return INT16_MAX;
    case ScalarType::uint16:
      return UINT16_MAX;
    case ScalarType::int32:
      return INT32_MAX;
    default:
      return UINT32_MAX;
  }
}

struct Property {
  std::string name;
  ScalarType value_type = ScalarType::float64;
  std::optional<ScalarType> list_count_type;  // set for a list property
  bool is_list() const { return list_count_type.has_value(); }
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  long header_line = 0;
};

enum class Encoding { ascii, binary_little_endian, binary_big_endian };

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;  // first byte after the end_header line
  long body_first_line = 0;     // for ascii messages
};

std::vector<std::string_view> whitespace_tokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

// Parses the whole token as an integer of type T, or nothing.
template <class T>
std::optional<T> parse_whole_integer(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  T value{};
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

// ---------------------------------------------------------------- header

class HeaderParser {
 public:
  HeaderParser(std::string file, std::string_view bytes) : file_(std::move(file)), bytes_(bytes) {}

  Header parse() {
    std::string_view line;
    if (!next_line(line) || line != "ply") fail("not a PLY file: the first line must be 'ply'");
    bool has_format = false;
    while (next_line(line)) {
      const std::vector<std::string_view> tokens = whitespace_tokens(line);
      if (tokens.empty()) continue;
      const std::string_view keyword = tokens.front();
      if (keyword == "comment" || keyword == "obj_info") continue;
      if (keyword == "format") {
        parse_format(tokens, has_format);
      } else if (keyword == "element") {
        parse_element(tokens);
      } else if (keyword == "property") {
        parse_property(tokens);
      } else if (keyword == "end_header") {
        if (tokens.size() != 1) fail("unexpected text after end_header");
        if (!has_format) fail("the header has no format line");
        header_.body_offset = position_;
        header_.body_first_line = line_ + 1;
        return header_;
      } else {
        fail("unknown header keyword " + in_quotes(keyword));
      }
    }
    throw InputError(file_, 0, "the header has no end_header line");
  }

 private:
  // The next line without its '\n' (and '\r'); false at the end of the file.
  bool next_line(std::string_view& line) {
    if (position_ >= bytes_.size()) return false;
    std::size_t end = bytes_.find('\n', position_);
    const std::size_t next = end == std::string_view::npos ? bytes_.size() : end + 1;
    if (end == std::string_view::npos) end = bytes_.size();
    line = bytes_.substr(position_, end - position_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    position_ = next;
    ++line_;
    return true;
  }

  void parse_format(const std::vector<std::string_view>& tokens, bool& has_format) {
    if (has_format) fail("a second format line");
    if (tokens.size() != 3) fail("expected 'format ENCODING 1.0'");
    if (tokens[1] == "ascii") {
      header_.encoding = Encoding::ascii;
    } else if (tokens[1] == "binary_little_endian") {
      header_.encoding = Encoding::binary_little_endian;
    } else if (tokens[1] == "binary_big_endian") {
      header_.encoding = Encoding::binary_big_endian;
    } else {
      fail("unknown format " + in_quotes(tokens[1]));
    }
    if (tokens[2] != "1.0") fail("unsupported PLY version " + in_quotes(tokens[2]) + " (expected 1.0)");
    has_format = true;
  }

  void parse_element(const std::vector<std::string_view>& tokens) {
    if (tokens.size() != 3) fail("expected 'element NAME COUNT'");
    const std::string name(tokens[1]);
    for (const Element& element : header_.elements)
      if (element.name == name) fail("a second element named " + in_quotes(name));
    const auto count = parse_whole_integer<std::uint64_t>(tokens[2]);
    if (!count) fail("element count " + in_quotes(tokens[2]) + " is not a non-negative integer");
    header_.elements.push_back({name, *count, {}, line_});
  }

  void parse_property(const std::vector<std::string_view>& tokens) {
    if (header_.elements.empty()) fail("a property before any element");
    Property property;
    if (tokens.size() == 5 && tokens[1] == "list") {
      property.list_count_type = type_named(tokens[2]);
      if (!is_integer(*property.list_count_type)) fail("a list count type must be an integer type");
      property.value_type = type_named(tokens[3]);
      property.name = tokens[4];
    } else if (tokens.size() == 3 && tokens[1] != "list") {
      property.value_type = type_named(tokens[1]);
      property.name = tokens[2];
    } else {
      fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
    }
    std::vector<Property>& properties = header_.elements.back().properties;
    for (const Property& other : properties)
      if (other.name == property.name) fail("a second property named " + in_quotes(property.name));
    properties.push_back(std::move(property));
  }

  ScalarType type_named(std::string_view name) const {
    const std::optional<ScalarType> type = scalar_type_named(name);
    if (!type) fail("unknown property type " + in_quotes(name));
    return *type;
  }

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(file_, line_, problem); }

  std::string file_;
  std::string_view bytes_;
  std::size_t position_ = 0;
  long line_ = 0;
  Header header_;
};

// ---------------------------------------------------------------- layout

// Where the mesh lives among the elements and properties of a header.
struct MeshLayout {
  const Element* vertex = nullptr;
  std::array<std::size_t, 3> coordinate_property{};  // x, y, z
  const Element* face = nullptr;
  std::size_t index_property = 0;  // the vertex_indices list
};

std::optional<std::size_t> property_index(const Element& element, std::string_view name) {
  for (std::size_t i = 0; i < element.properties.size(); ++i)
    if (element.properties[i].name == name) return i;
  return std::nullopt;
}

const Element* element_named(const Header& header, std::string_view name) {
  for (const Element& element : header.elements)
    if (element.name == name) return &element;
  return nullptr;
}

// Eigen's rows and face ids are int: larger counts cannot be represented.
void check_count_fits_int(const std::string& file, const Element& element) {
  if (element.count > static_cast<std::uint64_t>(INT_MAX))
    throw InputError(file, element.header_line,
                     "element " + element.name + " declares " + std::to_string(element.count) + " entries (at most " +
                         std::to_string(INT_MAX) + " supported)");
}

void locate_coordinates(const std::string& file, const Element& vertex, MeshLayout& layout) {
  constexpr std::array<std::string_view, 3> names{"x", "y", "z"};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const std::optional<std::size_t> index = property_index(vertex, names[axis]);
    if (!index)
      throw InputError(file, vertex.header_line, "the vertex element has no property " + in_quotes(names[axis]));
    if (vertex.properties[*index].is_list())
      throw InputError(file, vertex.header_line, "vertex property " + in_quotes(names[axis]) + " is a list");
    layout.coordinate_property[axis] = *index;
  }
}

void locate_face_indices(const std::string& file, const Element& face, MeshLayout& layout) {
  std::optional<std::size_t> index = property_index(face, "vertex_indices");
  if (!index) index = property_index(face, "vertex_index");
  if (!index)
    throw InputError(file, face.header_line, "the face element has no vertex_indices (or vertex_index) property");
  const Property& property = face.properties[*index];
  if (!property.is_list())
    throw InputError(file, face.header_line, "face property " + property.name + " is not a list");
  if (!is_integer(property.value_type))
    throw InputError(file, face.header_line, "face property " + property.name + " must hold integers");
  layout.index_property = *index;
}

MeshLayout mesh_layout(const std::string& file, const Header& header) {
  MeshLayout layout;
  layout.vertex = element_named(header, "vertex");
  if (!layout.vertex) throw InputError(file, 0, "the header declares no vertex element");
  check_count_fits_int(file, *layout.vertex);
  locate_coordinates(file, *layout.vertex, layout);
  layout.face = element_named(header, "face");
  if (layout.face) {
    check_count_fits_int(file, *layout.face);
    locate_face_indices(file, *layout.face, layout);
  }
  return layout;
}

// The fewest bytes one entry of an element can take in a binary body.
std::uint64_t least_binary_size(const Element& element) {
  std::uint64_t size = 0;
  for (const Property& property : element.properties)
    size += byte_size(property.list_count_type.value_or(property.value_type));
  return size;
}

// Refuses a header that declares more than the body can hold before anything
// is allocated for it. An ascii entry takes at least one byte.
void check_declared_size(const std::string& file, const Header& header, std::uint64_t body_size) {
  std::uint64_t remaining = body_size;
  for (const Element& element : header.elements) {
    if (element.properties.empty()) continue;
    const std::uint64_t entry_size = header.encoding == Encoding::ascii ? 1 : least_binary_size(element);
    if (element.count > remaining / entry_size)
      throw InputError(file, 0,
                       "truncated file: the header declares " + std::to_string(element.count) + " " + element.name +
                           " entries, more than the " + std::to_string(body_size) + " bytes of the body can hold");
    remaining -= element.count * entry_size;
  }
}

// ---------------------------------------------------------------- value sources

// Names the element entry being read, for messages.
class EntryContext {
 public:
  void enter(const Element& element, std::uint64_t index) {
    element_ = &element;
    index_ = index;
  }
  std::string describe() const {
    if (!element_) return "header";
    return io_detail::printable(element_->name) + " " + std::to_string(index_);
  }

 private:
  const Element* element_ = nullptr;
  std::uint64_t index_ = 0;
};

template <class T>
T load_bytes(const char* bytes, bool swap_bytes) {
  std::array<char, sizeof(T)> raw;
  std::memcpy(raw.data(), bytes, sizeof(T));
  if (swap_bytes) std::reverse(raw.begin(), raw.end());
  T value;
  std::memcpy(&value, raw.data(), sizeof(T));
  return value;
}

class BinarySource {
 public:
  BinarySource(std::string file, std::string_view body, bool swap_bytes)
      : file_(std::move(file)), body_(body), swap_bytes_(swap_bytes) {}

  void begin_entry(const Element& element, std::uint64_t index) { context_.enter(element, index); }
  void end_entry() {}

  double read_real(ScalarType type) {
    const char* bytes = take(byte_size(type));
    switch (type) {
      case ScalarType::float32:
        return static_cast<double>(load_bytes<float>(bytes, swap_bytes_));
      case ScalarType::float64:
        return load_bytes<double>(bytes, swap_bytes_);
      default:
        return static_cast<double>(decode_integer(type, bytes));
    }
  }

  std::int64_t read_integer(ScalarType type) { return decode_integer(type, take(byte_size(type))); }

  void skip(ScalarType type, std::uint64_t count) {
    if (count > (body_.size() - position_) / byte_size(type)) fail_truncated();
    position_ += static_cast<std::size_t>(count) * byte_size(type);
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(file_, 0, context_.describe() + ": " + problem);
  }

 private:
  const char* take(std::size_t size) {
    if (size > body_.size() - position_) fail_truncated();
    const char* bytes = body_.data() + position_;
    position_ += size;
    return bytes;
  }

  std::int64_t decode_integer(ScalarType type, const char* bytes) const {
    switch (type) {
      case ScalarType::int8:
        return load_bytes<std::int8_t>(bytes, swap_bytes_);
      case ScalarType::uint8:
        return load_bytes<std::uint8_t>(bytes, swap_bytes_);
      case ScalarType::int16:
        return load_bytes<std::int16_t>(bytes, swap_bytes_);
      case ScalarType::uint16:
        return load_bytes<std::uint16_t>(bytes, swap_bytes_);
      case ScalarType::int32:
        return load_bytes<std::int32_t>(bytes, swap_bytes_);
      case ScalarType::uint32:
        return load_bytes<std::uint32_t>(bytes, swap_bytes_);
      default:
        fail("expected an integer type");  // excluded by the header checks
    }
  }

  [[noreturn]] void fail_truncated() const {
    fail("truncated file: the binary body ends before the entries the header declares");
  }

  std::string file_;
  std::string_view body_;
  std::size_t position_ = 0;
  bool swap_bytes_;
  EntryContext context_;
};

// One entry a line, values separated by spaces or tabs; blank lines skipped.
class AsciiSource {
 public:
  AsciiSource(std::string file, std::string_view body, long first_line)
      : file_(std::move(file)), body_(body), next_line_number_(first_line) {}

  void begin_entry(const Element& element, std::uint64_t index) {
    context_.enter(element, index);
    tokens_.clear();
    next_token_ = 0;
    while (tokens_.empty()) {
      if (position_ >= body_.size()) fail("truncated file: the body ends before the entries the header declares");
      tokens_ = whitespace_tokens(next_line());
    }
  }

  void end_entry() {
    if (next_token_ < tokens_.size())
      fail("expected " + std::to_string(next_token_) + " values on this line, found " + std::to_string(tokens_.size()));
  }

  // A float property's text is kept at double precision: the digits are what
  // the writer meant, and the finite check comes after.
  double read_real(ScalarType type) {
    if (is_integer(type)) return static_cast<double>(read_integer(type));
    std::string_view token = next_token();
    if (token.size() > 1 && token.front() == '+') token.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error == std::errc::result_out_of_range) fail("number " + in_quotes(token) + " is out of the double range");
    if (error != std::errc() || end != token.data() + token.size())
      fail("expected a number, found " + in_quotes(token));
    return value;
  }

  std::int64_t read_integer(ScalarType type) {
    const std::string_view token = next_token();
    const std::optional<std::int64_t> value = parse_whole_integer<std::int64_t>(token);
    if (!value) fail("expected an integer, found " + in_quotes(token));
    if (*value < lowest_value(type) || *value > highest_value(type))
      fail("integer " + in_quotes(token) + " is out of the range of its property type");
    return *value;
  }

  void skip(ScalarType, std::uint64_t count) {
    if (count > tokens_.size() - next_token_)
      fail("expected at least " + std::to_string(next_token_ + count) + " values on this line, found " +
           std::to_string(tokens_.size()));
    next_token_ += static_cast<std::size_t>(count);
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(file_, line_number_, context_.describe() + ": " + problem);
  }

 private:
  std::string_view next_line() {
    std::size_t end = body_.find('\n', position_);
    if (end == std::string_view::npos) end = body_.size();
    std::string_view line = body_.substr(position_, end - position_);
    position_ = end + 1;
    line_number_ = next_line_number_++;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }

  std::string_view next_token() {
    if (next_token_ >= tokens_.size())
      fail("expected more than " + std::to_string(tokens_.size()) + " values on this line");
    return tokens_[next_token_++];
  }

  std::string file_;
  std::string_view body_;
  std::size_t position_ = 0;
  long next_line_number_;
  long line_number_ = 0;
  std::vector<std::string_view> tokens_;
  std::size_t next_token_ = 0;
  EntryContext context_;
};

// ---------------------------------------------------------------- body

template <class Source>
class BodyReader {
 public:
  BodyReader(Source& source, const Header& header, const MeshLayout& layout)
      : source_(source), header_(header), layout_(layout) {}

  PlyMesh read() {
    PlyMesh mesh;
    mesh.vertices.resize(static_cast<Eigen::Index>(layout_.vertex->count), 3);
    mesh.faces.resize(layout_.face ? static_cast<Eigen::Index>(layout_.face->count) : 0, 3);
    for (const Element& element : header_.elements) {
      if (element.properties.empty()) continue;  // nothing stored for it
      for (std::uint64_t index = 0; index < element.count; ++index) {
        source_.begin_entry(element, index);
        if (&element == layout_.vertex) {
          read_vertex(element, mesh.vertices.row(static_cast<Eigen::Index>(index)));
        } else if (&element == layout_.face) {
          read_face(element, mesh.faces.row(static_cast<Eigen::Index>(index)));
        } else {
          skip_entry(element);
        }
        source_.end_entry();
      }
    }
    return mesh;
  }

 private:
  template <class Row>
  void read_vertex(const Element& element, Row&& row) {
    for (std::size_t i = 0; i < element.properties.size(); ++i) {
      const Property& property = element.properties[i];
      const auto axis = std::find(layout_.coordinate_property.begin(), layout_.coordinate_property.end(), i);
      if (axis == layout_.coordinate_property.end()) {
        skip_property(property);
        continue;
      }
      const double value = source_.read_real(property.value_type);
      if (!std::isfinite(value)) source_.fail("coordinate " + property.name + " is not finite");
      row(axis - layout_.coordinate_property.begin()) = value;
    }
  }

  template <class Row>
  void read_face(const Element& element, Row&& row) {
    for (std::size_t i = 0; i < element.properties.size(); ++i) {
      const Property& property = element.properties[i];
      if (i != layout_.index_property) {
        skip_property(property);
        continue;
      }
      const std::int64_t count = read_list_count(property);
      if (count != 3) source_.fail("a face with " + std::to_string(count) + " vertices: only triangles are supported");
      for (Eigen::Index corner = 0; corner < 3; ++corner) row(corner) = read_vertex_id(property);
    }
  }

  int read_vertex_id(const Property& property) {
    const std::int64_t id = source_.read_integer(property.value_type);
    const auto vertex_count = static_cast<std::int64_t>(layout_.vertex->count);
    if (id < 0 || id >= vertex_count)
      source_.fail("vertex index " + std::to_string(id) + " is out of range (the mesh has " +
                   std::to_string(vertex_count) + " vertices)");
    return static_cast<int>(id);
  }

  void skip_entry(const Element& element) {
    for (const Property& property : element.properties) skip_property(property);
  }

  void skip_property(const Property& property) {
    const std::uint64_t count = property.is_list() ? static_cast<std::uint64_t>(read_list_count(property)) : 1;
    source_.skip(property.value_type, count);
  }

  std::int64_t read_list_count(const Property& property) {
    const std::int64_t count = source_.read_integer(*property.list_count_type);
    if (count < 0)
      source_.fail("negative list length " + std::to_string(count) + " in " + io_detail::printable(property.name));
    return count;
  }

  Source& source_;
  const Header& header_;
  const MeshLayout& layout_;
};

template <class Source>
PlyMesh read_body(Source&& source, const Header& header, const MeshLayout& layout) {
  return BodyReader<std::remove_reference_t<Source>>(source, header, layout).read();
}

bool needs_byte_swap(Encoding encoding) {
  const bool file_is_little = encoding == Encoding::binary_little_endian;
  return file_is_little != (std::endian::native == std::endian::little);
}

}  // namespace

PlyMesh read_ply(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::string bytes = io_detail::read_input_file(path);
  const Header header = HeaderParser(file, bytes).parse();
  const MeshLayout layout = mesh_layout(file, header);
  const std::string_view body = std::string_view(bytes).substr(header.body_offset);
  check_declared_size(file, header, body.size());
  if (header.encoding == Encoding::ascii)
    return read_body(AsciiSource(file, body, header.body_first_line), header, layout);
  return read_body(BinarySource(file, body, needs_byte_swap(header.encoding)), header, layout);
}

}  // namespace batchccd
