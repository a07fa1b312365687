// sslr - Screen Space Local Reflections for OpenGL 4.5 deferred renderers (depth-only variant).
//
// Quick start (docs/integration.md has the full checklist and the input table; the same lines are
// compiled by the find_package consumer test, tests/consumer/main.cpp):
//   auto ctx = sslr::Context::create({width, height, eglGetProcAddress});   // once
//   if (!ctx) log(ctx.error());
//   sslr::FrameInputs in;                                                     // per frame
//   in.colorTexture = colorTex; in.normalTexture = normalTex; in.depthTexture = depthTex;
//   in.clipFromView = clipFromView;  // glm::dmat4, the matrix that rasterized the depth
//   if (auto st = ctx.value()->dispatch(in, sslr::Settings::preset(sslr::Preset::High)); !st)
//     log(st.message());
//   ctx.value()->composite(hostFramebuffer);   // adds the resolved reflection to what is there
//   // or, where the host's lighting already added a fallback specular (probes, sky) it keeps:
//   ctx.value()->composite(hostFramebuffer, {sslr::CompositeMode::BlendOverFallback, fallbackTex});
//
// The library loads its own GL function table from the host's getProcAddress (no global gl*
// symbols, no loader clash), owns only the objects it creates, and restores every piece of GL
// state it touches (see docs/integration.md, "GL state"). C++20 (std::span, requires-expressions):
// the CMake target sslr::sslr asks its users' compilers for it.
#pragma once

#if !defined(__cplusplus) || (__cplusplus < 202002L && !(defined(_MSVC_LANG) && _MSVC_LANG >= 202002L))
#error "sslr/sslr.hpp needs C++20 (-std=c++20, /std:c++20, or link the CMake target sslr::sslr)"
#endif

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include <glm/glm.hpp>

#include "sslr/compare.hpp"  // the comparison methods' settings (Settings::positionBuffer, dda, ffx)
#include "sslr/version.hpp"  // SSLR_VERSION_MAJOR/MINOR/PATCH, SSLR_VERSION_STRING

namespace sslr {

using GLProc = void (*)();
using GetProcAddress = GLProc (*)(const char* name);  // eglGetProcAddress, glfwGetProcAddress
using GLName = std::uint32_t;                          // a GLuint texture / framebuffer name

// ---- Results ---------------------------------------------------------------------------------
// The version of the library that was linked ("MAJOR.MINOR.PATCH"): a host built against headers
// of another version can compare it with SSLR_VERSION_STRING at start.
const char* libraryVersion();

// What kind of error a Status carries, for a host that reacts by kind (the message says what and
// where, for people).
enum class StatusCode {
  Ok = 0,
  InvalidSettings,    // Settings (validate()) or CompositeOptions out of range
  InvalidInput,       // a host texture, framebuffer or FrameInputs field sslr cannot use
  InvalidProjection,  // clipFromView / DepthConvention: not a supported or consistent projection
  InvalidSize,        // a context size out of range
  NoCurrentContext,   // no GL context current on the calling thread
  GlUnavailable,      // GL below 4.5, missing entry points or limits
  ShaderBuild,        // an embedded shader failed to compile or link (a driver problem: report it)
  NoFrame,            // composite() before a successful dispatch()
  Failed,             // anything else (the tools' own errors)
};
const char* toString(StatusCode code);

class Status {
 public:
  Status() = default;
  static Status error(StatusCode code, std::string message) { return Status(code, std::move(message)); }
  static Status error(std::string message) { return Status(StatusCode::Failed, std::move(message)); }
  bool ok() const { return code_ == StatusCode::Ok; }
  explicit operator bool() const { return ok(); }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }

 private:
  Status(StatusCode code, std::string message) : message_(std::move(message)), code_(code) {}
  std::string message_;
  StatusCode code_ = StatusCode::Ok;
};

template <typename T>
class Expected {
 public:
  Expected(T value) : value_(std::move(value)) {}
  Expected(Status error) : error_(std::move(error)) {}
  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  T& value() { return *value_; }
  const T& value() const { return *value_; }
  T& operator*() { return *value_; }
  const T& operator*() const { return *value_; }
  // The value's members; for a pointer-like value (Context::create's unique_ptr) its pointee's,
  // so `ctx->dispatch(...)` works on what create() returned. Only on success, like value().
  decltype(auto) operator->() {
    if constexpr (requires(T& t) { t.operator->(); }) return (*value_);
    else return &*value_;
  }
  decltype(auto) operator->() const {
    if constexpr (requires(const T& t) { t.operator->(); }) return (*value_);
    else return &*value_;
  }
  const std::string& error() const { return error_.message(); }
  const Status& status() const { return error_; }  // the error with its code (Ok on success)

