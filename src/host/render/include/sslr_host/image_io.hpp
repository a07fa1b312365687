// Images on the host side: float pixels in GL row order (row 0 = bottom), read and written
// through OpenImageIO or tinyexr + stb. Files are stored top row first, as every viewer expects.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "sslr/sslr.hpp"

namespace sslr::host {

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;  // width * height * channels, row 0 = bottom (GL)

  float& at(int x, int y, int c) { return pixels[(static_cast<size_t>(y) * width + x) * channels + c]; }
  float at(int x, int y, int c) const { return pixels[(static_cast<size_t>(y) * width + x) * channels + c]; }
};

// Two codecs behind one interface. OpenImageIO is the default where it is installed; tinyexr +
// stb (a few hundred kB instead of OpenImageIO's ~400 MB of dependencies) is always built, is
// the default without OpenImageIO (cmake -DSSLR_WITH_OPENIMAGEIO=OFF), and lets the tests check
// each codec's files against the other's.
enum class ImageCodec { OpenImageIO, TinyExrStb };
const char* imageCodecName(ImageCodec codec);
bool hasImageCodec(ImageCodec codec);
ImageCodec defaultImageCodec();

// .exr: 32-bit float, values as they are. .png: 8-bit, linear -> sRGB, clamped to [0,1].
// `channelNames` (optional) name the EXR channels, e.g. {"R","G","B","A"}.
// The file is written in full under a temporary name and renamed into place: a failed write (disk
// full, no permission) leaves nothing behind and says so.
Status writeImage(const std::string& path, const Image& image,
                  const std::vector<std::string>& channelNames = {});
// The image encoded as the file `path` would hold it (the extension picks the format).
Expected<std::vector<unsigned char>> encodeImage(const std::string& path, const Image& image,
                                                 const std::vector<std::string>& channelNames = {},
                                                 ImageCodec codec = defaultImageCodec());
// Writes every file under a temporary name of its own (a hidden, unique name beside it, created
// with O_CREAT | O_EXCL | O_NOFOLLOW), checking each write, then renames them all into place; on
// any failure every temporary is removed and no file is touched. A link at a destination is
// replaced, never followed. A destination that exists and is not a regular file (or a link to one)
// refuses the whole set (checkReplaceable).
Status writeFiles(const std::vector<std::pair<std::string, std::vector<unsigned char>>>& files);
Status writeTextFile(const std::string& path, const std::string& text);
// Creates and removes a uniquely named file in `dir`: "" if the tools can write there.
Status probeWritableDirectory(const std::string& dir);
// An output directory, checked before any work: created if missing, refused (with a message
// beginning with `dir`) if it is a file, a dangling link, or not writable.
Status prepareOutputDirectory(const std::string& dir);
// "" if writing `file` would replace nothing or a regular file (through a link: what it points to);
// else StatusCode::InvalidInput, naming what is there (a device, a fifo, a socket, a directory).
Status checkReplaceable(const std::string& file);
// An output file, checked before any work: not a directory, nor anything else checkReplaceable
// refuses, in an existing, writable directory.
Status checkOutputFile(const std::string& file);
// SIGINT, SIGTERM, SIGHUP and SIGXFSZ (a file size limit reached mid-write) remove the temporaries
// being written, then end the process as the signal would have. The first three are blocked in
// every thread and taken by one thread of their own (sigwait), which removes the temporaries while
// no writer can create or rename one. Call it first in main, before any other thread starts.
// A signal the process was started with ignored stays ignored.
void removeTemporariesOnSignal();
// PNG (8 or 16 bit) reads as stored, scaled to [0,1] (no sRGB decoding); EXR channels R, G, B, A
// come first in that order whatever the file's order.
Expected<Image> readImage(const std::string& path, ImageCodec codec = defaultImageCodec());

// Per-channel statistics of the difference of two images (same size and channels).
struct ImageDiff {
  double maxAbs = 0.0;
  double meanAbs = 0.0;
  size_t pixelsOver = 0;  // pixels with any channel above the threshold
};
ImageDiff compareImages(const Image& a, const Image& b, float threshold);

// Bilinear sample of the first three channels at uv (texel centres at (i + 0.5)/size, clamped).
glm::vec3 sampleBilinear(const Image& image, glm::vec2 uv);

// Pixels with any NaN or Inf channel.
size_t countNonFinite(const Image& image);

}  // namespace sslr::host
