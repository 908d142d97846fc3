// NameOf: the name of an enum value, looked up in a table of {value, name} pairs written once
// beside the function that names the enum (for logs, reports and stats.json), instead of a
// switch with one case and one return per value.
#pragma once

#include <cstddef>

namespace drvslam {

template <typename Enum>
struct EnumName {
  Enum value;
  const char* name;
};

// `unknown` when the table has no entry for `value` (a value the table forgot, or one cast from
// a bad integer).
template <typename Enum, std::size_t N>
constexpr const char* NameOf(Enum value, const EnumName<Enum> (&names)[N], const char* unknown) {
  for (const EnumName<Enum>& entry : names) {
    if (entry.value == value) return entry.name;
  }
  return unknown;
}

}  // namespace drvslam