 private:
  std::optional<T> value_;
  Status error_;
};

// ---- Inputs ----------------------------------------------------------------------------------
enum class DepthRange {
  NegativeOneToOne,  // GL's default clip space: window depth = ndc z * 0.5 + 0.5
  ZeroToOne,         // glClipControl(..., GL_ZERO_TO_ONE): window depth = ndc z
};

struct DepthConvention {
  DepthRange range = DepthRange::ZeroToOne;
  bool reversedZ = true;  // near plane at depth 1, background (clear value) 0
  // Infinite far planes need no flag: they are a property of clipFromView.

  static constexpr DepthConvention glDefault() { return {DepthRange::NegativeOneToOne, false}; }
  static constexpr DepthConvention zeroToOne() { return {DepthRange::ZeroToOne, false}; }
  static constexpr DepthConvention reversed() { return {DepthRange::ZeroToOne, true}; }
};

enum class NormalEncoding {
  Octahedral,  // channels R,G = the octahedral normal's two coordinates (see NormalSpace), stored
               // as SurfaceLayout::normalScale/normalBias unpack them: [0, 1] by default (UNORM,
               // or floats holding 0..1), -1..1 with scale 1, bias 0 (SNORM, or floats holding -1..1)
  XyzUnorm,    // channels R,G,B = the normal's components, stored the same way (by default
               // normal * 0.5 + 0.5, the article's packing)
};

enum class NormalSpace {
  View,   // the normal texture holds view-space normals
  World,  // it holds world-space normals; FrameInputs::viewFromWorld turns them into view space
};

// Where the material bits live: channels of the normal texture, or of FrameInputs::materialTexture.
struct SurfaceLayout {
  NormalEncoding normals = NormalEncoding::Octahedral;
  int roughnessChannel = 2;         // 0..3 of the normal texture, or -1: constantRoughness
  int reflectanceChannel = 3;       // 0..3 (F0 in [0,1]), or -1: constantReflectance
  float constantRoughness = 0.0f;
  float constantReflectance = 1.0f;
  NormalSpace space = NormalSpace::View;  // the space the decoded normals are in
  // How a stored normal channel unpacks to [-1, 1]: value * normalScale + normalBias (finite, scale
  // not 0). The default suits unsigned formats (RGBA8, RGBA16, RG16, float textures holding 0..1);
  // signed normalized formats (RG16_SNORM, RGBA16_SNORM, RGBA8_SNORM) and float textures holding
  // -1..1 take scale 1, bias 0. Octahedral: the two coordinates; xyz: the three components. A
  // normalized format on the wrong decode is refused; a float one on the unsigned decode is said
  // once in ContextDesc::log (its values are the host's to know).
  float normalScale = 2.0f;
  float normalBias = -1.0f;
  // Coloured F0 (metalness workflow): the channel of the material texture (else of the normal
  // texture) holding metalness 0..1, with FrameInputs::baseColorTexture. The Fresnel term's F0 is
  // then mix(reflectance, base colour, metalness) per channel (a metal's reflection takes its
  // tint); -1 (the default): F0 = the reflectance, grey.
  int metalnessChannel = -1;
};

// The rectangle of the host's textures that holds this frame, in texels from their (0, 0) corner
// (GL's: bottom left): dynamic resolution renders into a part of textures sized for the largest
// frame. width = height = 0: the whole of them (the context's size).
struct Viewport {
  int x = 0, y = 0;
  int width = 0, height = 0;
};

