#include "idbench/render/png_codec.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace idbench {
namespace {

TEST(PngCodecTest, RoundTripIsExact) {
  Image image(7, 5);
  for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = static_cast<std::uint8_t>((i * 37) % 251);
  const std::string png = EncodePng(image);
  ASSERT_EQ(png.substr(1, 3), "PNG");
  const Image back = DecodePng(png);
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  EXPECT_EQ(back.rgb, image.rgb);
  // Deterministic: no time stamps.
  EXPECT_EQ(EncodePng(image), png);
}

TEST(PngCodecTest, RejectsOtherBytes) {
  EXPECT_THROW(DecodePng("GIF89a not a png"), std::runtime_error);
}

TEST(ImageTest, PastePlacesRowsAtOffset) {
  Image big(4, 3, 0), small(2, 2, 9);
  big.Paste(small, 1, 1);
  EXPECT_EQ(big.at(0, 1)[0], 0);
  EXPECT_EQ(big.at(1, 1)[0], 9);
  EXPECT_EQ(big.at(2, 2)[2], 9);
  EXPECT_EQ(big.at(3, 2)[0], 0);
  EXPECT_EQ(big.at(1, 0)[0], 0);
}

}  // namespace
}  // namespace idbench
