// The glTF loader's file access (only inside the model's folder, through checked descriptors) and
// its image limits (sizes from the headers before decoding, a budget for all images together).
#include "gltf_internal.hpp"

#include "sslr_host/image_decode.hpp"

#include <cerrno>
#include <cstring>
#include <limits>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sslr::host::gltf {

std::string printable(const std::string& text, size_t limit) {
  std::string out;
  for (char ch : text) {
    if (out.size() >= limit) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(ch);
    out += (c >= 32 && c < 127) ? ch : (c == '\n' ? ' ' : '?');
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// ---- File access: only inside the model's folder ----------------------------------------------
// tinygltf reads external buffers and images through these callbacks. A URI may name any path
// ("/etc/passwd", "../../x"); a renderer run on files from elsewhere must not read outside the
// model's folder, nor try to read a directory or a huge file into memory.
// 'text', printable and short (built by appending: GCC 12 misreads "'" + std::string at -O3).
std::string quoted(const std::string& text) {
  std::string out = "'";
  out += printable(text);
  out += "'";
  return out;
}

std::string explainOutside(const std::string& path, const FolderJail& jail) {
  return quoted(path) + " is outside the model's folder " + jail.root.string() +
         " (external buffers and images must lie in that folder or below it)";
}

// Opens `path` and checks what was opened, not the name: a regular file (a FIFO or device is
// never read: the open does not block), of at most `limit` bytes, and, with a jail, inside its
// root (the descriptor's real path, read back from /proc/self/fd). Then reads it through the same
// descriptor, so a file swapped for a link after the check is never what is read. "" on success.
std::string readChecked(const std::string& path, const FolderJail* jail, std::uintmax_t limit,
                        std::vector<unsigned char>& out) {
  namespace fs = std::filesystem;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) return quoted(path) + ": " + std::strerror(errno);
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) return quoted(path) + ": " + std::strerror(errno);
  if (!S_ISREG(st.st_mode)) return quoted(path) + " is not a regular file";
  if (jail != nullptr) {
    std::error_code ec;
    const fs::path opened = fs::read_symlink("/proc/self/fd/" + std::to_string(fd), ec);
    if (ec) return quoted(path) + ": cannot tell where it lies (/proc/self/fd: " + ec.message() + ")";
    if (opened.string() != jail->modelFile) {
      const auto rel = opened.lexically_relative(jail->root);
      if (rel.empty() || *rel.begin() == "..") return explainOutside(path, *jail);
    }
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > limit)
    return quoted(path) + " is " + std::to_string(size >> 20) + " MiB (more than the " +
           std::to_string(limit >> 20) + " MiB limit)";
  out.resize(static_cast<size_t>(size));
  size_t done = 0;
  while (done < out.size()) {
    const ssize_t n = ::read(fd, out.data() + done, out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return "cannot read '" + printable(path) + "'" + (n < 0 ? std::string(": ") + std::strerror(errno) : "");
    done += static_cast<size_t>(n);
  }
  return {};
}

// Anything that exists "exists" here, so that the read below is attempted and its refusal says why.
bool jailFileExists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

std::string jailExpandFilePath(const std::string& path, void*) { return path; }  // no ~ or $VAR

bool jailReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  if (std::string why = readChecked(path, static_cast<FolderJail*>(user), kMaxExternalFileBytes, *out); !why.empty()) {
    if (err) *err += why + "\n";
    return false;
  }
  return true;
}

bool jailWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not supported\n";
  return false;
}

// ---- Images: size limits before decoding ---------------------------------------------------------
constexpr int kMaxImageSide = 16384;
// All images of a file together, decoded to RGBA8: a small PNG can stand for a large image, and a
// file can list one many times (each entry decodes on its own).
constexpr std::uint64_t kMaxDecodedImageBytes = std::uint64_t(1) << 30;  // 1 GiB

// Width and height from a PNG or JPEG header (false: another format or a short header).
bool imageSize(const unsigned char* bytes, int size, int& w, int& h) {
  auto be16 = [&](int at) { return (bytes[at] << 8) | bytes[at + 1]; };
  auto be32 = [&](int at) { return int((unsigned(bytes[at]) << 24) | (unsigned(bytes[at + 1]) << 16) | (unsigned(bytes[at + 2]) << 8) | bytes[at + 3]); };
  static const unsigned char png[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  if (size >= 24 && std::memcmp(bytes, png, 8) == 0) {
    w = be32(16);
    h = be32(20);
    return true;
  }
  if (size >= 4 && bytes[0] == 0xff && bytes[1] == 0xd8) {
    int at = 2;
    while (at + 9 < size && bytes[at] == 0xff) {
      const int marker = bytes[at + 1];
      const int length = be16(at + 2);
      // Start-of-frame markers (baseline, progressive, ...) carry the size.
      if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc) {
        h = be16(at + 5);
        w = be16(at + 7);
        return true;
      }
      at += 2 + length;
    }
  }
  return false;
}