struct FrameInputs {
  GLName colorTexture = 0;   // lit colour (any float/unorm colour format), sampled bilinearly
  GLName normalTexture = 0;  // packed view-space normal + material, see SurfaceLayout
  GLName depthTexture = 0;   // the hardware depth buffer the G-buffer was rasterized with
  GLName positionTexture = 0;  // Method::PositionBuffer only: RGBA32F/RGBA16F view position, w = 1
  GLName materialTexture = 0;  // optional: the texture SurfaceLayout's roughness/reflectance
                               // channels refer to (0: they are channels of normalTexture)
  GLName maskTexture = 0;      // optional: rays start only where its first channel is > 0.5
                               // (an engine's "SSR here" stencil, copied to a colour texture)
  GLName backDepthTexture = 0; // optional: the nearest back face's depth per pixel (the host's depth
                               // pass again with front faces culled; a depth format, the same size
                               // and convention as depthTexture). The depth-only tracers then take
                               // what each pixel shows to be as deep as measured instead of
                               // Settings::traversal.objectDepthRelative x its distance (where a back face lies
                               // behind it): rays pass behind thin legs and stop inside boxes
  GLName baseColorTexture = 0; // with SurfaceLayout::metalnessChannel: the surface's base colour
                               // (linear RGB, >= 3 channels), metals' F0
  GLName motionTexture = 0;    // optional, Settings::temporal: RG = this pixel's uv minus the uv the
                               // same surface point had in the previous frame (the host's motion
                               // vectors, uv units); where history is looked up instead of the
                               // matrix reprojection, so moving objects are followed
  glm::dmat4 clipFromView{1.0};  // the exact projection that rasterized the depth (jitter incl.)
  glm::dmat4 viewFromWorld{0.0}; // NormalSpace::World only: the view matrix of the frame (all zeros = not given: an error then)
  // Settings::temporal only: where this frame's view-space points were in the previous frame's
  // clip space = previous clipFromView (its jitter included) x previous viewFromWorld x this
  // frame's worldFromView (the inverse of viewFromWorld). All zeros = not given: taken where no
  // previous frame exists (the context's first temporal frame, historyReset), refused after that.
  glm::dmat4 previousClipFromView{0.0};
  // Scene-to-display scale of colorTexture's values (an engine's exposure), for
  // Settings::radianceClamp's limit; finite, > 0.
  float exposure = 1.0f;
  // Settings::temporal only: this frame starts the history afresh (a camera cut, a teleport): no
  // history is read, as on the first frame; this frame's output becomes the next one's history.
  bool historyReset = false;
  DepthConvention depth{};
  SurfaceLayout surface{};
  // Where the frame lies in the textures (all of them, inputs and outputs, the context's size):
  // clipFromView maps onto this rectangle, motion vectors are in its uv units, and sslr writes its
  // outputs to the same rectangle (zeros elsewhere). Changing it from frame to frame reallocates
  // nothing; a frame whose rectangle differs from the previous one's starts without temporal
  // history.
  Viewport viewport{};
};

// ---- Settings --------------------------------------------------------------------------------
enum class FresnelMode {
  Classic,  // the article: reflectance * saturate(2.8 (1 - cos)^2) * (1 - saturate(L / d * errorK)),
            // d = the reflecting point's distance from the camera (scale-independent)
  Schlick,  // F0 + (1 - F0)(1 - cos)^5 with F0 = the pixel's reflectance
};

// What the reflection and resolved outputs hold (alpha: the blur weight and the coverage alike).
enum class OutputMode {
  // rgb = hit colour x Fresnel term (FresnelMode, from the surface's reflectance) x coverage: ready
  // to add (composite()).
  Weighted,
  // rgb = hit colour x coverage: the reflected radiance, for an engine that applies its own
  // specular term (split-sum DFG, coloured F0, clear coat): specular = resolved.rgb x its term +
  // (1 - resolved.a) x its fallback's. composite() refuses a frame traced so.
  Radiance,
};

// How rough surfaces reflect.
enum class GlossyMode {
  // The SSLR article's: the mirror ray, its reflection blurred over the cone of the surface's
  // roughness (Settings::blur). Deterministic; biased where the lobe sees more than the mirror
  // image's neighbourhood.
  ConeBlur,
  // Pixels at least Settings::glossy.stochasticFrom rough trace one ray a frame drawn from their
  // GGX lobe (visible normals, Heitz 2018), resolved in space and over frames (Settings::temporal):
  // with the blur on, by a 3x3 filter in the temporal blend once there is a history (their
  // reflection's blur weight is then 0). With temporal reuse, a frame without history (the first,
  // a reset, a new viewport) is ConeBlur's: the history starts from the best single-frame
  // estimate. Without temporal reuse each frame is one noisy sample per pixel, blurred over the
  // same cone; with blur.maxRadiusPx = 0 the samples are left raw (for an engine's own denoiser).
  // A lobe ray reads the colour of the surface it hit, not a bilinear blend across an outline.
  // Not with halfResolution.
  Stochastic,
};

