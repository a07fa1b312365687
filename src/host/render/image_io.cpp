#include "sslr_host/image_io.hpp"

#include "image_codecs.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <random>
#include <thread>

#include <fcntl.h>
#include <pthread.h>
#include <unistd.h>

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

namespace {
// Temporaries being written: fixed slots, so that SIGXFSZ's handler (run on the writing thread,
// mid-write) reads them without allocating. Creating or renaming a temporary and its slot change
// together under gTempMutex, which the signal thread takes before it removes them: a temporary is
// either registered or not yet created when the process ends.
constexpr int kTempSlots = 64;
char gTempPaths[kTempSlots][4096];
std::atomic<bool> gTempUsed[kTempSlots];
std::mutex gTempMutex;

int registerTemp(const std::string& path) {
  if (path.size() >= sizeof gTempPaths[0]) return -1;
  for (int i = 0; i < kTempSlots; ++i) {
    bool expected = false;
    if (gTempUsed[i].compare_exchange_strong(expected, true)) {
      std::memcpy(gTempPaths[i], path.c_str(), path.size() + 1);
      return i;
    }
  }
  return -1;  // more open temporaries than slots: that one is not removed on a signal
}
void unregisterTemp(int slot) {
  if (slot >= 0) gTempUsed[slot].store(false);
}
void removeRegisteredTemps() {
  for (int i = 0; i < kTempSlots; ++i)
    if (gTempUsed[i].load()) ::unlink(gTempPaths[i]);
}
// Ends the process as `sig` would have, from the calling thread.
[[noreturn]] void endBySignal(int sig) {
  std::signal(sig, SIG_DFL);
  sigset_t one;
  sigemptyset(&one);
  sigaddset(&one, sig);
  ::pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
  std::raise(sig);
  std::_Exit(128 + sig);  // only if the default action did not end the process
}
extern "C" void removeTempsOnFileSizeLimit(int sig) {
  removeRegisteredTemps();
  endBySignal(sig);
}

// A new file beside `path` under a name nobody else uses: O_CREAT | O_EXCL | O_NOFOLLOW, so a file
// or link planted under a guessable name is never opened, and two writers never share one.
struct TempFile {
  int fd = -1;
  std::string path;
  int slot = -1;
};
Expected<TempFile> createTemp(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  static std::atomic<unsigned> counter{0};
  std::random_device random;
  for (int attempt = 0; attempt < 100; ++attempt) {
    char suffix[64];
    std::snprintf(suffix, sizeof suffix, ".%d-%u-%08x.partial", static_cast<int>(::getpid()), counter++, random());
    TempFile t;
    std::string name(1, '.');  // hidden: a listing of --out shows finished files only
    name.append(target.filename().string()).append(suffix);
    t.path = (target.parent_path() / name).string();
    std::lock_guard<std::mutex> lock(gTempMutex);
    t.fd = ::open(t.path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (t.fd >= 0) {
      t.slot = registerTemp(t.path);
      return t;
    }
    if (errno != EEXIST) return Status::error(path + ": cannot create a temporary file beside it: " + std::strerror(errno));
  }
  return Status::error(path + ": cannot create a temporary file beside it: 100 unique names were taken");
}

bool writeAll(int fd, const unsigned char* data, size_t size, size_t& written) {
  written = 0;
  while (written < size) {
    const ssize_t n = ::write(fd, data + written, size - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    written += static_cast<size_t>(n);
  }
  return true;
}
}  // namespace

void removeTemporariesOnSignal() {
  // SIGINT, SIGTERM and SIGHUP come from outside, to whichever thread does not block them (EGL's
  // and llvmpipe's threads too): they are blocked here, before any other thread starts (threads
  // inherit the mask), and one thread of ours takes them with sigwait. A signal the process was
  // started with ignored (nohup) stays ignored.
  sigset_t outside;
  sigemptyset(&outside);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    if (::sigaction(sig, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    sigaddset(&outside, sig);
  }
  ::pthread_sigmask(SIG_BLOCK, &outside, nullptr);
  std::thread([outside] {
    int sig = 0;
    while (::sigwait(&outside, &sig) != 0) {
    }
    gTempMutex.lock();  // held until the process ends: no temporary is created or renamed after this
    removeRegisteredTemps();
    endBySignal(sig);
  }).detach();
  // SIGXFSZ (a file size limit reached) is raised on the thread whose write passed the limit, with
  // its temporary registered: a handler there removes the temporaries.
  struct sigaction current {};
  if (::sigaction(SIGXFSZ, nullptr, &current) == 0 && current.sa_handler != SIG_IGN)
    std::signal(SIGXFSZ, removeTempsOnFileSizeLimit);
}

Status probeWritableDirectory(const std::string& dir) {
  auto temp = createTemp((std::filesystem::path(dir) / "sslr-write-probe").string());
  if (!temp) return Status::error(temp.error());
  ::close(temp.value().fd);
  std::lock_guard<std::mutex> lock(gTempMutex);
  ::unlink(temp.value().path.c_str());
  unregisterTemp(temp.value().slot);
  return {};
}

Status prepareOutputDirectory(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path path(dir);
  if (fs::is_symlink(fs::symlink_status(path, ec)) && !fs::exists(path, ec))
    return Status::error(dir + " is a link to '" + fs::read_symlink(path, ec).string() + "', which does not exist");
  if (fs::exists(path, ec) && !fs::is_directory(path, ec)) return Status::error(dir + " exists and is not a directory");
  fs::create_directories(path, ec);
  if (ec) return Status::error(dir + ": cannot create the directory: " + ec.message());
  if (Status s = probeWritableDirectory(dir); !s) return Status::error(dir + " is not writable: " + s.message());
  return {};
}

Status checkReplaceable(const std::string& file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status target = fs::status(file, ec);  // through a link: what it points to
  if (!fs::exists(target) || fs::is_regular_file(target)) return {};
  const char* what = fs::is_directory(target)  ? "a directory"
                     : fs::is_fifo(target)      ? "a fifo"
                     : fs::is_character_file(target) ? "a character device"
                     : fs::is_block_file(target)     ? "a block device"
                     : fs::is_socket(target)         ? "a socket"
                                                     : "not a regular file";
  return Status::error(StatusCode::InvalidInput,
                       file + " exists and is " + what + ": refused, nothing written (name a new or regular file)");
}

Status checkOutputFile(const std::string& file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path path(file);
  if (file.empty()) return Status::error("the file name is empty");
  if (fs::is_directory(path, ec)) return Status::error(file + " is a directory: name a file");
  if (Status s = checkReplaceable(file); !s) return s;
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec)) return Status::error(file + ": its directory " + parent.string() + " does not exist");
  if (Status s = probeWritableDirectory(parent.string()); !s)
    return Status::error(file + ": its directory is not writable: " + s.message());
  return {};
}

Status writeFiles(const std::vector<std::pair<std::string, std::vector<unsigned char>>>& files) {
  std::vector<TempFile> temps;
  auto discard = [&] {
    std::lock_guard<std::mutex> lock(gTempMutex);
    for (const auto& t : temps) {
      ::unlink(t.path.c_str());
      unregisterTemp(t.slot);
    }
  };
  for (const auto& [path, bytes] : files) {
    auto temp = createTemp(path);
    if (!temp) {
      discard();
      return Status::error(temp.error());
    }
    temps.push_back(temp.value());
    size_t written = 0;
    const bool ok = writeAll(temps.back().fd, bytes.data(), bytes.size(), written);
    const int writeErrno = errno;
    const bool closed = ::close(temps.back().fd) == 0;
    if (!ok || !closed) {
      const std::string why = std::strerror(!ok ? writeErrno : errno);
      discard();
      return Status::error(path + ": write failed after " + std::to_string(written) + " of " +
                           std::to_string(bytes.size()) + " bytes: " + why + " (nothing was written)");
    }
  }
  // Nothing but regular files (or links to them) is replaced: not a device, a fifo or a socket
  // that took the name since the tool checked it.
  for (const auto& file : files)
    if (Status s = checkReplaceable(file.first); !s) {
      discard();
      return s;
    }
  // rename() replaces a link at the destination itself, never the file it points to.
  for (size_t i = 0; i < files.size(); ++i) {
    std::unique_lock<std::mutex> lock(gTempMutex);
    if (::rename(temps[i].path.c_str(), files[i].first.c_str()) != 0) {
      const std::string why = std::strerror(errno);
      lock.unlock();
      discard();
      return Status::error(files[i].first + ": cannot move the finished file into place: " + why);
    }
    unregisterTemp(temps[i].slot);
  }
  return {};
}

Status writeTextFile(const std::string& path, const std::string& text) {
  return writeFiles({{path, std::vector<unsigned char>(text.begin(), text.end())}});
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
