#include "batchccd/names.hpp"

#include <algorithm>

#include "batchccd/lab.hpp"

namespace batchccd {
namespace {

constexpr EnumName<Kind> kKinds[] = {{"vf", Kind::vertex_face},
                                     {"ee", Kind::edge_edge},
                                     {"ve", Kind::vertex_edge},
                                     {"vv", Kind::vertex_vertex}};
constexpr EnumName<Mode> kModes[] = {{"conservative", Mode::conservative}, {"exact", Mode::exact}};
constexpr EnumName<lab::Baseline> kBaselines[] = {
    {"none", lab::Baseline::none}, {"fast", lab::Baseline::fast}, {"cubic", lab::Baseline::cubic}};
constexpr EnumName<Isa> kIsas[] = {{"auto", Isa::automatic}, {"scalar", Isa::scalar},
                                   {"sse4", Isa::sse4},      {"avx2", Isa::avx2},
                                   {"avx512", Isa::avx512},  {"neon", Isa::neon}};

// The table's names are literals: .data() is null-terminated.
template <class Enum>
const char* name_in(std::span<const EnumName<Enum>> table, Enum value) {
  for (const EnumName<Enum>& entry : table)
    if (entry.value == value) return entry.name.data();
  return "?";
}

template <class Enum>
std::optional<Enum> value_in(std::span<const EnumName<Enum>> table, std::string_view name) {
  for (const EnumName<Enum>& entry : table)
    if (entry.name == name) return entry.value;
  return std::nullopt;
}

}  // namespace

std::span<const EnumName<Kind>> kind_names() { return kKinds; }
std::span<const EnumName<Mode>> mode_names() { return kModes; }
std::span<const EnumName<Isa>> isa_names() { return kIsas; }

const char* to_string(Kind kind) { return name_in(kind_names(), kind); }
const char* to_string(Mode mode) { return name_in(mode_names(), mode); }
const char* to_string(Isa isa) { return name_in(isa_names(), isa); }
const char* lab::to_string(Baseline baseline) { return name_in<Baseline>(kBaselines, baseline); }
const char* lab::to_string(const Method& method) {
  return method.baseline == Baseline::none ? batchccd::to_string(method.mode) : to_string(method.baseline);
}

std::optional<Kind> kind_from_string(std::string_view name) { return value_in(kind_names(), name); }
std::optional<Mode> mode_from_string(std::string_view name) { return value_in(mode_names(), name); }
std::optional<Isa> isa_from_string(std::string_view name) { return value_in(isa_names(), name); }

}  // namespace batchccd