enum class Preset { Low, Medium, High, Ultra };

enum class Method {
  AdaptiveL,           // depth-only, sslr's method: the hierarchical traversal on every ray and the
                       // SSLR article's adaptive-L iteration where it has no hit (with
                       // traversal.maxSteps = 0, adaptive L alone)
  HierarchicalDepth,   // depth-only: the min-max depth pyramid traversal alone (for comparison)
  PositionBuffer,      // comparison: "3D Game Shaders For Beginners" march on a position texture
  ScreenSpaceDDA,      // comparison, depth-only: McGuire & Mara 2014's perspective-correct DDA
  FidelityFxSssr,      // comparison, depth-only: AMD FidelityFX SSSR 1.1.4's hierarchical raymarch
                       // and hit validation for mirror rays (shaders/sslr_trace_ffx.h)
};

// Where Method::AdaptiveL's second stage runs (ContextDesc::traversalPass): adaptive L after the
// traversal, and the hit model's answer for a ray whose walk ended inside what a pixel shows
// (sslrJudgeInside). The answers are the same.
enum class TraversalPass {
  Auto,      // Inline under DeviceProfile::Gpu. Under DeviceProfile::Software Deferred,
             // but Inline while more than about half the pixels (half resolution: quads) of the
             // traced tiles needed the second stage in the previous frame (deferring then costs
             // more than it saves)
  Inline,    // in the pixel's own invocation, after the walk: GPUs
  Deferred,  // a pass of its own that traces the pixels that need it again, whole: CPU
             // rasterizers run code a pixel does not take under lane masks, so the second stage
             // inline slows every pixel
};

// Every setting with its unit and valid range; validate() enforces each range. Grouped by the
// stage it steers; Settings::preset gives the tuned combinations.
struct Settings {
  Method method = Method::AdaptiveL;
  FresnelMode fresnel = FresnelMode::Classic;
  OutputMode output = OutputMode::Weighted;
  // Also write hitDistanceTexture(): each pixel's reflected ray length to its hit, in view units
  // (the input FidelityFX's and Unreal's denoisers and contact-hardening blurs take); a guess's
  // negated.
  bool hitDistance = false;
  bool halfResolution = false;  // one ray per 2x2 quad (the traced pixel rotates per frame); the
                                // quad's pixels on the same surface reuse its hit, the others trace
                                // their own ray. Depth-only methods only

  // Which pixels get a ray.
  struct Selection {
    float roughnessCutoff = 0.5f;  // roughness, 0..1: rougher pixels are not traced
    float minReflectance = 0.01f;  // finite: pixels with reflectance <= this are not traced
  } selection;

  // Method::AdaptiveL's iteration (the article's), docs/algorithm.md, "Adaptive L".
  struct AdaptiveL {
    int maxIterations = 16;             // 1..256 iterations, each one depth fetch (the article: 10)
    float convergenceEps = 0.002f;      // >= 0: stop once |L_new - L| <= eps * L
    float initialLengthScreen = 0.03f;  // (0, 1]: the first L moves the probe this fraction of
                                        // the screen height (at least 4 px); 0.09 in Preset::Low,
                                        // where adaptive L starts at the surface, not after a walk
  } adaptiveL;

  // The min-max depth pyramid traversal: AdaptiveL's fallback and check, HierarchicalDepth's
  // tracer (docs/algorithm.md, "The hierarchical traversal").
  struct Traversal {
    int maxSteps = 112;  // 0..1024 pyramid cells visited per ray, each one fetch. AdaptiveL: the
                         // traversal runs on every ray, adaptive L where it has no hit (from where
                         // it ran out of steps); 0 = no traversal, adaptive L alone (Preset::Low).
                         // HierarchicalDepth: 1..1024
    float objectDepthRelative = 0.075f;  // >= 0, fraction of the view depth: how deep what a
                                         // pixel shows is assumed to be (without a back-face
                                         // depth). A ray less deep behind it ran into it (no
                                         // hit), a deeper one passes behind. Less deep near
                                         // an object's outline, deeper behind convex curved
                                         // surfaces (docs/algorithm.md, "Thickness")
    float hiddenGuess = 0.5f;  // 0..1: the confidence of a guess. A ray that ends without a hit
                               // where it went out of sight (behind what the screen shows, or into
                               // an object's assumed thickness) gets the colour where it did, at
                               // this weight: what the screen shows of the occluder standing in for
                               // its hidden side, the rest the fallback. 0 = a miss. Adaptive L
                               // alone (maxSteps = 0) guesses too, where its probes went behind.
                               // Not for GlossyMode::Stochastic's rays once temporal reuse has a
                               // history (their mean over frames takes misses)
  } traversal;

