// PNG encoding and decoding with libpng, in memory (so that callers write the
// bytes atomically). Encoding is deterministic: no time or text chunks.
#pragma once

#include <string>
#include <string_view>

#include "idbench/render/image.h"

namespace idbench {

// 8-bit RGB PNG of `image`.
std::string EncodePng(const Image& image);

// Reads an 8-bit RGB or RGBA PNG (alpha dropped). Throws std::runtime_error
// when the bytes are not such a PNG.
Image DecodePng(std::string_view bytes);

}  // namespace idbench
