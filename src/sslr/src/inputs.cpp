// Checks of the host's inputs: every texture exists, is 2D, has the context's size and a usable
// format, and the surface layout fits it. Each error names the field, the GL name and the problem.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "context_impl.hpp"

namespace sslr {

FormatInfo formatInfo(GLint f) {
  switch (f) {
    case GL_DEPTH_COMPONENT16: return {FormatInfo::Depth, 1, "DEPTH_COMPONENT16", 2};
    case GL_DEPTH_COMPONENT24: return {FormatInfo::Depth, 1, "DEPTH_COMPONENT24", 4};
    case GL_DEPTH_COMPONENT32: return {FormatInfo::Depth, 1, "DEPTH_COMPONENT32", 4};
    case GL_DEPTH_COMPONENT32F: return {FormatInfo::Depth, 1, "DEPTH_COMPONENT32F", 4};
    case GL_DEPTH24_STENCIL8: return {FormatInfo::Depth, 1, "DEPTH24_STENCIL8", 4};
    case GL_DEPTH32F_STENCIL8: return {FormatInfo::Depth, 1, "DEPTH32F_STENCIL8", 8};
    case GL_R8: return {FormatInfo::Color, 1, "R8", 1};
    case GL_R16: return {FormatInfo::Color, 1, "R16", 2};
    case GL_R16F: return {FormatInfo::Color, 1, "R16F", 2};
    case GL_R32F: return {FormatInfo::Color, 1, "R32F", 4};
    case GL_RG8: return {FormatInfo::Color, 2, "RG8", 2};
    case GL_RG16: return {FormatInfo::Color, 2, "RG16", 4};
    case GL_RG16F: return {FormatInfo::Color, 2, "RG16F", 4};
    case GL_RG32F: return {FormatInfo::Color, 2, "RG32F", 8};
    case GL_RGB8: return {FormatInfo::Color, 3, "RGB8", 3};
    case GL_RGB16: return {FormatInfo::Color, 3, "RGB16", 6};
    case GL_RGB16F: return {FormatInfo::Color, 3, "RGB16F", 6};
    case GL_RGB32F: return {FormatInfo::Color, 3, "RGB32F", 12};
    case GL_R11F_G11F_B10F: return {FormatInfo::Color, 3, "R11F_G11F_B10F", 4};
    case GL_RGB9_E5: return {FormatInfo::Color, 3, "RGB9_E5", 4};
    case GL_SRGB8: return {FormatInfo::Color, 3, "SRGB8", 3};
    case GL_RGBA8: return {FormatInfo::Color, 4, "RGBA8", 4};
    case GL_SRGB8_ALPHA8: return {FormatInfo::Color, 4, "SRGB8_ALPHA8", 4};
    case GL_RGB10_A2: return {FormatInfo::Color, 4, "RGB10_A2", 4};
    case GL_RGBA16: return {FormatInfo::Color, 4, "RGBA16", 8};
    case GL_RGBA16F: return {FormatInfo::Color, 4, "RGBA16F", 8};
    case GL_RGBA32F: return {FormatInfo::Color, 4, "RGBA32F", 16};
    // Signed normalized: normals with SurfaceLayout::normalScale 1, normalBias 0.
    case GL_R8_SNORM: return {FormatInfo::Color, 1, "R8_SNORM", 1};
    case GL_RG8_SNORM: return {FormatInfo::Color, 2, "RG8_SNORM", 2};
    case GL_RGBA8_SNORM: return {FormatInfo::Color, 4, "RGBA8_SNORM", 4};
    case GL_R16_SNORM: return {FormatInfo::Color, 1, "R16_SNORM", 2};
    case GL_RG16_SNORM: return {FormatInfo::Color, 2, "RG16_SNORM", 4};
    case GL_RGBA16_SNORM: return {FormatInfo::Color, 4, "RGBA16_SNORM", 8};
    default: return {};
  }
}

Status Context::Impl::checkCurrentContext(const char* call) const {
  if (gl.GetString(GL_VERSION) != nullptr) return {};
  return Status::error(StatusCode::NoCurrentContext, std::string("sslr: ") + call +
                       ": no OpenGL context is current on this thread (make the context sslr was created "
                       "with current first)");
}

namespace {
// Integer formats by name: sslr samples through float samplers, which read an integer texture as
// undefined values, so they are refused with what they are.
const char* integerFormatName(GLint f) {
  switch (f) {
    case GL_R8UI: return "R8UI"; case GL_R8I: return "R8I"; case GL_R16UI: return "R16UI"; case GL_R16I: return "R16I";
    case GL_R32UI: return "R32UI"; case GL_R32I: return "R32I"; case GL_RG8UI: return "RG8UI"; case GL_RG8I: return "RG8I";
    case GL_RG16UI: return "RG16UI"; case GL_RG16I: return "RG16I"; case GL_RG32UI: return "RG32UI";
    case GL_RG32I: return "RG32I"; case GL_RGB8UI: return "RGB8UI"; case GL_RGB8I: return "RGB8I";
    case GL_RGB16UI: return "RGB16UI"; case GL_RGB16I: return "RGB16I"; case GL_RGB32UI: return "RGB32UI";
    case GL_RGB32I: return "RGB32I"; case GL_RGBA8UI: return "RGBA8UI"; case GL_RGBA8I: return "RGBA8I";
    case GL_RGB10_A2UI: return "RGB10_A2UI"; case GL_RGBA16UI: return "RGBA16UI"; case GL_RGBA16I: return "RGBA16I";
    case GL_RGBA32UI: return "RGBA32UI"; case GL_RGBA32I: return "RGBA32I";
    default: return nullptr;
  }
}
}  // namespace

// Checks one host texture: exists, is 2D (of several views: a 2D array with a layer a view), has
// the context's size and a usable format.
Status Context::Impl::checkTexture(GLName tex, const char* what, FormatInfo::Kind kind, int minChannels,
                                   FormatInfo* infoOut, bool perView) const {
  std::ostringstream where;
  where << "sslr: " << what << " (texture " << tex << ")";
  if (tex == 0) return Status::error(StatusCode::InvalidInput, where.str() + " is 0: the texture is required");
  if (!gl.IsTexture(tex)) return Status::error(StatusCode::InvalidInput, where.str() + " is not a texture name");
  GLint target = 0;
  gl.GetTextureParameteriv(tex, GL_TEXTURE_TARGET, &target);
  const bool layered = perView && views > 1;
  if (!layered && target != GL_TEXTURE_2D) return Status::error(StatusCode::InvalidInput, where.str() + " is not a GL_TEXTURE_2D");
  if (layered) {
    if (target != GL_TEXTURE_2D_ARRAY)
      return Status::error(StatusCode::InvalidInput, where.str() + " is not a GL_TEXTURE_2D_ARRAY: a context of " +
                           std::to_string(views) + " views (ContextDesc::views) reads layer v of each input for view v");
    GLint layers = 0;
    gl.GetTextureLevelParameteriv(tex, 0, GL_TEXTURE_DEPTH, &layers);
    if (layers < views)
      return Status::error(StatusCode::InvalidInput, where.str() + " has " + std::to_string(layers) + " layer(s); the context's " +
                           std::to_string(views) + " views need one each");
  }
  GLint w = 0, h = 0, format = 0;
  gl.GetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
  gl.GetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &h);
  gl.GetTextureLevelParameteriv(tex, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
  if (w != width || h != height) {
    where << " is " << w << "x" << h << " but the context is " << width << "x" << height;
    return Status::error(StatusCode::InvalidInput, where.str());
  }
  FormatInfo info = formatInfo(format);
  if (const char* integer = integerFormatName(format)) {
    where << " has internal format 0x" << std::hex << format << std::dec << " (" << integer
          << "), an integer format: sslr samples it as floats; use a unorm or float format";
    return Status::error(StatusCode::InvalidInput, where.str());
  }
  if (info.kind != kind) {
    where << " has internal format 0x" << std::hex << format << std::dec << " ("
          << info.name << "); expected " << (kind == FormatInfo::Depth ? "a depth format" :
                                             "a float or unorm colour format");
    return Status::error(StatusCode::InvalidInput, where.str());
  }
  if (info.channels < minChannels) {
    where << " has " << info.channels << " channel(s) (" << info.name << "); needs " << minChannels;
    return Status::error(StatusCode::InvalidInput, where.str());
  }
  if (kind == FormatInfo::Depth &&
      (format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8)) {
    GLint mode = 0;
    gl.GetTextureParameteriv(tex, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
    if (mode != GL_DEPTH_COMPONENT)
      return Status::error(StatusCode::InvalidInput, where.str() + " samples stencil (GL_DEPTH_STENCIL_TEXTURE_MODE); "
                           "set it to GL_DEPTH_COMPONENT");
  }
  if (infoOut) *infoOut = info;
  return {};
}

// A normalized format's stored range, decoded by SurfaceLayout::normalScale/normalBias, must be
// [-1, 1] (within 5%): an SNORM texture left on the unsigned default (2, -1) decodes to [-3, 1] and
// finds almost no hit, a UNORM one on the signed decode (1, 0) to [0, 1]. Float formats hold
// whatever the host wrote. The GL says which kind the texture's components are.
Status Context::Impl::checkNormalDecode(const SurfaceLayout& sl, const FormatInfo& info, GLName tex) const {
  GLint componentType = GL_NONE;
  gl.GetTextureLevelParameteriv(tex, 0, GL_TEXTURE_RED_TYPE, &componentType);
  const bool snorm = componentType == GL_SIGNED_NORMALIZED;
  auto decodesToUnit = [&](float stored0) {
    const float a = stored0 * sl.normalScale + sl.normalBias, b = sl.normalScale + sl.normalBias;
    return std::abs(std::min(a, b) + 1.0f) <= 0.05f && std::abs(std::max(a, b) - 1.0f) <= 0.05f;
  };
  // A float format holds whatever the host wrote: [0, 1] decoded as unsigned is right, -1..1 so
  // decoded finds almost no hit. Said once per texture (the log), not refused.
  if (componentType == GL_FLOAT && decodesToUnit(0.0f) && warnedFloatNormals != tex) {
    warnedFloatNormals = tex;
    std::ostringstream why;
    why << "sslr: FrameInputs::normalTexture (texture " << tex << ") is " << info.name
        << ", a float format, decoded as holding [0, 1] (SurfaceLayout::normalScale/normalBias = " << sl.normalScale
        << "/" << sl.normalBias << "); if it holds -1..1, set 1/0, or reflections point the wrong way";
    message(LogLevel::Warning, why.str());
  }
  if (!snorm && componentType != GL_UNSIGNED_NORMALIZED) return {};
  if (decodesToUnit(snorm ? -1.0f : 0.0f)) return {};
  const float a = (snorm ? -1.0f : 0.0f) * sl.normalScale + sl.normalBias, b = sl.normalScale + sl.normalBias;
  const float lo = std::min(a, b), hi = std::max(a, b);
  std::ostringstream why;
  why << "sslr: FrameInputs::normalTexture (texture " << tex << ") is " << info.name << ", whose "
      << (snorm ? "[-1, 1]" : "[0, 1]") << " values SurfaceLayout::normalScale/normalBias = " << sl.normalScale << "/"
      << sl.normalBias << " decode to [" << lo << ", " << hi << "], not [-1, 1]: use "
      << (snorm ? "1/0 for a signed (SNORM) format" : "2/-1 for an unsigned (UNORM) format");
  return Status::error(StatusCode::InvalidInput, why.str());
}

// SurfaceLayout's channels against the texture holding them (`materialInfo`: the material
// texture's format, else the normal texture's), its constants, and the coloured F0's inputs.
Status Context::Impl::checkSurfaceLayout(const FrameInputs& in, const FormatInfo& materialInfo,
                                         FormatInfo* baseColorInfo) const {
  const SurfaceLayout& sl = in.surface;
  const bool separate = in.materialTexture != 0;
  const char* materialName = separate ? "materialTexture" : "normalTexture";
  auto checkChannel = [&](int channel, const char* name) -> Status {
    if (channel < -1 || channel > 3)
      return Status::error(StatusCode::InvalidInput, std::string("sslr: SurfaceLayout::") + name + " = " +
                           std::to_string(channel) + " (must be -1..3)");
    if (channel >= materialInfo.channels)
      return Status::error(StatusCode::InvalidInput, std::string("sslr: SurfaceLayout::") + name + " = " +
                           std::to_string(channel) + " but " + materialName + " (" + materialInfo.name +
                           ") has only " + std::to_string(materialInfo.channels) + " channel(s)");
    return {};
  };
  if (Status s = checkChannel(sl.roughnessChannel, "roughnessChannel"); !s) return s;
  if (Status s = checkChannel(sl.reflectanceChannel, "reflectanceChannel"); !s) return s;
  if (Status s = checkChannel(sl.metalnessChannel, "metalnessChannel"); !s) return s;
  if (sl.metalnessChannel >= 0 && in.baseColorTexture == 0)
    return Status::error(StatusCode::InvalidInput, "sslr: SurfaceLayout::metalnessChannel = " +
                         std::to_string(sl.metalnessChannel) + " needs FrameInputs::baseColorTexture (metals' F0)");
  if (in.baseColorTexture != 0) {
    if (sl.metalnessChannel < 0)
      return Status::error(StatusCode::InvalidInput, "sslr: FrameInputs::baseColorTexture is set but SurfaceLayout::metalnessChannel "
                           "is -1: name the channel holding metalness");
    if (Status s = checkTexture(in.baseColorTexture, "FrameInputs::baseColorTexture", FormatInfo::Color, 3, baseColorInfo); !s)
      return s;
  }
  const int normalUses = separate ? 0 : (sl.normals == NormalEncoding::Octahedral ? 2 : 3);
  if (sl.roughnessChannel >= 0 && sl.roughnessChannel < normalUses)
    return Status::error(StatusCode::InvalidInput, "sslr: SurfaceLayout::roughnessChannel overlaps the normal's channels");
  if (sl.reflectanceChannel >= 0 && sl.reflectanceChannel < normalUses)
    return Status::error(StatusCode::InvalidInput, "sslr: SurfaceLayout::reflectanceChannel overlaps the normal's channels");
  if (sl.metalnessChannel >= 0 && sl.metalnessChannel < normalUses)
    return Status::error(StatusCode::InvalidInput, "sslr: SurfaceLayout::metalnessChannel overlaps the normal's channels");
  if (!std::isfinite(sl.constantRoughness) || !std::isfinite(sl.constantReflectance))
    return Status::error(StatusCode::InvalidInput, "sslr: SurfaceLayout constant roughness/reflectance must be finite");
  return {};
}

Status Context::Impl::checkInputs(const FrameInputs& in, Method method, TrafficModel* formats) const {
  FormatInfo depthInfo, positionInfo, colorInfo, maskInfo, backDepthInfo, motionInfo;
  if (Status s = checkTexture(in.depthTexture, "FrameInputs::depthTexture", FormatInfo::Depth, 1, &depthInfo); !s)
    return s;
  if (method == Method::PositionBuffer) {
    if (Status s = checkTexture(in.positionTexture, "FrameInputs::positionTexture", FormatInfo::Color, 4, &positionInfo); !s)
      return Status::error(s.code(), s.message() + " (Method::PositionBuffer needs a view-space position texture)");
  }
  if (Status s = checkTexture(in.colorTexture, "FrameInputs::colorTexture", FormatInfo::Color, 3, &colorInfo); !s)
    return s;
  const int normalChannels = in.surface.normals == NormalEncoding::Octahedral ? 2 : 3;
  FormatInfo normalInfo;
  if (Status s = checkTexture(in.normalTexture, "FrameInputs::normalTexture", FormatInfo::Color, normalChannels,
                              &normalInfo);
      !s)
    return s;
  if (Status s = checkNormalDecode(in.surface, normalInfo, in.normalTexture); !s) return s;
  const SurfaceLayout& sl = in.surface;
  // The material channels are of the material texture when there is one, else of the normal one.
  const bool separate = in.materialTexture != 0;
  FormatInfo materialInfo = normalInfo;
  if (separate) {
    if (Status s = checkTexture(in.materialTexture, "FrameInputs::materialTexture", FormatInfo::Color, 1, &materialInfo); !s)
      return s;
  }
  if (in.maskTexture != 0) {
    if (Status s = checkTexture(in.maskTexture, "FrameInputs::maskTexture", FormatInfo::Color, 1, &maskInfo); !s) return s;
  }
  if (in.backDepthTexture != 0) {
    if (Status s = checkTexture(in.backDepthTexture, "FrameInputs::backDepthTexture", FormatInfo::Depth, 1, &backDepthInfo); !s)
      return Status::error(s.code(), s.message() + " (the back-face depth: the host's depth pass with front faces culled)");
    if (in.backDepthTexture == in.depthTexture)
      return Status::error(StatusCode::InvalidInput, "sslr: FrameInputs::backDepthTexture is the depthTexture itself; it must be a depth pass "
                           "of its own with front faces culled");
  }
  if (in.motionTexture != 0) {
    if (Status s = checkTexture(in.motionTexture, "FrameInputs::motionTexture", FormatInfo::Color, 2, &motionInfo); !s) return s;
  }
  FormatInfo baseColorInfo;
  if (Status s = checkSurfaceLayout(in, materialInfo, &baseColorInfo); !s) return s;
  if (formats != nullptr) {
    formats->depthBytes = depthInfo.bytes;
    formats->normalBytes = normalInfo.bytes;
    formats->materialBytes = separate ? materialInfo.bytes : 0;
    formats->maskBytes = in.maskTexture != 0 ? maskInfo.bytes : 0;
    formats->backDepthBytes = in.backDepthTexture != 0 ? backDepthInfo.bytes : 0;
    formats->colorBytes = colorInfo.bytes;
    formats->positionBytes = method == Method::PositionBuffer ? positionInfo.bytes : 0;
    formats->motionBytes = in.motionTexture != 0 ? motionInfo.bytes : 0;
    formats->baseColorBytes = in.baseColorTexture != 0 ? baseColorInfo.bytes : 0;
    formats->materialGathers = (sl.roughnessChannel >= 0 ? 1 : 0) + (sl.reflectanceChannel >= 0 ? 1 : 0);
  }
  return {};
}

}  // namespace sslr