  // What weighs a hit's reflection down (never the hit itself).
  struct Fades {
    float errorK = 0.15f;         // >= 0, FresnelMode::Classic: the article's error term, weight
                                  // 1 - saturate(L / distance * errorK) (its "LDelmiter")
    float maxDistance = 1.0e30f;  // > 0 view units: longer reflections get no weight at all
    float screenEdge = 0.03f;     // 0..0.5 of the screen: fade width at the screen border
    float cameraStart = 0.6f;     // dot(R, to-camera) where camera-facing rays begin to fade
    float cameraEnd = 0.9f;       // >= cameraStart: ... and where they are gone
  } fades;

  // The roughness blur (pass 4): a bilateral blur whose radius is the reflection's alpha.
  struct Blur {
    float maxRadiusPx = 8.0f;   // 0..32 pixels: the radius that alpha = 1 stands for; 0 = no
                                // blur (resolved = the raw reflection)
    float coneScale = 1.0f;     // >= 0: cone tan(half angle) = roughness^2 * coneScale
    float depthSigma = 0.02f;   // > 0: neighbour weight exp(-|dz| / (depthSigma * z))
    float normalPower = 16.0f;  // >= 0: neighbour weight max(0, n0.n1)^normalPower
  } blur;

  // Rough surfaces (GlossyMode).
  struct Glossy {
    GlossyMode mode = GlossyMode::ConeBlur;
    float stochasticFrom = 0.1f;  // 0..1 roughness: Stochastic draws rays from this roughness up
  } glossy;

  // Temporal reuse (pass 5): blends with the previous frame's output, reprojected through
  // FrameInputs::previousClipFromView (converges half resolution and jittered projections).
  // HDR-safe radiance: a sun or an emitter at 1,000x the average luminance, reflected by a few
  // pixels, turns the blur and the temporal history into fireflies. A hit colour whose luminance
  // (Rec. 709) times FrameInputs::exposure exceeds maxLuminance is scaled down to it (hue kept),
  // before the weights, the blur and temporal reuse. 0 = off.
  struct RadianceClamp {
    float maxLuminance = 0.0f;  // >= 0, in display units (the colour texture's x exposure)
  } radianceClamp;

  struct Temporal {
    bool enabled = false;
    float historyWeight = 0.8f;  // 0..0.98: the history's share of the output
    // Also write historyConfidenceTexture(): how much of each pixel's resolved value came from
    // history (0 where it was disoccluded, rejected or absent), for an engine's own TAA.
    bool outputConfidence = false;
  } temporal;

  struct Debug {
    bool outputs = false;       // also write hitTexture() and iterationsTexture()
    bool collectStats = false;  // count tiles, traced pixels and fetches, time the passes (read a
                                // few frames late: no stall; see lastStats)
  } debug;

  // The comparison methods' parameters (sslr/compare.hpp); sslr's own method reads none of them.
  PositionBufferSettings positionBuffer;  // Method::PositionBuffer only
  DdaSettings dda;                        // Method::ScreenSpaceDDA only
  FfxSssrSettings ffx;                    // Method::FidelityFxSssr only

  static Settings preset(Preset preset);
};

// Settings -> why they are invalid ("" when fine). dispatch() calls it too.
std::string validate(const Settings& settings);

// ---- Context ---------------------------------------------------------------------------------
enum class LogLevel { Info, Warning, Error };
using LogCallback = std::function<void(LogLevel, const std::string&)>;

// Which device the pass shapes are chosen for (the outputs are the same bit for bit). A GPU pays
// for each dispatch, barrier and half-empty warp; a CPU rasterizer (llvmpipe) runs a shader's
// every instruction under lane masks and pays for a group barrier with a split shader.
enum class DeviceProfile {
  Auto,      // Software where GL_RENDERER names a CPU rasterizer (llvmpipe, softpipe, SwiftShader),
             // else Gpu
  Gpu,       // classification in groups of 64 (2x2 tiles) that also clear last frame's untraced
             // tiles and set the pyramid's dispatches: one pass where Software runs three; half
             // resolution's quad rays 4 tiles a group of 64. TraversalPass::Auto runs adaptive L
             // after the traversal inline
  Software,  // classification and the quad rays in groups of 16 (one tile, no barrier), the
             // clean-up and the pyramid's arguments as passes of their own; TraversalPass::Auto
             // chooses inline or deferred from the previous frame's counts
};

