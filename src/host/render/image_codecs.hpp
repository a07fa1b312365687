// The two image codecs behind image_io.hpp. Each encodes into memory (the files are written by
// writeFiles) and reads into an Image with row 0 = bottom.
#pragma once

#include <string>
#include <vector>

#include "sslr_host/image_io.hpp"

namespace sslr::host::detail {

// `srgb8` holds the PNG's bytes (top row first) when the path ends in .png; EXR encodes `image`.
Expected<std::vector<unsigned char>> encodeOiio(const std::string& path, const Image& image,
                                                const std::vector<unsigned char>& srgb8,
                                                const std::vector<std::string>& channelNames);
Expected<Image> readOiio(const std::string& path);

Expected<std::vector<unsigned char>> encodeTinyExrStb(const std::string& path, const Image& image,
                                                      const std::vector<unsigned char>& srgb8,
                                                      const std::vector<std::string>& channelNames);
Expected<Image> readTinyExrStb(const std::string& path);

}  // namespace sslr::host::detail
