// tinyexr (EXR) and stb (PNG) from Debian's libtinyexr-dev / libstb-dev: the small codec.
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <numeric>

#include "image_codecs.hpp"

namespace sslr::host::detail {

namespace {
// Channel names in our order: R, G, B, A first (as OpenImageIO reads them), and the names given
// to the first four channels when the caller names none.
constexpr std::array<const char*, 4> kRgba{"R", "G", "B", "A"};

std::string exrError(const char* err) {
  std::string s = err != nullptr ? err : "unknown error";
  if (err != nullptr) FreeEXRErrorMessage(err);
  return s;
}

// Where a channel goes in our order: kRgba first, then the others in file order.
int canonicalRank(const char* name) {
  for (int i = 0; i < 4; ++i)
    if (std::strcmp(name, kRgba[static_cast<size_t>(i)]) == 0) return i;
  return 4;
}
}  // namespace

Expected<std::vector<unsigned char>> encodeTinyExrStb(const std::string& path, const Image& image,
                                                      const std::vector<unsigned char>& srgb8,
                                                      const std::vector<std::string>& channelNames) {
  if (!srgb8.empty()) {
    std::vector<unsigned char> bytes;
    auto append = [](void* context, void* data, int size) {
      auto* out = static_cast<std::vector<unsigned char>*>(context);
      out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
    };
    if (stbi_write_png_to_func(append, &bytes, image.width, image.height, image.channels, srgb8.data(),
                               image.width * image.channels) == 0)
      return Status::error(path + ": PNG encoding failed (stb supports 1 to 4 channels)");
    return bytes;
  }
  const size_t n = static_cast<size_t>(image.channels);
  std::vector<std::string> names(n);
  for (size_t c = 0; c < n; ++c) {
    names[c] = channelNames.size() == n ? channelNames[c]
               : c < 4                  ? std::string(kRgba[c])
                                        : "channel" + std::to_string(c);
    if (names[c].empty() || names[c].size() > 255) return Status::error(path + ": bad EXR channel name");
  }
  // OpenEXR stores channels sorted by name; readers take the file's list as that order.
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return names[a] < names[b]; });
  const size_t pixels = static_cast<size_t>(image.width) * image.height;
  std::vector<std::vector<float>> planes(n, std::vector<float>(pixels));
  std::vector<unsigned char*> planePtrs(n);
  std::vector<EXRChannelInfo> channels(n);
  std::vector<int> types(n, TINYEXR_PIXELTYPE_FLOAT);
  for (size_t i = 0; i < n; ++i) {
    const size_t c = order[i];
    for (int y = 0; y < image.height; ++y)  // file rows top first
      for (int x = 0; x < image.width; ++x)
        planes[i][static_cast<size_t>(y) * image.width + x] = image.at(x, image.height - 1 - y, static_cast<int>(c));
    planePtrs[i] = reinterpret_cast<unsigned char*>(planes[i].data());
    channels[i] = EXRChannelInfo{};
    std::memcpy(channels[i].name, names[c].c_str(), names[c].size() + 1);
  }
  EXRHeader header;
  InitEXRHeader(&header);
  header.num_channels = image.channels;
  header.channels = channels.data();
  header.pixel_types = types.data();
  header.requested_pixel_types = types.data();
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
  EXRImage exr;
  InitEXRImage(&exr);
  exr.images = planePtrs.data();
  exr.width = image.width;
  exr.height = image.height;
  exr.num_channels = image.channels;
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const size_t size = SaveEXRImageToMemory(&exr, &header, &memory, &err);
  if (size == 0 || memory == nullptr) return Status::error(path + ": EXR encoding failed: " + exrError(err));
  std::vector<unsigned char> bytes(memory, memory + size);
  std::free(memory);
  return bytes;
}

Expected<Image> readTinyExrStb(const std::string& path) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) return Status::error(path + ": cannot open image");
  std::vector<unsigned char> bytes(static_cast<size_t>(std::max<std::streamoff>(file.tellg(), 0)));
  file.seekg(0);
  if (bytes.empty()) return Status::error(path + ": empty file");
  if (!file.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
    return Status::error(path + ": read failed");
  Image image;
  EXRVersion version;
  if (ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()) == TINYEXR_SUCCESS) {
    if (version.tiled != 0 || version.multipart != 0 || version.non_image != 0)
      return Status::error(path + ": tiled, multi-part and deep EXR files are not supported by tinyexr + stb");
    EXRHeader header;
    InitEXRHeader(&header);
    const char* err = nullptr;
    if (ParseEXRHeaderFromMemory(&header, &version, bytes.data(), bytes.size(), &err) != TINYEXR_SUCCESS) {
      FreeEXRHeader(&header);  // a failed parse can leave parts allocated
      return Status::error(path + ": bad EXR header: " + exrError(err));
    }
    for (int c = 0; c < header.num_channels; ++c) header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    EXRImage exr;
    InitEXRImage(&exr);
    if (LoadEXRImageFromMemory(&exr, &header, bytes.data(), bytes.size(), &err) != TINYEXR_SUCCESS) {
      FreeEXRHeader(&header);
      return Status::error(path + ": EXR read failed: " + exrError(err));
    }
    const size_t n = static_cast<size_t>(header.num_channels);
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      return canonicalRank(header.channels[a].name) < canonicalRank(header.channels[b].name);
    });
    image.width = exr.width;
    image.height = exr.height;
    image.channels = header.num_channels;
    image.pixels.resize(static_cast<size_t>(image.width) * image.height * n);
    for (size_t i = 0; i < n; ++i) {
      const auto* plane = reinterpret_cast<const float*>(exr.images[order[i]]);
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
          image.at(x, image.height - 1 - y, static_cast<int>(i)) = plane[static_cast<size_t>(y) * image.width + x];
    }
    FreeEXRImage(&exr);
    FreeEXRHeader(&header);
    return image;
  }
  // Everything else through stb (PNG, 8 or 16 bit; also JPEG, TGA, BMP), values scaled to [0,1].
  const int len = static_cast<int>(std::min<size_t>(bytes.size(), INT32_MAX));
  int w = 0, h = 0, comp = 0;
  if (stbi_info_from_memory(bytes.data(), len, &w, &h, &comp) == 0)
    return Status::error(path + ": cannot open image: " + stbi_failure_reason());
  const bool wide = stbi_is_16_bit_from_memory(bytes.data(), len) != 0;
  void* data = wide ? static_cast<void*>(stbi_load_16_from_memory(bytes.data(), len, &w, &h, &comp, 0))
                    : static_cast<void*>(stbi_load_from_memory(bytes.data(), len, &w, &h, &comp, 0));
  if (data == nullptr) return Status::error(path + ": read failed: " + stbi_failure_reason());
  image.width = w;
  image.height = h;
  image.channels = comp;
  image.pixels.resize(static_cast<size_t>(w) * h * comp);
  const size_t row = static_cast<size_t>(w) * comp;
  for (int y = 0; y < h; ++y)
    for (size_t i = 0; i < row; ++i) {
      const size_t src = static_cast<size_t>(y) * row + i;
      const float v = wide ? static_cast<const unsigned short*>(data)[src] / 65535.0f
                           : static_cast<const unsigned char*>(data)[src] / 255.0f;
      image.pixels[static_cast<size_t>(h - 1 - y) * row + i] = v;
    }
  stbi_image_free(data);
  return image;
}

}  // namespace sslr::host::detail
