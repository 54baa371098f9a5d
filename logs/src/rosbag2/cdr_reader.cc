#include "cdr_reader.h"

#include <bit>
#include <cstring>
#include <stdexcept>

namespace idbench::internal {
namespace {

constexpr std::size_t kHeaderBytes = 4;  // encapsulation kind (2 bytes) and options (2 bytes)

[[noreturn]] void Fail(const char* field, const std::string& what) {
  throw std::invalid_argument(std::string("field '") + field + "': " + what);
}

}  // namespace

CdrReader::CdrReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {
  if (size < kHeaderBytes) {
    throw std::invalid_argument("CDR message of " + std::to_string(size) + " bytes, shorter than its 4-byte header");
  }
  // Encapsulation kinds: 0x0000 CDR_BE, 0x0001 CDR_LE; the rest (PL_CDR,
  // XCDR2) are not what ROS 2's default middleware writes.
  if (data[0] != 0 || data[1] > 1) {
    throw std::invalid_argument("CDR encapsulation " + std::to_string(data[0]) + " " + std::to_string(data[1]) +
                                ", expected 00 01 (little endian) or 00 00 (big endian)");
  }
  big_endian_ = data[1] == 0;
}

const std::uint8_t* CdrReader::Take(std::size_t alignment, std::size_t n, const char* field) {
  const std::size_t body = pos_ - kHeaderBytes;
  const std::size_t padded = pos_ + (alignment - body % alignment) % alignment;
  if (padded > size_ || n > size_ - padded) {
    Fail(field, "needs " + std::to_string(n) + " bytes at offset " + std::to_string(padded) + ", the message has " +
                    std::to_string(size_));
  }
  pos_ = padded + n;
  return data_ + padded;
}

std::uint32_t CdrReader::Uint32At(const std::uint8_t* p) const {
  return big_endian_ ? (std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3])
                     : (std::uint32_t{p[3]} << 24 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[1]} << 8 | p[0]);
}

double CdrReader::Float64At(const std::uint8_t* p) const {
  std::uint64_t bits = 0;
  if (std::endian::native == std::endian::little && !big_endian_) {
    std::memcpy(&bits, p, sizeof bits);  // the common case: one load
  } else {
    for (int i = 0; i < 8; ++i) bits |= std::uint64_t{p[big_endian_ ? 7 - i : i]} << (8 * i);
  }
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::int32_t CdrReader::ReadInt32(const char* field) {
  return static_cast<std::int32_t>(Uint32At(Take(4, 4, field)));
}

std::uint32_t CdrReader::ReadUint32(const char* field) { return Uint32At(Take(4, 4, field)); }

double CdrReader::ReadFloat64(const char* field) { return Float64At(Take(8, 8, field)); }

void CdrReader::ReadString(const char* field, std::string* out) {
  const std::uint32_t length = ReadUint32(field);  // bytes including the NUL
  if (length == 0) {  // some writers encode "" as length 0
    out->clear();
    return;
  }
  const std::uint8_t* p = Take(1, length, field);
  if (p[length - 1] != 0) Fail(field, "string of " + std::to_string(length) + " bytes does not end with NUL");
  out->assign(reinterpret_cast<const char*>(p), length - 1);
}

void CdrReader::ReadStringSequence(const char* field, std::vector<std::string>* out) {
  const std::uint32_t count = ReadUint32(field);
  // Each string takes at least its 4-byte length: a count beyond that is
  // corrupt, and is refused before anything is allocated for it.
  if (count > (size_ - pos_) / 4) {
    Fail(field, "sequence of " + std::to_string(count) + " strings overruns the message of " +
                    std::to_string(size_) + " bytes");
  }
  out->resize(count);
  for (std::uint32_t i = 0; i < count; ++i) ReadString(field, &(*out)[i]);
}

void CdrReader::ReadFloat64Sequence(const char* field, std::vector<double>* out) {
  const std::uint32_t count = ReadUint32(field);
  if (count == 0) {
    out->clear();
    return;
  }
  if (count > size_ / 8) {
    Fail(field, "sequence of " + std::to_string(count) + " float64 overruns the message of " +
                    std::to_string(size_) + " bytes");
  }
  const std::uint8_t* p = Take(8, std::size_t{count} * 8, field);
  out->resize(count);
  for (std::uint32_t i = 0; i < count; ++i) (*out)[i] = Float64At(p + 8 * i);
}

}  // namespace idbench::internal
