// Reading rendered images in tests: which pixels show the robot, where.
#pragma once

#include <algorithm>
#include <cstdlib>

#include "idbench/render/image.h"

namespace idbench::testing {

// The stage (background, floor, shadow), hinges and labels are neutral greys;
// links are saturated colours. A pixel shows a link iff max − min channel > 40.
inline bool IsRobotPixel(const std::uint8_t* p) {
  return std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) > 40;
}

struct PixelBox {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;  // inclusive; empty when x1 < x0
  long long count = 0;
  bool empty() const { return count == 0; }
};

// Robot pixels inside the rectangle [x, x + w) × [y, y + h).
inline PixelBox RobotBox(const Image& image, int x, int y, int w, int h) {
  PixelBox box;
  for (int v = y; v < y + h; ++v) {
    for (int u = x; u < x + w; ++u) {
      if (!IsRobotPixel(image.at(u, v))) continue;
      box.x0 = std::min(box.x0, u), box.x1 = std::max(box.x1, u);
      box.y0 = std::min(box.y0, v), box.y1 = std::max(box.y1, v);
      ++box.count;
    }
  }
  return box;
}

// Pixels that are robot in one rectangle and not in the other (same size).
inline long long RobotMaskDifference(const Image& image, int xa, int ya, int xb, int yb, int w, int h) {
  long long n = 0;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) n += IsRobotPixel(image.at(xa + u, ya + v)) != IsRobotPixel(image.at(xb + u, yb + v));
  return n;
}

// How far below the robot's pixel centroid the first link of a six-link
// robot (the only blue one, LinkColor(0) = (0.20, 0.42, 0.74)) sits [px]:
// > 0 below, < 0 above; 0 when fewer than 50 of its pixels show.
inline double FirstLinkBelowCentroid(const Image& image) {
  double robot_v = 0, robot_n = 0, base_v = 0, base_n = 0;
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const std::uint8_t* p = image.at(u, v);
      if (!IsRobotPixel(p)) continue;
      robot_v += v, ++robot_n;
      if (p[2] > 1.4 * p[1] && p[2] > 2.0 * p[0]) base_v += v, ++base_n;
    }
  }
  return base_n >= 50 ? base_v / base_n - robot_v / robot_n : 0.0;
}

}  // namespace idbench::testing
