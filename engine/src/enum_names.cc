#include "idbench/engine/enum_names.h"

namespace idbench {

int FindEnumName(std::string_view field, std::span<const std::string_view> names, bool quoted, std::string_view text,
                 std::string* why) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == text) return static_cast<int>(i);
  }
  if (why) {
    const std::string quote = quoted ? "'" : "";
    std::string choices;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (i > 0) choices += i + 1 == names.size() ? " or " : ", ";
      choices += quote + std::string(names[i]) + quote;
    }
    *why = std::string(field) + ": expected " + choices + ", got '" + std::string(text) + "'";
  }
  return -1;
}

}  // namespace idbench
