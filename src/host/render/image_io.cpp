#include "sslr_host/image_io.hpp"

#include "image_codecs.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace sslr::host {

namespace {
float linearToSrgb(float v) {
  if (!(v > 0.0f)) return 0.0f;  // NaN and negatives -> 0
  if (v >= 1.0f) return 1.0f;
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}
bool endsWith(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(s[s.size() - suffix.size() + i]) != suffix[i]) return false;
  return true;
}
}  // namespace

Expected<std::vector<unsigned char>> encodeImage(const std::string& path, const Image& image,
                                                 const std::vector<std::string>& channelNames, ImageCodec codec) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels)
    return Status::error(path + ": refusing to write an empty or inconsistent image");
  const bool png = endsWith(path, ".png");
  const bool exr = endsWith(path, ".exr");
  if (!png && !exr) return Status::error(path + ": unsupported image extension (use .png or .exr)");
  if (!hasImageCodec(codec))
    return Status::error(path + ": this build has no " + imageCodecName(codec) + " image codec");
  // PNG rows are stored top first, 8-bit sRGB; alpha stays linear.
  std::vector<unsigned char> srgb;
  if (png) {
    const size_t row = static_cast<size_t>(image.width) * image.channels;
    srgb.resize(row * image.height);
    for (int y = 0; y < image.height; ++y)
      for (size_t i = 0; i < row; ++i) {
        float v = image.pixels[static_cast<size_t>(image.height - 1 - y) * row + i];
        const bool alpha = image.channels == 4 && i % 4 == 3;
        v = alpha ? std::clamp(std::isfinite(v) ? v : 0.0f, 0.0f, 1.0f) : linearToSrgb(v);
        srgb[static_cast<size_t>(y) * row + i] = static_cast<unsigned char>(std::lround(v * 255.0f));
      }
  }
#ifdef SSLR_HAVE_OPENIMAGEIO
  if (codec == ImageCodec::OpenImageIO) return detail::encodeOiio(path, image, srgb, channelNames);
#endif
  return detail::encodeTinyExrStb(path, image, srgb, channelNames);
}

Status writeFiles(const std::vector<std::pair<std::string, std::vector<unsigned char>>>& files) {
  namespace fs = std::filesystem;
  std::vector<std::string> temps;
  auto discard = [&] {
    std::error_code ec;
    for (const auto& t : temps) fs::remove(t, ec);
  };
  for (const auto& [path, bytes] : files) {
    const std::string temp = path + ".partial";
    temps.push_back(temp);
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (f == nullptr) {
      const std::string why = std::strerror(errno);
      discard();
      return Status::error(path + ": cannot create: " + why);
    }
    const size_t written = bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), f);
    const bool flushed = std::fflush(f) == 0;
    const int writeErrno = errno;
    const bool closed = std::fclose(f) == 0;
    if (written != bytes.size() || !flushed || !closed) {
      const std::string why = std::strerror(written != bytes.size() || !flushed ? writeErrno : errno);
      discard();
      return Status::error(path + ": write failed after " + std::to_string(written) + " of " +
                           std::to_string(bytes.size()) + " bytes: " + why + " (nothing was written)");
    }
  }
  for (size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    fs::rename(temps[i], files[i].first, ec);
    if (ec) {
      discard();
      return Status::error(files[i].first + ": cannot move the finished file into place: " + ec.message());
    }
  }
  return {};
}

Status writeImage(const std::string& path, const Image& image, const std::vector<std::string>& channelNames) {
  auto bytes = encodeImage(path, image, channelNames);
  if (!bytes) return Status::error(bytes.error());
  return writeFiles({{path, std::move(bytes.value())}});
}

Expected<Image> readImage(const std::string& path, ImageCodec codec) {
  if (!hasImageCodec(codec))
    return Status::error(path + ": this build has no " + imageCodecName(codec) + " image codec");
#ifdef SSLR_HAVE_OPENIMAGEIO
  if (codec == ImageCodec::OpenImageIO) return detail::readOiio(path);
#endif
  return detail::readTinyExrStb(path);
}

const char* imageCodecName(ImageCodec codec) {
  return codec == ImageCodec::OpenImageIO ? "OpenImageIO" : "tinyexr + stb";
}

bool hasImageCodec(ImageCodec codec) {
#ifdef SSLR_HAVE_OPENIMAGEIO
  if (codec == ImageCodec::OpenImageIO) return true;
#endif
  return codec == ImageCodec::TinyExrStb;
}

ImageCodec defaultImageCodec() {
#ifdef SSLR_HAVE_OPENIMAGEIO
  return ImageCodec::OpenImageIO;
#else
  return ImageCodec::TinyExrStb;
#endif
}

ImageDiff compareImages(const Image& a, const Image& b, float threshold) {
  ImageDiff d;
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) {
    d.maxAbs = INFINITY;
    d.pixelsOver = static_cast<size_t>(std::max(a.width * a.height, b.width * b.height));
    return d;
  }
  double sum = 0.0;
  for (size_t p = 0; p < static_cast<size_t>(a.width) * a.height; ++p) {
    bool over = false;
    for (int c = 0; c < a.channels; ++c) {
      const double diff = std::abs(static_cast<double>(a.pixels[p * a.channels + c]) - b.pixels[p * a.channels + c]);
      const double v = std::isfinite(diff) ? diff : INFINITY;
      d.maxAbs = std::max(d.maxAbs, v);
      sum += std::isfinite(v) ? v : 0.0;
      over = over || !(v <= threshold);
    }
    d.pixelsOver += over ? 1 : 0;
  }
  d.meanAbs = sum / (static_cast<double>(a.width) * a.height * a.channels);
  return d;
}

glm::vec3 sampleBilinear(const Image& image, glm::vec2 uv) {
  const float fx = uv.x * image.width - 0.5f, fy = uv.y * image.height - 0.5f;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  const float ax = fx - x0, ay = fy - y0;
  auto texel = [&](int x, int y) {
    x = std::clamp(x, 0, image.width - 1);
    y = std::clamp(y, 0, image.height - 1);
    glm::vec3 v(0.0f);
    for (int c = 0; c < std::min(image.channels, 3); ++c) v[c] = image.at(x, y, c);
    return v;
  };
  return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), ax), glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), ax), ay);
}

size_t countNonFinite(const Image& image) {
  size_t n = 0;
  for (size_t p = 0; p < static_cast<size_t>(image.width) * image.height; ++p) {
    bool bad = false;
    for (int c = 0; c < image.channels; ++c) bad = bad || !std::isfinite(image.pixels[p * image.channels + c]);
    n += bad ? 1 : 0;
  }
  return n;
}

}  // namespace sslr::host
