// An 8-bit RGB raster, rows top to bottom: what the renderer produces and the
// PNG codec reads and writes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace idbench {

struct Image {
  int width = 0;   // [px]
  int height = 0;  // [px]
  std::vector<std::uint8_t> rgb;  // 3·width·height bytes, row-major, top row first

  Image() = default;
  Image(int w, int h, std::uint8_t fill = 0)
      : width(w), height(h), rgb(static_cast<std::size_t>(3) * static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill) {}

  std::uint8_t* at(int x, int y) { return rgb.data() + 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)); }
  const std::uint8_t* at(int x, int y) const {
    return rgb.data() + 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x));
  }

  // Copies `source` with its top-left corner at (x, y); it must fit.
  void Paste(const Image& source, int x, int y);
};

}  // namespace idbench
