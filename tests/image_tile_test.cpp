// Image tiles: header identification (tileformat §8) on encoded tiles and
// damaged bytes, the encoder's format choices, and the pyramid step.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "geo/image_codec.hpp"
#include "imagery/image_pyramid.hpp"
#include "tileformat/error.hpp"
#include "tileformat/image_tile.hpp"

namespace {

using globe::TilePixels;
using tileformat::ImageFormat;

TilePixels gradient(int size, int colour, uint8_t alpha) {
  TilePixels px(size, colour);
  for (int c = 0; c < colour; ++c)
    for (size_t i = 0; i < px.plane_size(); ++i)
      px.plane(c)[i] = static_cast<uint8_t>((i * (c + 1)) % 256);
  std::fill_n(px.plane(colour), px.plane_size(), alpha);
  return px;
}

TEST(ImageTile, EncodesAndIdentifiesEveryFormat) {
  for (ImageFormat f : {ImageFormat::kPng, ImageFormat::kJpeg, ImageFormat::kWebp})
    for (int colour : {1, 3}) {
      const auto blob = globe::encode_image_tile(gradient(256, colour, 255), {f, 90});
      const auto h = tileformat::inspect_image_tile(blob);
      EXPECT_EQ(h.format, f);
      EXPECT_EQ(h.width, 256);
      EXPECT_EQ(h.height, 256);
      // Opaque tiles carry no alpha; WebP has no gray.
      EXPECT_EQ(h.channels, f == ImageFormat::kWebp ? 3 : colour) << int(f);
      const TilePixels back = globe::decode_image_tile(blob, 256, colour);
      EXPECT_TRUE(back.opaque());
      if (f == ImageFormat::kPng) {
        EXPECT_EQ(back.planes, gradient(256, colour, 255).planes);
      }
    }
}

// The first JPEG and WebP encodes of a process, from many threads at once:
// GDAL 3.6 built the JPEG driver's option list on first use in every thread
// that got there together (a use after free under ASan, OSGeo/gdal#12389).
// Each test runs in its own process, so these are the first encodes.
TEST(ImageTile, FirstEncodesOnManyThreadsAtOnceAreSafe) {
  for (ImageFormat f : {ImageFormat::kJpeg, ImageFormat::kWebp}) {
    std::vector<std::vector<uint8_t>> blobs(8);
    std::atomic<int> ready{0};
    std::vector<std::thread> threads;
    for (size_t t = 0; t < blobs.size(); ++t)
      threads.emplace_back([&, t] {
        const globe::TilePixels px = gradient(64, 3, 255);
        ++ready;
        while (ready < int(blobs.size())) {
        }
        blobs[t] = globe::encode_image_tile(px, {f, 90});
      });
    for (std::thread& t : threads)
      t.join();
    for (const auto& blob : blobs)
      EXPECT_EQ(blob, blobs[0]);
  }
}

TEST(ImageTile, TransparentJpegTilesBecomePng) {
  TilePixels px = gradient(256, 3, 255);
  px.plane(3)[0] = 0;
  const auto blob = globe::encode_image_tile(px, {ImageFormat::kJpeg, 90});
  EXPECT_EQ(tileformat::inspect_image_tile(blob).format, ImageFormat::kPng);
  EXPECT_EQ(globe::decode_image_tile(blob, 256, 3).planes, px.planes);
}

// PNG tiles are lossless at every effort, with and without alpha (GDAL
// decodes what libpng wrote).
TEST(ImageTile, PngRoundTripsAtEveryEffort) {
  for (int effort : {1, 2, 6, 9})
    for (int colour : {1, 3})
      for (uint8_t alpha : {uint8_t{255}, uint8_t{128}}) {
        TilePixels px = gradient(256, colour, alpha);
        px.plane(colour)[7] = 0;  // one transparent pixel: an alpha channel is written
        if (alpha == 255) std::fill_n(px.plane(colour), px.plane_size(), uint8_t{255});
        const auto blob = globe::encode_image_tile(px, {ImageFormat::kPng, 85, effort});
        EXPECT_EQ(tileformat::inspect_image_tile(blob).channels, colour + (alpha == 255 ? 0 : 1));
        EXPECT_EQ(globe::decode_image_tile(blob, 256, colour).planes, px.planes)
            << "effort " << effort << ", colour " << colour << ", alpha " << int(alpha);
      }
}

TEST(ImageTile, RejectsDamagedHeadersWithTheSection) {
  const auto blob = globe::encode_image_tile(gradient(256, 3, 255), {ImageFormat::kPng, 90});
  for (size_t n : {size_t(0), size_t(3), size_t(8), size_t(20), size_t(32)}) {
    const std::vector<uint8_t> cut(blob.begin(), blob.begin() + std::min(n, blob.size()));
    try {
      tileformat::inspect_image_tile(cut);
      ADD_FAILURE() << "accepted " << n << " bytes";
    } catch (const tileformat::FormatError& e) {
      EXPECT_EQ(e.section(), "8");
    }
  }
  EXPECT_THROW(tileformat::inspect_image_tile(std::vector<uint8_t>(100, 0xAB)),
               tileformat::FormatError);
  // A JPEG whose segments run past the end, and one without a frame header.
  EXPECT_THROW(
      tileformat::inspect_image_tile(std::vector<uint8_t>{0xFF, 0xD8, 0xFF, 0xE0, 0xFF, 0xFF}),
      tileformat::FormatError);
  EXPECT_THROW(tileformat::inspect_image_tile(std::vector<uint8_t>{0xFF, 0xD8, 0xFF, 0xDA, 0, 2}),
               tileformat::FormatError);
  // Decoding checks the size against the package's tile size.
  EXPECT_THROW(globe::decode_image_tile(blob, 512, 3), tileformat::FormatError);
  // Colour tiles in a gray package.
  EXPECT_THROW(globe::decode_image_tile(blob, 256, 1), tileformat::FormatError);
}

TEST(ImagePyramid, AveragesWeightedByAlpha) {
  // Child 0: a 2x2 block with one opaque white pixel and three transparent
  // black ones: the parent pixel is white (colour is alpha-weighted) with a
  // quarter of the alpha. Missing children stay transparent.
  TilePixels kid(4, 1);
  kid.plane(0)[0] = 255;
  kid.plane(1)[0] = 255;
  const TilePixels parent = globe::downsample_children({&kid, nullptr, nullptr, nullptr}, 4, 1);
  EXPECT_EQ(parent.plane(0)[0], 255);
  EXPECT_EQ(parent.plane(1)[0], 64);
  EXPECT_EQ(parent.plane(1)[2], 0);   // the north-east quarter: no child
  EXPECT_EQ(parent.plane(1)[10], 0);  // south-east
  // Opaque children average plainly, with rounding.
  TilePixels a(4, 3);
  std::fill(a.planes.begin(), a.planes.end(), 255);
  for (int c = 0; c < 3; ++c) {
    a.plane(c)[0] = 10;
    a.plane(c)[1] = 11;
    a.plane(c)[4] = 12;
    a.plane(c)[5] = 12;
  }
  const TilePixels p = globe::downsample_children({&a, &a, &a, &a}, 4, 3);
  EXPECT_EQ(p.plane(0)[0], 11);  // (10 + 11 + 12 + 12) / 4 = 11.25
  EXPECT_EQ(p.plane(3)[0], 255);
  EXPECT_TRUE(p.opaque());
}

}  // namespace
