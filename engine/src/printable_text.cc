#include "idbench/engine/printable_text.h"

#include <cstdio>

namespace idbench {
namespace {

// Length of the valid UTF-8 sequence starting at text[i] (0 if none), its
// code point in *code.
std::size_t Utf8Length(std::string_view text, std::size_t i, char32_t* code) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  if (lead < 0x80) length = 1, *code = lead;
  else if (lead >= 0xc2 && lead <= 0xdf) length = 2, *code = lead & 0x1f;
  else if (lead >= 0xe0 && lead <= 0xef) length = 3, *code = lead & 0x0f;
  else if (lead >= 0xf0 && lead <= 0xf4) length = 4, *code = lead & 0x07;
  else return 0;
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
    *code = (*code << 6) | (byte(i + k) & 0x3f);
  }
  const bool overlong = (length == 3 && *code < 0x800) || (length == 4 && *code < 0x10000);
  const bool invalid = overlong || *code > 0x10ffff || (*code >= 0xd800 && *code <= 0xdfff);
  return invalid ? 0 : length;
}

// Length of the valid UTF-8 sequence of two or more bytes starting at
// text[i] that is shown as it is (not a C1 control, not the invisible U+FEFF
// byte order mark); 0 if none.
std::size_t ShownUtf8Length(std::string_view text, std::size_t i) {
  char32_t code = 0;
  const std::size_t length = Utf8Length(text, i, &code);
  return length < 2 || code <= 0x9f || code == 0xfeff ? 0 : length;
}

}  // namespace

std::string PrintableText(std::string_view text, std::size_t max_bytes) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size() && i < max_bytes) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
      ++i;
    } else if (c == '\t' || c == '\n' || c == '\r') {
      out += c == '\t' ? "\\t" : c == '\n' ? "\\n" : "\\r";
      ++i;
    } else if (const std::size_t length = ShownUtf8Length(text, i); length > 0) {
      out.append(text.substr(i, length));
      i += length;
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02x", c);
      out += escaped;
      ++i;
    }
  }
  if (i < text.size()) out += "… (" + std::to_string(text.size()) + " bytes)";
  return out;
}

std::size_t FindInvalidUtf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    char32_t code = 0;
    const std::size_t length = Utf8Length(text, i, &code);
    if (length == 0) return i;
    i += length;
  }
  return std::string_view::npos;
}

}  // namespace idbench
