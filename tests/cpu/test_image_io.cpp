// Image files through both codecs: each reads back what it wrote, and what the other wrote
// (tinyexr's EXR read by OpenImageIO and the reverse), so neither can drift from the formats.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "sslr_host/image_io.hpp"

namespace fs = std::filesystem;
using namespace sslr::host;

namespace {
Image testImage(int w, int h, int channels) {
  Image img{w, h, channels, std::vector<float>(static_cast<size_t>(w) * h * channels)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c)  // distinct per row, column and channel; not symmetric
        img.at(x, y, c) = 0.01f * static_cast<float>(x + 7 * y) + 0.3f * static_cast<float>(c) - 0.5f;
  if (w > 1 && h > 2) img.at(1, 2, 0) = 1e6f;  // EXR keeps any float
  return img;
}

fs::path tmpDir() {
  fs::path dir = fs::path(SSLR_TEST_TMP) / "image_io";
  fs::create_directories(dir);
  return dir;
}

std::vector<ImageCodec> codecs() {
  std::vector<ImageCodec> all;
  for (ImageCodec c : {ImageCodec::OpenImageIO, ImageCodec::TinyExrStb})
    if (hasImageCodec(c)) all.push_back(c);
  return all;
}

// `image` encoded by `writer` into the file `path`, read back by `reader`.
sslr::Expected<Image> roundTrip(const fs::path& path, const Image& image, const std::vector<std::string>& channelNames,
                          ImageCodec writer, ImageCodec reader) {
  auto bytes = encodeImage(path.string(), image, channelNames, writer);
  if (!bytes) return sslr::Status::error(bytes.error());
  if (sslr::Status st = writeFiles({{path.string(), bytes.value()}}); !st) return sslr::Status::error(st.message());
  return readImage(path.string(), reader);
}

float srgb8(float linear) {  // what a PNG holds for `linear`, read back as stored / 255
  const float v = std::clamp(linear, 0.0f, 1.0f);
  const float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return std::round(s * 255.0f) / 255.0f;
}
}  // namespace

TEST(ImageIo, TheSmallCodecIsAlwaysBuilt) {
  EXPECT_TRUE(hasImageCodec(ImageCodec::TinyExrStb));
  EXPECT_TRUE(hasImageCodec(defaultImageCodec()));
}

TEST(ImageIo, ExrRoundTripsExactlyAcrossCodecs) {
  for (int channels : {1, 3, 4})
    for (ImageCodec writer : codecs())
      for (ImageCodec reader : codecs()) {
        SCOPED_TRACE(std::string(imageCodecName(writer)) + " -> " + imageCodecName(reader) + ", " +
                     std::to_string(channels) + " channels");
        const Image img = testImage(13, 6, channels);
        auto back = roundTrip(tmpDir() / ("x" + std::to_string(channels) + ".exr"), img, {}, writer, reader);
        ASSERT_TRUE(back) << back.error();
        ASSERT_EQ(back.value().width, 13);
        ASSERT_EQ(back.value().height, 6);
        ASSERT_EQ(back.value().channels, channels);
        EXPECT_EQ(back.value().pixels, img.pixels);  // 32-bit float, lossless: bit for bit, rows in order
      }
}

TEST(ImageIo, ExrChannelsComeBackInRgbaOrder) {
  // Files store channels sorted by name (A, B, G, R); the reader puts R, G, B, A first again.
  for (ImageCodec writer : codecs())
    for (ImageCodec reader : codecs()) {
      Image img = testImage(4, 3, 4);
      auto back = roundTrip(tmpDir() / "rgba.exr", img, {"R", "G", "B", "A"}, writer, reader);
      ASSERT_TRUE(back) << back.error();
      for (int c = 0; c < 4; ++c) EXPECT_EQ(back.value().at(3, 2, c), img.at(3, 2, c)) << imageCodecName(writer) << c;
    }
}

TEST(ImageIo, PngHoldsSrgbBytesAcrossCodecs) {
  for (ImageCodec writer : codecs())
    for (ImageCodec reader : codecs()) {
      SCOPED_TRACE(std::string(imageCodecName(writer)) + " -> " + imageCodecName(reader));
      Image img = testImage(9, 5, 4);
      img.at(0, 0, 0) = NAN;  // NaN colour -> 0, alpha clamped and linear
      auto back = roundTrip(tmpDir() / "x.png", img, {}, writer, reader);
      ASSERT_TRUE(back) << back.error();
      ASSERT_EQ(back.value().channels, 4);
      for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 9; ++x)
          for (int c = 0; c < 4; ++c) {
            const float v = img.at(x, y, c);
            const float want = c == 3 ? std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f
                                      : (std::isnan(v) ? 0.0f : srgb8(v));
            EXPECT_NEAR(back.value().at(x, y, c), want, 1e-6f) << x << "," << y << "," << c;
          }
    }
}

TEST(ImageIo, BadFilesAndImagesSayWhatIsWrong) {
  for (ImageCodec codec : codecs()) {
    SCOPED_TRACE(imageCodecName(codec));
    const fs::path missing = tmpDir() / "missing.exr";
    auto r = readImage(missing.string(), codec);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find("missing.exr"), std::string::npos) << r.error();
    const fs::path junk = tmpDir() / "junk.png";
    std::ofstream(junk) << "not an image";
    r = readImage(junk.string(), codec);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find("junk.png"), std::string::npos) << r.error();
    const fs::path truncated = tmpDir() / "truncated.exr";
    auto full = encodeImage(truncated.string(), testImage(8, 8, 3), {}, codec).value();
    full.resize(full.size() / 2);
    ASSERT_TRUE(writeFiles({{truncated.string(), full}}));
    r = readImage(truncated.string(), codec);
    EXPECT_FALSE(r);
    EXPECT_FALSE(encodeImage("x.tif", testImage(2, 2, 3), {}, codec));
    EXPECT_FALSE(encodeImage("x.exr", Image{}, {}, codec));
  }
}
