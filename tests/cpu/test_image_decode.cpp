// The glTF loader's image decoding (image_decode.hpp: libpng, libjpeg-turbo): exact RGBA8 from
// PNGs of every layout the test can write, JPEG within its quantization, and every malformed
// input refused with a message rather than read past its end. The images are written here with
// the same libraries' encoders.
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <cstdio>
#include <cstring>
#include <vector>

#include <jpeglib.h>

#include "sslr_host/image_decode.hpp"

using sslr::host::decodePngOrJpeg;
using sslr::host::DecodedImage;

namespace {

std::vector<unsigned char> writePng(png_uint_32 width, png_uint_32 height, png_uint_32 format, const void* pixels,
                                    const void* colormap = nullptr, png_uint_32 colormapEntries = 0) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = width;
  image.height = height;
  image.format = format;
  image.colormap_entries = colormapEntries;
  png_alloc_size_t size = 0;
  EXPECT_NE(png_image_write_get_memory_size(image, size, 0, pixels, 0, colormap), 0) << image.message;
  std::vector<unsigned char> bytes(size);
  EXPECT_NE(png_image_write_to_memory(&image, bytes.data(), &size, 0, pixels, 0, colormap), 0) << image.message;
  bytes.resize(size);
  return bytes;
}

std::vector<unsigned char> writeJpeg(int width, int height, const unsigned char rgb[3]) {
  jpeg_compress_struct info;
  jpeg_error_mgr errors;
  info.err = jpeg_std_error(&errors);
  jpeg_create_compress(&info);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&info, &buffer, &size);
  info.image_width = static_cast<JDIMENSION>(width);
  info.image_height = static_cast<JDIMENSION>(height);
  info.input_components = 3;
  info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, 95, TRUE);
  jpeg_start_compress(&info, TRUE);
  std::vector<unsigned char> row(static_cast<size_t>(width) * 3);
  for (int x = 0; x < width; ++x) std::memcpy(&row[static_cast<size_t>(x) * 3], rgb, 3);
  while (info.next_scanline < info.image_height) {
    JSAMPROW r = row.data();
    jpeg_write_scanlines(&info, &r, 1);
  }
  jpeg_finish_compress(&info);
  std::vector<unsigned char> bytes(buffer, buffer + size);
  jpeg_destroy_compress(&info);
  std::free(buffer);
  return bytes;
}

std::string decode(const std::vector<unsigned char>& bytes, DecodedImage& out, int maxSide = 16384) {
  return decodePngOrJpeg(bytes.data(), bytes.size(), maxSide, out);
}

TEST(ImageDecode, RgbaPngComesBackExactly) {
  std::vector<unsigned char> pixels(5 * 3 * 4);
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<unsigned char>(i * 37 + 11);
  DecodedImage out;
  ASSERT_EQ(decode(writePng(5, 3, PNG_FORMAT_RGBA, pixels.data()), out), "");
  EXPECT_EQ(out.width, 5);
  EXPECT_EQ(out.height, 3);
  EXPECT_EQ(out.rgba8, pixels);
}

TEST(ImageDecode, PalettedAndGreyPngsBecomeOpaqueRgba) {
  // A palette of three colours and 8-bit grey.
  const unsigned char palette[3 * 3] = {255, 0, 0, 0, 128, 255, 7, 200, 9};
  const unsigned char indices[4 * 2] = {0, 1, 2, 1, 2, 0, 0, 2};
  DecodedImage out;
  ASSERT_EQ(decode(writePng(4, 2, PNG_FORMAT_RGB_COLORMAP, indices, palette, 3), out), "");
  ASSERT_EQ(out.rgba8.size(), 4u * 2 * 4);
  for (int p = 0; p < 8; ++p) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(out.rgba8[p * 4 + c], palette[indices[p] * 3 + c]) << "pixel " << p;
    EXPECT_EQ(out.rgba8[p * 4 + 3], 255);
  }
  const unsigned char grey[3] = {0, 99, 255};
  ASSERT_EQ(decode(writePng(3, 1, PNG_FORMAT_GRAY, grey), out), "");
  for (int p = 0; p < 3; ++p)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(out.rgba8[p * 4 + c], grey[p]);
}

TEST(ImageDecode, JpegDecodesWithinItsQuantization) {
  const unsigned char colour[3] = {200, 40, 90};
  DecodedImage out;
  ASSERT_EQ(decode(writeJpeg(16, 8, colour), out), "");
  EXPECT_EQ(out.width, 16);
  EXPECT_EQ(out.height, 8);
  ASSERT_EQ(out.rgba8.size(), 16u * 8 * 4);
  // A flat colour survives quality-95 JPEG within a few levels (chroma rounding, YCbCr <-> RGB).
  for (size_t p = 0; p < 16 * 8; ++p) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out.rgba8[p * 4 + c], colour[c], 4) << "pixel " << p;
    EXPECT_EQ(out.rgba8[p * 4 + 3], 255);
  }
}

