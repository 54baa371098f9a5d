// Echoing text from an input file in a message: bytes that are not printable
// ASCII or UTF-8 are escaped, and long text is cut, so a binary file or a
// 1 GB line cannot flood a terminal or hide what is wrong (a UTF-8 BOM shows
// as \xef\xbb\xbf).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace idbench {

// `text` with control and invalid bytes as \xNN (\t, \r, \n as such) and at
// most `max_bytes` of it kept, then "… (N bytes)" giving the full length.
std::string PrintableText(std::string_view text, std::size_t max_bytes = 64);

// The offset of the first byte of `text` that does not start a valid UTF-8
// sequence (a stray continuation byte, a cut or overlong sequence, a
// surrogate); npos when all of it is UTF-8.
std::size_t FindInvalidUtf8(std::string_view text);

}  // namespace idbench
