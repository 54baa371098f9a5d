// Bytes of hand-made CDR messages for the tests, laid out by the test itself.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace idbench::testing {

// Appends the low `bytes` bytes of v in the given byte order.
inline void Put(std::vector<std::uint8_t>& out, std::uint64_t v, int bytes, bool big_endian = false) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * (big_endian ? bytes - 1 - i : i))));
}

inline void PutDouble(std::vector<std::uint8_t>& out, double d, bool big_endian = false) {
  std::uint64_t bits;
  std::memcpy(&bits, &d, 8);
  Put(out, bits, 8, big_endian);
}

}  // namespace idbench::testing