TEST(ImageDecode, MalformedAndOtherFormatsAreRefusedWithAMessage) {
  const unsigned char red[4] = {255, 0, 0, 255};
  std::vector<unsigned char> png = writePng(1, 1, PNG_FORMAT_RGBA, red);
  const unsigned char colour[3] = {1, 2, 3};
  std::vector<unsigned char> jpeg = writeJpeg(8, 8, colour);
  DecodedImage out;
  // Cut short: PNG and JPEG, before their image data ends.
  for (size_t keep : {size_t(9), size_t(20), size_t(40)}) {  // in the signature, IHDR, IDAT
    std::vector<unsigned char> cut(png.begin(), png.begin() + static_cast<long>(keep));
    EXPECT_NE(decode(cut, out).find("PNG"), std::string::npos) << keep << " bytes";
    EXPECT_TRUE(out.rgba8.empty());
  }
  {
    std::vector<unsigned char> cut(jpeg.begin(), jpeg.begin() + 40);
    EXPECT_NE(decode(cut, out).find("JPEG"), std::string::npos);
    EXPECT_TRUE(out.rgba8.empty());
  }
  // A flipped byte in a chunk: libpng checks every CRC.
  std::vector<unsigned char> flipped = png;
  flipped[20] ^= 0x40;
  EXPECT_NE(decode(flipped, out).find("PNG"), std::string::npos);
  // Formats glTF does not allow (stb_image would have tried its GIF, BMP, PSD... decoders).
  for (const char* other : {"GIF89a\x01\0\x01\0", "BM\x3a\0\0\0\0\0\0\0", "8BPS\0\x01\0\0\0\0"}) {  // 10 bytes each
    const std::vector<unsigned char> bytes(other, other + 10);
    EXPECT_NE(decode(bytes, out).find("not a PNG or JPEG"), std::string::npos) << other;
  }
  EXPECT_NE(decode({}, out).find("not a PNG or JPEG"), std::string::npos);
}

TEST(ImageDecode, SidesAboveTheLimitAreRefusedBeforeDecoding) {
  std::vector<unsigned char> pixels(40 * 2 * 4, 9);
  DecodedImage out;
  EXPECT_NE(decode(writePng(40, 2, PNG_FORMAT_RGBA, pixels.data()), out, 32).find("40x2"), std::string::npos);
  const unsigned char colour[3] = {1, 2, 3};
  EXPECT_NE(decode(writeJpeg(8, 48, colour), out, 32).find("8x48"), std::string::npos);
  EXPECT_TRUE(out.rgba8.empty());
}

TEST(ImageDecode, PngTooSmallForItsPixelsIsRefusedBeforeAllocating) {
  // A 16384x16384 header over a few bytes of data: deflate cannot pack 805 MB of rows into them,
  // so it is refused from the header (it allocated 1.15 GB before failing on the missing data).
  std::vector<unsigned char> small(4 * 4 * 4, 7);
  std::vector<unsigned char> bytes = writePng(4, 4, PNG_FORMAT_RGBA, small.data());
  for (int k = 0; k < 4; ++k) {  // IHDR's width and height, then a fresh CRC is not needed:
    bytes[16 + k] = static_cast<unsigned char>((16384u >> (8 * (3 - k))) & 0xff);
    bytes[20 + k] = static_cast<unsigned char>((16384u >> (8 * (3 - k))) & 0xff);
  }
  png_uint_32 crc = static_cast<png_uint_32>(crc32(0, bytes.data() + 12, 17));  // "IHDR" + 13 bytes
  for (int k = 0; k < 4; ++k) bytes[29 + k] = static_cast<unsigned char>((crc >> (8 * (3 - k))) & 0xff);
  DecodedImage out;
  const std::string why = decode(bytes, out);
  EXPECT_NE(why.find("PNG of 16384x16384 in"), std::string::npos) << why;
  EXPECT_NE(why.find("too few to hold its pixels"), std::string::npos) << why;
  EXPECT_TRUE(out.rgba8.empty());
  // The same image with its own size decodes (the bound is far above what real files need).
  EXPECT_EQ(decode(writePng(4, 4, PNG_FORMAT_RGBA, small.data()), out), "");
}

}  // namespace