// ContextDesc::views at most (list entries keep their view in two bits).
inline constexpr int kMaxViews = 4;

struct ContextDesc {
  int width = 0;
  int height = 0;
  GetProcAddress getProcAddress = nullptr;
  LogCallback log;  // optional: shader compile logs, warnings
  DeviceProfile device = DeviceProfile::Auto;
  // Views traced in the same dispatches (1..kMaxViews: two for stereo, four for quad views). With
  // more than one, every input and output is a GL_TEXTURE_2D_ARRAY whose layer v is view v, and
  // frames go to dispatch(std::span<const FrameInputs>), one FrameInputs a view (integration.md,
  // "Stereo and multiview").
  int views = 1;
  // Pass shapes for timing and for hosts that know their device better (the answers are the same;
  // prepare() compiles what they choose): where adaptive L after the traversal runs, and
  // whether the traversal's walk and pixel tests share one loop body (a lane tests as soon as it
  // reaches a pixel) instead of two phases (results/gpu-h100.md).
  TraversalPass traversalPass = TraversalPass::Auto;
  bool oneBodyTraversal = false;
  // For timing on a GPU: FidelityFX SSSR's exit at low occupancy. Once the lanes of a subgroup
  // still walking the traversal are at most an eighth of those that began it (4 of a full 32-lane
  // subgroup; none of fewer than 8), they stop, and adaptive L resumes from there as at the step
  // cap (the traversal alone, Method::HierarchicalDepth, ends them as at its step cap). The
  // answers then depend on the neighbouring lanes and the subgroup size (8 on llvmpipe), so they
  // differ from the default's. Needs GL_ARB_shader_ballot and GL_ARB_gpu_shader_int64: create()
  // fails without them (docs/results/ray-work.md, "An exit at low occupancy").
  bool occupancyExit = false;
};

// The commands one pass of a frame recorded for the GPU, counted as dispatch() records them: the
// same on every device for the same inputs, settings and DeviceProfile (ContextDesc::traversalPass's
// Auto choice aside). A GPU pays for each dispatch and barrier even when its group counts are zero, so these
// are a frame's fixed costs, where the times below are its variable ones.
struct PassCommands {
  std::uint32_t dispatches = 0;          // glDispatchCompute
  std::uint32_t indirectDispatches = 0;  // glDispatchComputeIndirect (group counts from the GPU, zero included)
  std::uint32_t barriers = 0;            // glMemoryBarrier
  std::uint32_t programs = 0;            // glUseProgram
  std::uint32_t uploads = 0;             // buffer writes and copies and texture clears
};

// The texture memory one pass touched, from the frame's counts and the textures' formats: a model
// of what its shaders fetch and store, the same on every device (caches and compression aside).
// Texels: one per fetch or store (a gather counts its four texels, a bilinear read its four).
// Bytes: texels x their format's size. Where a count is not known on the CPU the model takes its
// bound (integration.md, "Cost" lists them). Buffers (tile lists, counters) are not counted.
struct PassTraffic {
  std::uint64_t texelsRead = 0, texelsWritten = 0;
  std::uint64_t bytesRead = 0, bytesWritten = 0;
};

// The ray work of a trace dispatch: what a GPU pays for its rays whatever its speed. A lane's
// steps are its tracer's iterations (adaptive L's probes, the traversal's cells and pixel tests):
// each one fetch whose result decides the next, so they form a dependent chain. SIMT hardware runs
// a group of 32 or 64 lanes as long as its slowest lane: simt32/simt64 sum each group's largest
// count, in the dispatch's real group shape. Counted on the GPU with a group barrier (stats only).
struct RayWork {
  std::uint64_t laneSteps = 0;    // the lanes' steps, summed
  std::uint64_t simt32 = 0;       // each 32-lane group's largest, summed
  std::uint64_t simt64 = 0;       // each 64-lane group's largest, summed
  std::uint32_t longestChain = 0; // the largest of any lane (the frame's: the dispatches' summed,
                                  // since each starts when the one before has finished)
  std::uint32_t groups = 0;       // work groups with a lane that traced
};

