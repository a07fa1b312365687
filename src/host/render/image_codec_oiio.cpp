#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "image_codecs.hpp"

namespace sslr::host::detail {

Expected<std::vector<unsigned char>> encodeOiio(const std::string& path, const Image& image,
                                                const std::vector<unsigned char>& srgb8,
                                                const std::vector<std::string>& channelNames) {
  const bool png = !srgb8.empty();
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return Status::error(path + ": cannot create image writer: " + OIIO::geterror());
  OIIO::ImageSpec spec(image.width, image.height, image.channels, png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
  if (!png && channelNames.size() == static_cast<size_t>(image.channels)) spec.channelnames = channelNames;
  if (!png) spec.attribute("compression", "zip");
  // Bytes as given: OpenImageIO would otherwise divide an RGBA PNG's colour by its alpha.
  if (png) spec.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::Filesystem::IOVecOutput memory;
  if (!out->supports("ioproxy") || !out->set_ioproxy(&memory))
    return Status::error(path + ": the image writer cannot encode into memory");
  if (!out->open(path, spec)) return Status::error(path + ": cannot encode: " + out->geterror());
  bool ok = true;
  if (png) {
    ok = out->write_image(OIIO::TypeDesc::UINT8, srgb8.data());
  } else {
    // Flip rows so the file's first row is the top of the picture (negative y stride).
    const size_t row = static_cast<size_t>(image.width) * image.channels;
    const auto stride = static_cast<OIIO::stride_t>(row * sizeof(float));
    ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data() + row * (image.height - 1),
                          OIIO::AutoStride, -stride);
  }
  if (!ok) {
    std::string err = out->geterror();
    out->close();
    return Status::error(path + ": encoding failed: " + err);
  }
  if (!out->close()) return Status::error(path + ": encoding failed: " + out->geterror());
  return memory.buffer();
}

Expected<Image> readOiio(const std::string& path) {
  // Values as stored: OpenImageIO would otherwise premultiply an RGBA PNG's colour by its alpha.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) return Status::error(path + ": cannot open image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  const size_t row = static_cast<size_t>(image.width) * image.channels;
  image.pixels.resize(row * image.height);
  const auto stride = static_cast<OIIO::stride_t>(row * sizeof(float));
  if (!in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT,
                      image.pixels.data() + row * (image.height - 1), OIIO::AutoStride, -stride))
    return Status::error(path + ": read failed: " + in->geterror());
  return image;
}

}  // namespace sslr::host::detail