// tinygltf's image callback: libpng or libjpeg (image_decode.hpp), never stb_image. An image larger
// than the tools load, or one that does not decode, is left empty with a warning; images that
// together would decode to more than kMaxDecodedImageBytes refuse the file (by their headers,
// before decoding).
bool limitedImageLoader(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int, int,
                        const unsigned char* bytes, int size, void* user) {
  // An image stored in a bufferView arrives as a pointer into the buffer and the view's byteLength:
  // tinygltf 2.7 (Debian 12) does not check that the view lies inside the buffer, so a view past its
  // end had the decoder read past the heap block (found by tests/fuzz). The model's buffers are
  // parsed by now: the view is checked against the bytes the buffer really holds.
  auto& budget = *static_cast<ImageBudget*>(user);
  if (image->bufferView >= 0) {
    const auto& model = *budget.model;
    const size_t viewIndex = static_cast<size_t>(image->bufferView);
    bool inside = viewIndex < model.bufferViews.size();
    if (inside) {
      const tinygltf::BufferView& view = model.bufferViews[viewIndex];
      size_t end = 0;
      inside = view.buffer >= 0 && static_cast<size_t>(view.buffer) < model.buffers.size() &&
               !addOverflows(view.byteOffset, view.byteLength, end) &&
               end <= model.buffers[static_cast<size_t>(view.buffer)].data.size() &&
               view.byteLength <= static_cast<size_t>(std::numeric_limits<int>::max());
    }
    if (!inside) {
      if (err)
        *err += "image " + std::to_string(index) + ": bufferView " + std::to_string(image->bufferView) +
                " runs past the end of its buffer\n";
      return false;
    }
  }
  auto notDecoded = [&](const std::string& why) {
    // The geometry is still good: the image is left empty and its materials keep their factors
    // (loadMaterials warns per material).
    if (warn) *warn += "image " + std::to_string(index) + " ('" + printable(image->uri) + "') not decoded: " + why + "\n";
    image->width = image->height = 0;
    image->image.clear();
    return true;
  };
  auto overBudget = [&](std::uint64_t bytesMore) {
    if (budget.decodedBytes + bytesMore <= kMaxDecodedImageBytes) return false;
    if (err)
      *err += "image " + std::to_string(index) + " ('" + printable(image->uri) + "') would bring the file's decoded images to " +
              std::to_string((budget.decodedBytes + bytesMore) >> 20) + " MiB: the tools load up to " +
              std::to_string(kMaxDecodedImageBytes >> 20) + " MiB of images (RGBA8) per file\n";
    return true;
  };
  int w = 0, h = 0;
  if (imageSize(bytes, size, w, h)) {
    if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide)
      return notDecoded("it is " + std::to_string(w) + "x" + std::to_string(h) + ": the tools load images up to " +
                        std::to_string(kMaxImageSide) + "x" + std::to_string(kMaxImageSide));
    // Counted from the header, before decoding: what the file claims is what it may cost.
    const std::uint64_t claimed = std::uint64_t(w) * std::uint64_t(h) * 4;
    if (overBudget(claimed)) return false;
    budget.decodedBytes += claimed;
  }
  // The decoder's own limit stays as the guard on what it allocates: the header sniff above may
  // miss a JPEG's frame marker.
  DecodedImage decoded;
  if (std::string why = decodePngOrJpeg(bytes, size > 0 ? static_cast<size_t>(size) : 0, kMaxImageSide, decoded);
      !why.empty())
    return notDecoded(printable(why));
  if (w <= 0) {  // a size the header sniff missed, counted once decoded
    if (overBudget(decoded.rgba8.size())) return false;
    budget.decodedBytes += decoded.rgba8.size();
  }
  image->width = decoded.width;
  image->height = decoded.height;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image = std::move(decoded.rgba8);
  return true;
}

}  // namespace sslr::host::gltf