struct FrameStats {  // filled when Settings::debug.collectStats is set
  std::uint64_t frame = 0;          // the dispatch these are of (1 = the context's first; 0 = none yet)
  std::uint32_t tiles = 0;          // classified tiles that were traced
  std::uint32_t blurTiles = 0;      // tiles the roughness blur ran over
  std::uint32_t tracedPixels = 0;   // pixels that ran the tracer
  std::uint32_t fetches = 0;        // depth (or position) texels read by the trace pass
  std::uint32_t hierarchicalPixels = 0;  // traced pixels that ran the hierarchical traversal
  bool traversalDeferred = false;   // the second stage ran in a pass of its own (ContextDesc::traversalPass)
  bool followedEmptyFrame = false;  // the frame before listed no tile, so classification skipped
                                    // the pyramid's levels 0 and 1 and a pass of their own re-read
                                    // depth for them (only if this frame lists a tile)
  // GPU time between the passes from GL_TIMESTAMP queries (-1 where the GL has no timestamps).
  // On software renderers (llvmpipe) these measure the CPU doing the work, not a GPU.
  double classifyMs = -1.0;         // classification and clean-up
  double pyramidMs = -1.0;          // the depth pyramid (0 when the mode needs none)
  double traceMs = -1.0;            // the trace (half resolution: its three passes)
  double blurMs = -1.0;             // the roughness blur
  double temporalMs = -1.0;         // temporal reuse (0 when Settings::temporal is off)
  // The commands of the same passes; `finishCommands`: the frame's closing barrier and copies.
  PassCommands classifyCommands, pyramidCommands, traceCommands, blurCommands, temporalCommands, finishCommands;
  PassCommands totalCommands() const;  // the frame's: every pass's summed
  // The texture memory of the same passes (the finish pass touches none).
  PassTraffic classifyTraffic, pyramidTraffic, traceTraffic, blurTraffic, temporalTraffic;
  PassTraffic totalTraffic() const;  // the frame's: every pass's summed
  // The ray work of the trace dispatches: the full-resolution trace, the retrace of listed pixels
  // (deferred traversal, half resolution's own rays), half resolution's quad rays and their
  // deferred traversal (zero where a dispatch did not run).
  RayWork traceWork, retraceWork, quadWork, quadRetraceWork;
  RayWork totalRayWork() const;  // summed; longestChain: the frame's critical path through them
};

// How composite() puts the resolved reflection into the host's framebuffer.
enum class CompositeMode {
  // final = existing + reflection. For hosts with no other specular source for these pixels.
  Add,
  // final = existing - coverage * fallback + reflection: the framebuffer already holds the host's
  // fallback specular (probes, IBL, sky), given again as CompositeOptions::fallbackSpecularTexture;
  // where the trace answers (coverage) the reflection replaces it, elsewhere it stays. Equivalent
  // to blending reflection over fallback by coverage, without double-counting specular.
  BlendOverFallback,
};

struct CompositeOptions {
  CompositeMode mode = CompositeMode::Add;
  // BlendOverFallback only: the host's fallback specular radiance, already weighted by its BRDF
  // (what its lighting added to the framebuffer for reflections). rgb is read; the context's size.
  GLName fallbackSpecularTexture = 0;
  // The view to composite (ContextDesc::views > 1: one call a view, each into that view's
  // framebuffer; fallbackSpecularTexture is then that view's, a GL_TEXTURE_2D).
  int view = 0;
};

// Context::prepare's warm-up of composite(): its draw run once as the host will call it, into a
// scratch target of the format of `framebuffer`'s draw buffer 0 (the host's image is not written;
// the default framebuffer counts as RGBA8), reading `compositeOptions.fallbackSpecularTexture`.
struct PrepareOptions {
  bool composite = false;
  GLName framebuffer = 0;
  CompositeOptions compositeOptions;
};

class Context {
 public:
  static Expected<std::unique_ptr<Context>> create(const ContextDesc& desc);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  Status resize(int width, int height);
  int width() const;
  DeviceProfile device() const;  // the profile in use (Auto resolved at create())
  int height() const;

