// How the URDF reader and writer quote names and numbers from a file in
// their messages (internal to engine/src).
#pragma once

#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

#include "idbench/engine/printable_text.h"

namespace idbench::internal {

// A name or path from the file as a message shows it: escaped, and cut only
// beyond the length of a long path (a mesh's package:// URI must stay whole
// for the user to find it; 64 bytes cut the KUKA's).
constexpr std::size_t kMaxQuotedBytes = 1024;
inline std::string Quote(const std::string& name) { return "'" + PrintableText(name, kMaxQuotedBytes) + "'"; }

// Names as a message lists them: 'a', 'b', 'c' (the first 64, then "and N more").
inline std::string QuotedList(const std::vector<std::string>& names) {
  constexpr std::size_t kMaxListed = 64;
  std::string list;
  for (std::size_t k = 0; k < names.size() && k < kMaxListed; ++k) list += (list.empty() ? "" : ", ") + Quote(names[k]);
  if (names.size() > kMaxListed) list += " and " + std::to_string(names.size() - kMaxListed) + " more";
  return list;
}

// A number as a message shows it (6 significant digits).
inline std::string Format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace idbench::internal
