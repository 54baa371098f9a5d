// The names an option of enum type is written with, one table per enum: the
// text a front end parses into the value (its flag, keyword argument or
// combo), the name a result file records, and the one message a bad name
// gets. Names are listed in the enum's order (value i is names[i]).
//
//   enum class TorqueEstimator { kOls, kWls, kPhysicallyConsistent };
//   inline constexpr EnumNames<TorqueEstimator, 3> kTorqueEstimatorNames{"estimator", {"ols", "wls", "pc"}};
//   kTorqueEstimatorNames.Parse("wls", &e, &why);   // why: "estimator: expected ols, wls or pc, got 'x'"
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace idbench {

// The index of `text` in `names`; -1 and *why = "field: expected a, b or c,
// got 'text'" otherwise (the choices in single quotes when `quoted`).
int FindEnumName(std::string_view field, std::span<const std::string_view> names, bool quoted, std::string_view text,
                 std::string* why);

template <typename Enum, std::size_t N>
struct EnumNames {
  std::string_view field;                 // the option's field, as messages name it
  std::array<std::string_view, N> names;  // in the enum's order
  bool quoted = false;                    // the message quotes the choices: 'q' or 'q,qd,qdd'

  std::string_view Name(Enum value) const { return names[static_cast<std::size_t>(value)]; }
  // The value named `text`; false with *why naming the field and the choices.
  bool Parse(std::string_view text, Enum* value, std::string* why = nullptr) const {
    const int i = FindEnumName(field, names, quoted, text, why);
    if (i < 0) return false;
    *value = static_cast<Enum>(i);
    return true;
  }
  std::vector<std::string> Names() const { return {names.begin(), names.end()}; }
};

}  // namespace idbench
