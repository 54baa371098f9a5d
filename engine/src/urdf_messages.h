// How the URDF reader and writer quote names and numbers from a file in
// their messages (internal to engine/src).
#pragma once

#include <cstddef>
#include <sstream>
#include <string>

#include "idbench/engine/printable_text.h"

namespace idbench::internal {

// A name or path from the file as a message shows it: escaped, and cut only
// beyond the length of a long path (a mesh's package:// URI must stay whole
// for the user to find it; 64 bytes cut the KUKA's).
constexpr std::size_t kMaxQuotedBytes = 1024;
inline std::string Quote(const std::string& name) { return "'" + PrintableText(name, kMaxQuotedBytes) + "'"; }

// A number as a message shows it (6 significant digits).
inline std::string Format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace idbench::internal
