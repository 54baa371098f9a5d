// A reader of plain CDR (OMG XCDR1, the serialization ROS 2 writes into a
// bag): primitives at their natural alignment counted from the byte after the
// 4-byte encapsulation header (float64 aligned to 8), strings as a uint32
// length that includes the NUL, sequences as a uint32 count then the items.
// Written by hand: no Debian package decodes CDR without a ROS installation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace idbench::internal {

class CdrReader {
 public:
  // data: one serialized message, starting with its encapsulation header
  // (00 01 little endian, 00 00 big endian; both are read). The bytes must
  // outlive the reader. Throws std::invalid_argument for a message shorter
  // than the header or another encapsulation (XCDR2, parameter lists).
  CdrReader(const std::uint8_t* data, std::size_t size);

  // Each reads the next item of the message; `field` names it in messages.
  // Throws std::invalid_argument "field 'f': what" when the item overruns the
  // message, or a string lacks its NUL.
  std::int32_t ReadInt32(const char* field);
  std::uint32_t ReadUint32(const char* field);
  double ReadFloat64(const char* field);
  void ReadString(const char* field, std::string* out);
  void ReadStringSequence(const char* field, std::vector<std::string>* out);
  void ReadFloat64Sequence(const char* field, std::vector<double>* out);

  std::size_t offset() const { return pos_; }  // from the start of the message, header included
  bool big_endian() const { return big_endian_; }

 private:
  // Pads to a multiple of `alignment` counted from the end of the header,
  // then returns the next n bytes and steps over them.
  const std::uint8_t* Take(std::size_t alignment, std::size_t n, const char* field);
  std::uint32_t Uint32At(const std::uint8_t* p) const;
  double Float64At(const std::uint8_t* p) const;

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 4;
  bool big_endian_ = false;
};

}  // namespace idbench::internal
