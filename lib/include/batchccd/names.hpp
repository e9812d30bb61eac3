#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "batchccd/options.hpp"
#include "batchccd/query.hpp"

// The enums' names, one table each: what to_string prints (query.hpp,
// options.hpp) and what these read back, as a command line spells them.
namespace batchccd {

template <class Enum>
struct EnumName {
  std::string_view name;
  Enum value;
};

// Every value of the enum with its name, in declaration order.
std::span<const EnumName<Kind>> kind_names();  // vf, ee, ve, vv
std::span<const EnumName<Mode>> mode_names();  // conservative, exact
std::span<const EnumName<Isa>> isa_names();    // auto, scalar, sse4, avx2, avx512, neon

// The value a name stands for; std::nullopt for any other text (case matters).
std::optional<Kind> kind_from_string(std::string_view name);
std::optional<Mode> mode_from_string(std::string_view name);
std::optional<Isa> isa_from_string(std::string_view name);

}  // namespace batchccd