  // Traces, blurs and resolves one frame. The inputs stay the host's; sizes must match.
  Status dispatch(const FrameInputs& inputs, const Settings& settings);
  // The same for every view of a context made with ContextDesc::views = N, in the same dispatches:
  // `views` holds N FrameInputs, view v's matrices (clipFromView, viewFromWorld,
  // previousClipFromView) in views[v]. Every view names the same textures (2D arrays with at
  // least N layers, layer v = view v) and the same depth convention, surface layout, viewport,
  // exposure and historyReset. Each layer of the outputs is then what a one-view context given
  // that layer as its own textures writes.
  Status dispatch(std::span<const FrameInputs> views, const Settings& settings);
  int views() const;  // ContextDesc::views

  // Compiles every program dispatch() and composite() may use with these inputs and settings
  // (each variant a frame can choose: after an empty frame, with the traversal inline or in a pass
  // of its own) and runs each once on the inputs, since drivers finish compiling at first use for
  // the textures bound then: no frame pays for a compile (seconds with a cold driver cache, tens
  // of ms with a warm one: docs/integration.md). Call it at load time, with the inputs as they
  // will be dispatched: their projection and layout are validated, and which optional textures
  // are non-zero decides what is compiled in (their contents do not matter). Every program is
  // handed to the driver before any is waited on: a driver that compiles in parallel
  // (GL_KHR_parallel_shader_compile) builds them at once. Afterwards the context is as after
  // create(): outputs cleared, no temporal history, no frame to composite. Optional: dispatch
  // compiles what it needs on first use.
  Status prepare(const FrameInputs& inputs, const Settings& settings, const PrepareOptions& options = {});
  Status prepare(std::span<const FrameInputs> views, const Settings& settings, const PrepareOptions& options = {});

  // Puts the resolved reflection into colour attachment 0 of `framebuffer` (0 = default) over
  // (0, 0, width, height), by options.mode (see CompositeMode); its alpha is kept. Draws only the
  // tiles that had a reflective pixel (elsewhere coverage and reflection are 0).
  Status composite(GLName framebuffer, const CompositeOptions& options = {});

  // The production output: rgb = reflected radiance already weighted by Fresnel and coverage,
  // a = coverage (0..1, how much of the pixel's specular the trace answers), after the roughness
  // blur (which blurs both alike). Valid on the tiles a dispatch traced, 0 elsewhere. Every output
  // is a GL_TEXTURE_2D, or with ContextDesc::views > 1 a GL_TEXTURE_2D_ARRAY of one layer a view.
  GLName resolvedTexture() const;    // RGBA16F
  GLName reflectionTexture() const;  // RGBA16F, before the blur: rgb as above, a = blur weight
  GLName hitTexture() const;         // RGBA32F (debug.outputs): uvHit, confidence, L (the ray's
                                     // length in view units to the hit or the guess: |hit distance|;
                                     // 0 without either). Temporal reuse also writes it on the
                                     // traced tiles, for its own use. 0 until a dispatch with
                                     // debug.outputs or temporal created it
  GLName iterationsTexture() const;  // R32F (debug.outputs): adaptive-L iterations run; 0 until a
                                     // dispatch with debug.outputs created it
  // R32F (Settings::hitDistance): the reflected ray's length from the pixel's surface point to its
  // hit, in view units, where the pixel has a hit (coverage > 0); 0 (the sentinel: no hit, or not
  // traced) elsewhere. Negative where the answer is a guess (the ray went out of sight behind what
  // the screen shows, traversal.hiddenGuess): -(the length to where it
  // went out of sight), short of the true hit. This frame's ray, before the blur and temporal
  // reuse. 0 until a dispatch with hitDistance created it.
  GLName hitDistanceTexture() const;
  // R8 (Settings::temporal.outputConfidence): the history's share of each pixel's resolved value,
  // 0..temporal.historyWeight: 0 where history was not found (disocclusion, a camera cut, a new
  // rectangle, the first frame), historyWeight where it was fully trusted, a quarter of it on
  // curved mirrors. 0 until a dispatch with outputConfidence created it.
  GLName historyConfidenceTexture() const;
  // Stats never stall the pipeline: each dispatch with debug.collectStats records into a ring of 4
  // slots, and lastStats() returns the newest whose GPU work has finished (FrameStats::frame says
  // which dispatch; typically 1-3 frames back on a GPU). waitForStats() waits for the newest
  // dispatch's (a stall: for tools and tests). Both read GL objects: call them with the
  // Context's GL context current, like every other call.
  FrameStats lastStats() const;
  FrameStats waitForStats() const;

  struct Impl;

 private:
  explicit Context(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace sslr
