#include "idbench/render/image.h"

#include <cassert>
#include <cstring>

namespace idbench {

void Image::Paste(const Image& source, int x, int y) {
  assert(x >= 0 && y >= 0 && x + source.width <= width && y + source.height <= height);
  for (int row = 0; row < source.height; ++row) {
    std::memcpy(at(x, y + row), source.at(0, row), 3 * static_cast<size_t>(source.width));
  }
}

}  // namespace idbench
