#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>

#include "batchccd/options.hpp"
#include "batchccd/query.hpp"

// The command line's vocabulary: one table per enum, used both to parse an
// option's value and to print it back, so the two can never disagree.
namespace batchccd::cli {

template <class Enum, std::size_t Count>
using NameTable = std::array<std::pair<std::string_view, Enum>, Count>;

inline constexpr NameTable<Kind, 2> kind_names{{
    {"vf", Kind::vertex_face},
    {"ee", Kind::edge_edge},
}};

inline constexpr NameTable<Mode, 4> mode_names{{
    {"conservative", Mode::conservative},
    {"fast", Mode::fast},
    {"cubic", Mode::cubic},
    {"exact", Mode::exact},
}};

inline constexpr NameTable<Isa, 5> isa_names{{
    {"auto", Isa::automatic},
    {"scalar", Isa::scalar},
    {"sse4", Isa::sse4},
    {"avx2", Isa::avx2},
    {"avx512", Isa::avx512},
}};

template <class Enum, std::size_t Count>
std::optional<Enum> from_name(const NameTable<Enum, Count>& table, std::string_view name) {
  for (const auto& [entry_name, value] : table) {
    if (entry_name == name) return value;
  }
  return std::nullopt;
}

template <class Enum, std::size_t Count>
std::string_view name_of(const NameTable<Enum, Count>& table, Enum value) {
  for (const auto& [entry_name, entry_value] : table) {
    if (entry_value == value) return entry_name;
  }
  return "?";
}

inline std::string_view name_of(Kind kind) { return name_of(kind_names, kind); }
inline std::string_view name_of(Mode mode) { return name_of(mode_names, mode); }
inline std::string_view name_of(Isa isa) { return name_of(isa_names, isa); }

}  // namespace batchccd::cli
