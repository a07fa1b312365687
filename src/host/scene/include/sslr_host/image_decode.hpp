// Decoding the images a glTF file embeds or names: PNG through libpng, JPEG through libjpeg-turbo,
// to RGBA8. glTF 2.0 allows only these two formats; tinygltf would hand any bytes to stb_image,
// which tries a dozen decoders (GIF, PSD, PIC, TGA, HDR, ...) of less hardened code than the two
// libraries Debian maintains for every image viewer.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace sslr::host {

struct DecodedImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgba8;  // width * height * 4 bytes, row 0 = top (as stored)
};

// "" on success; else what is wrong ("not a PNG or JPEG", the decoder's message, a side above
// maxSide). `out` is left empty on failure.
std::string decodePngOrJpeg(const unsigned char* bytes, std::size_t size, int maxSide, DecodedImage& out);

}  // namespace sslr::host
