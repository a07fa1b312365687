#include "sslr_host/image_decode.hpp"

#include <png.h>

#include <csetjmp>
#include <cstdint>
#include <cstdio>  // jpeglib.h needs FILE
#include <cstring>

#include <jpeglib.h>

namespace sslr::host {

namespace {

constexpr std::uint64_t kMaxDeflateRatio = 1032;

std::string tooLarge(unsigned width, unsigned height, int maxSide) {
  return std::to_string(width) + "x" + std::to_string(height) + ": the tools load images up to " +
         std::to_string(maxSide) + "x" + std::to_string(maxSide);
}

// libpng's classic API with explicit transforms (palette, grey and 16-bit to 8-bit RGBA), every
// row buffer sized from png_get_rowbytes after the transforms, and a reader that refuses to read
// past the bytes it was given.
struct PngSource {
  const unsigned char* bytes;
  std::size_t size, offset;
  char message[200];
};

void pngRead(png_structp png, png_bytep out, png_size_t length) {
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (length > source->size - source->offset) png_error(png, "unexpected end of data");
  std::memcpy(out, source->bytes + source->offset, length);
  source->offset += length;
}

[[noreturn]] void pngError(png_structp png, png_const_charp message) {
  auto* source = static_cast<PngSource*>(png_get_error_ptr(png));
  std::snprintf(source->message, sizeof source->message, "%s", message);
  png_longjmp(png, 1);
}

void pngWarning(png_structp, png_const_charp) {}  // e.g. an unknown ancillary chunk: read on

// No object with a destructor lives in this frame across setjmp (`out` belongs to the caller, the
// error strings are built after the jump), and what the error path reads is volatile or unchanged.
std::string decodePng(const unsigned char* bytes, std::size_t size, int maxSide, DecodedImage& out) {
  PngSource source{bytes, size, 0, {}};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &source, pngError, pngWarning);
  if (png == nullptr) return "PNG: out of memory";
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    return "PNG: out of memory";
  }
  // Set after setjmp and read after a jump back: volatile, or their values would be indeterminate.
  volatile png_uint_32 width = 0, height = 0;
  volatile bool large = false, missing = false;
  if (setjmp(png_jmpbuf(png)) != 0) {
    png_destroy_read_struct(&png, &info, nullptr);
    if (missing)
      return "PNG of " + std::to_string(width) + "x" + std::to_string(height) + " in " + std::to_string(size) +
             " bytes: too few to hold its pixels (deflate packs at most " + std::to_string(kMaxDeflateRatio) +
             ":1); truncated or forged";
    return large ? "PNG of " + tooLarge(width, height, maxSide) : std::string("PNG: ") + source.message;
  }
  png_set_read_fn(png, &source, pngRead);
  png_read_info(png, info);
  width = png_get_image_width(png, info);
  height = png_get_image_height(png, info);
  if (width > unsigned(maxSide) || height > unsigned(maxSide)) {
    large = true;
    png_error(png, "too large");
  }
  // Deflate packs at most 1032 bytes into one, so a file too small to hold its pixels even at that
  // ratio is truncated or forged: refused before the pixels' memory is allocated.
  const std::uint64_t rawBytes = std::uint64_t(height) * (std::uint64_t(png_get_rowbytes(png, info)) + 1);
  if (rawBytes / kMaxDeflateRatio > size) {
    missing = true;
    png_error(png, "too little data");
  }
  png_set_expand(png);     // palette -> RGB, grey below 8 bits -> 8 bits, tRNS -> alpha
  png_set_strip_16(png);   // 16-bit -> 8-bit
  png_set_gray_to_rgb(png);
  png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);  // opaque where the image has no alpha
  const int passes = png_set_interlace_handling(png);  // Adam7: every row once per pass
  png_read_update_info(png, info);
  const std::size_t rowBytes = std::size_t(width) * 4;
  if (png_get_rowbytes(png, info) != rowBytes) png_error(png, "unexpected row layout after conversion to RGBA8");
  out.rgba8.resize(rowBytes * height);
  for (int pass = 0; pass < passes; ++pass)
    for (png_uint_32 y = 0; y < height; ++y) png_read_row(png, out.rgba8.data() + rowBytes * y, nullptr);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  out.width = static_cast<int>(width);
  out.height = static_cast<int>(height);
  return {};
}

// libjpeg reports fatal errors through error_exit, which must not return: it jumps back here.
struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void jpegErrorExit(j_common_ptr info) {
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  (*info->err->format_message)(info, errors->message);
  std::longjmp(errors->jump, 1);
}

void jpegIgnoreMessage(j_common_ptr) {}  // warnings (a truncated scan, say): decode what there is

// No object with a destructor lives in this frame between setjmp and the calls that may jump
// back: `out` belongs to the caller, and the error path builds its string after the jump.
std::string decodeJpeg(const unsigned char* bytes, std::size_t size, int maxSide, DecodedImage& out) {
  jpeg_decompress_struct info;
  std::memset(&info, 0, sizeof info);  // destroying it before jpeg_create_decompress ran is a no-op
  JpegErrors errors;
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jpegErrorExit;
  errors.manager.output_message = jpegIgnoreMessage;
  errors.message[0] = '\0';
  if (setjmp(errors.jump) != 0) {
    jpeg_destroy_decompress(&info);
    return std::string("JPEG: ") + errors.message;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes, static_cast<unsigned long>(size));
  jpeg_read_header(&info, TRUE);
  if (info.image_width > unsigned(maxSide) || info.image_height > unsigned(maxSide)) {
    const unsigned w = info.image_width, h = info.image_height;
    jpeg_destroy_decompress(&info);
    return "JPEG of " + tooLarge(w, h, maxSide);
  }
  info.out_color_space = JCS_EXT_RGBA;  // libjpeg-turbo: RGB with an opaque alpha byte
  jpeg_start_decompress(&info);
  const std::size_t rowBytes = std::size_t(info.output_width) * 4;
  out.rgba8.resize(rowBytes * info.output_height);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = out.rgba8.data() + rowBytes * info.output_scanline;
    if (jpeg_read_scanlines(&info, &row, 1) != 1) break;  // suspended: cannot happen from memory
  }
  out.width = static_cast<int>(info.output_width);
  out.height = static_cast<int>(info.output_height);
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return {};
}

}  // namespace

std::string decodePngOrJpeg(const unsigned char* bytes, std::size_t size, int maxSide, DecodedImage& out) {
  out = DecodedImage{};
  static const unsigned char pngMagic[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  std::string why = "not a PNG or JPEG (the only image formats of glTF 2.0)";
  if (size >= 8 && std::memcmp(bytes, pngMagic, 8) == 0) why = decodePng(bytes, size, maxSide, out);
  else if (size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) why = decodeJpeg(bytes, size, maxSide, out);
  if (!why.empty()) out = DecodedImage{};  // nothing half-decoded is handed on
  return why;
}

}  // namespace sslr::host
