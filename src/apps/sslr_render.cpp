// sslr-render: headless render of a scene with Screen Space Local Reflections.
//   sslr-render [--scene NAME|FILE] [--size WxH] [--out DIR] [--dump] ...
// Exit codes: 0 success, 1 rendering/GL failure, 2 bad command line or input file.
#include <cxxopts.hpp>

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <type_traits>

#include "sslr_host/cost_model.hpp"
#include "sslr_host/egl_context.hpp"
#include "sslr_host/frame_renderer.hpp"
#include "sslr_host/views_renderer.hpp"
#include "sslr_host/gbuffer.hpp"
#include "sslr_host/gltf_writer.hpp"
#include "sslr_host/ground_truth.hpp"
#include "sslr_host/reference_image.hpp"
#include "sslr_host/image_io.hpp"
#include "sslr_host/scene.hpp"

namespace fs = std::filesystem;
using namespace sslr;
using namespace sslr::host;

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

struct UsageError {
  std::string message;
};

glm::dvec3 parseVec3(const std::string& option, const std::string& text) {
  glm::dvec3 v;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !in.eof() ||
      !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw UsageError{"--" + option + " expects three finite numbers x,y,z (got '" + text + "')"};
  return v;
}

double parsePositive(const std::string& option, const std::string& text) {
  std::istringstream in(text);
  double v = 0.0;
  if (!(in >> v) || !in.eof() || !(v > 0.0) || !std::isfinite(v))
    throw UsageError{"--" + option + " expects a positive number (got '" + text + "')"};
  return v;
}

void parseSize(const std::string& text, int& w, int& h) {
  std::istringstream in(text);
  char x = 0;
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || !in.eof() || w < 1 || h < 1 || w > 16384 || h > 16384)
    throw UsageError{"--size expects WxH with 1..16384 each (got '" + text + "')"};
}

// --out must be a directory we can write to: checked (and created) before any rendering, so a
// typo or a read-only place costs no render and leaves nothing behind.
// Its final image, too, may not be a device, fifo or socket; the other files are checked when they
// are written (writeFiles refuses them all, exit 2).
void checkOutputDirectory(const fs::path& dir, int views) {
  if (Status s = prepareOutputDirectory(dir.string()); !s) throw UsageError{"--out " + s.message()};
  for (int v = 0; v < views; ++v) {
    const fs::path final = dir / (views == 1 ? std::string("final.png") : "final-view" + std::to_string(v) + ".png");
    if (Status s = checkReplaceable(final.string()); !s) throw UsageError{"--out: " + s.message()};
  }
}

// A failed write: exit 2 where a target was refused (not a regular file), 1 otherwise.
int writeFailed(const Status& s) {
  std::cerr << "sslr-render: " << s.message() << "\n";
  return s.code() == StatusCode::InvalidInput ? kExitUsage : kExitFailure;
}

// What a size needs, estimated before anything is allocated: on llvmpipe every texture lives in
// system memory. Per pixel: G-buffer 16 B (+16 position) and the final RGBA8/RGBA16F targets,
// sslr's targets 51 B (reflection, blur, resolved, hit, iterations, pyramid, the deferred
// traversal's pixel list), the read-back float images and their encoded files (~30 B; ~250 B
// more with --dump); each of --views N has all of it (a layer of every target, its own image).
void checkMemory(int width, int height, int views, bool dump) {
  const double pixels = double(width) * height * views;
  const double need = pixels * (16.0 + 16.0 + 16.0 + 51.0 + 30.0 + (dump ? 250.0 : 0.0));
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double availableKiB = 0.0;
  while (meminfo >> key) {
    if (key == "MemAvailable:") {
      meminfo >> availableKiB;
      break;
    }
    meminfo.ignore(1 << 10, '\n');
  }
  if (availableKiB > 0.0 && need > 0.8 * availableKiB * 1024.0) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "--size %dx%d%s needs about %.1f GiB%s; %.1f GiB of memory are available (use a smaller size)",
                  width, height, views > 1 ? (" x " + std::to_string(views) + " views").c_str() : "",
                  need / double(1 << 30), dump ? " with --dump" : "", availableKiB / double(1 << 20));
    throw UsageError{text};
  }
}

// Prints each pass's commands (FrameStats::*Commands) on the current line.
void printPassCommands(const FrameStats& st) {
  const std::pair<const char*, const PassCommands*> passes[] = {
      {"classify", &st.classifyCommands}, {"pyramid", &st.pyramidCommands},   {"trace", &st.traceCommands},
      {"blur", &st.blurCommands},         {"temporal", &st.temporalCommands}, {"finish", &st.finishCommands}};
  for (const auto& [name, c] : passes)
    std::printf(" %s %u + %u / %u / %u / %u%s", name, c->dispatches, c->indirectDispatches, c->barriers, c->programs,
                c->uploads, name == passes[5].first ? "" : ",");
}

// Prints each pass's texture traffic (FrameStats::*Traffic) in MB on the current line, then the frame's.
void printPassTraffic(const FrameStats& st) {
  const std::pair<const char*, const PassTraffic*> passes[] = {{"classify", &st.classifyTraffic},
                                                              {"pyramid", &st.pyramidTraffic},
                                                              {"trace", &st.traceTraffic},
                                                              {"blur", &st.blurTraffic},
                                                              {"temporal", &st.temporalTraffic}};
  for (const auto& [name, t] : passes)
    std::printf(" %s %.2f / %.2f,", name, double(t->bytesRead) * 1e-6, double(t->bytesWritten) * 1e-6);
  const PassTraffic total = st.totalTraffic();
  std::printf(" frame %.2f / %.2f\n", double(total.bytesRead) * 1e-6, double(total.bytesWritten) * 1e-6);
}

// A numeric option, when given: the whole text must parse as the field's type.
template <typename T>
void numberOption(const cxxopts::ParseResult& args, const char* name, const char* kind, T& field) {
  if (!args.count(name)) return;
  const std::string text = args[name].as<std::string>();
  bool parsed = false;
  if constexpr (std::is_floating_point_v<T>) {  // "inf" and "nan" too, as the API takes them: validate() judges
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), field);
    parsed = error == std::errc() && end == text.data() + text.size() && !text.empty();
  } else {
    std::istringstream in(text);
    parsed = static_cast<bool>(in >> field) && in.eof();
  }
  if (!parsed) throw UsageError{"--" + std::string(name) + " expects " + kind + " (got '" + text + "')"};
}

Settings parseSettings(const cxxopts::ParseResult& args) {
  const std::string preset = args["preset"].as<std::string>();
  Settings s;
  if (preset == "low") s = Settings::preset(Preset::Low);
  else if (preset == "medium") s = Settings::preset(Preset::Medium);
  else if (preset == "high") s = Settings::preset(Preset::High);
  else if (preset == "ultra") s = Settings::preset(Preset::Ultra);
  else throw UsageError{"--preset must be low, medium, high or ultra (got '" + preset + "')"};
  const std::string fresnel = args["fresnel"].as<std::string>();
  if (fresnel == "classic") s.fresnel = FresnelMode::Classic;
  else if (fresnel == "schlick") s.fresnel = FresnelMode::Schlick;
  else throw UsageError{"--fresnel must be classic or schlick (got '" + fresnel + "')"};
  if (args.count("no-blur")) s.blur.maxRadiusPx = 0.0f;
  if (args.count("glossy")) {
    const std::string glossy = args["glossy"].as<std::string>();
    if (glossy == "cone") s.glossy.mode = GlossyMode::ConeBlur;
    else if (glossy == "stochastic") s.glossy.mode = GlossyMode::Stochastic;
    else throw UsageError{"--glossy must be cone or stochastic (got '" + glossy + "')"};
  }
  numberOption(args, "object-thickness", "a number", s.traversal.objectDepthRelative);
  numberOption(args, "hidden-guess", "a number in 0..1", s.traversal.hiddenGuess);
  numberOption(args, "max-luminance", "a number >= 0", s.radianceClamp.maxLuminance);
  numberOption(args, "ffx-thickness", "a number", s.ffx.depthBufferThickness);
  numberOption(args, "dda-thickness", "a number", s.dda.objectDepth);
  if (args.count("dda-stride")) {  // steps enough to cross about 1024 pixels, as sslr-bench's grid
    numberOption(args, "dda-stride", "a number >= 1", s.dda.stride);
    if (s.dda.stride >= 1.0f && s.dda.stride <= 1024.0f) s.dda.maxSteps = static_cast<int>(1024.0f / s.dda.stride);
  }
  numberOption(args, "error-k", "a number", s.fades.errorK);
  numberOption(args, "iterations", "an integer", s.adaptiveL.maxIterations);
  numberOption(args, "hiz-steps", "an integer", s.traversal.maxSteps);
  return s;  // validated by the caller, once every flag is applied
}

// Every option, with its help.
// The tracer's options: method, preset, caps, where the traversal runs, the thickness rules.
void addTracerOptions(cxxopts::Options& options) {
  options.add_options()
      ("method", "tracer: adaptive-l (depth-only SSLR, hierarchical fallback), hiz (the depth pyramid traversal alone), dda (McGuire & Mara 2014's screen-space DDA), ffx-sssr (AMD FidelityFX SSSR's hierarchical raymarch) or position-buffer (the tutorial's), for comparison, or none", cxxopts::value<std::string>()->default_value("adaptive-l"))
      ("no-hiz-fallback", "adaptive-l alone, without the hierarchical traversal where it finds nothing")
      ("preset", "quality preset: low, medium, high, ultra", cxxopts::value<std::string>()->default_value("high"))
      ("fresnel", "weighting: classic (the article) or schlick", cxxopts::value<std::string>()->default_value("classic"))
      ("iterations", "override the preset's adaptive-L iteration cap", cxxopts::value<std::string>())
      ("hiz-steps", "override the preset's cap on hierarchical traversal steps (0: adaptive L alone)", cxxopts::value<std::string>())
      ("traversal-pass", "where adaptive L after the hierarchical traversal runs: auto (deferred on a software "
                         "renderer), inline or deferred (a pass of its own); the hits are the same "
                         "(ContextDesc::traversalPass)",
       cxxopts::value<std::string>())
      ("device-profile", "sslr's pass shapes: auto (software on a CPU rasterizer, else gpu), gpu or software; the "
                         "outputs are the same", cxxopts::value<std::string>())
      ("no-blur", "skip the roughness blur")
      ("glossy", "rough surfaces: cone (the mirror reflection blurred over the roughness cone, the default) or "
                 "stochastic (rays drawn from the GGX lobe, resolved by the blur and --temporal)",
       cxxopts::value<std::string>())
      ("composite", "how the reflection enters final.png: blend (over the fallback specular, a sky/ground environment, by coverage) or add (on top of it)",
       cxxopts::value<std::string>()->default_value("blend"))
      ("half-res", "one ray per 2x2 quad, reused by the quad's pixels on the same surface")
      ("one-body-traversal", "the traversal's walk and pixel tests in one loop body (for timing on a GPU; the "
                             "same hits: ContextDesc::oneBodyTraversal)")
      ("occupancy-exit", "stop the traversal of a subgroup's lanes once at most an eighth of those that began still "
                         "walk, adaptive L resuming there (for timing on a GPU; other hits: ContextDesc::occupancyExit)")
      ("error-k", "classic Fresnel's error term: weight 1 - saturate(L / distance x K) (default 0.15; 0 = off)",
       cxxopts::value<std::string>())
      ("hidden-guess", "a ray that ends without a hit where it went out of sight (behind what the screen shows, "
                       "or into an object's assumed thickness) gets the colour where it did, at this weight 0..1 "
                       "(Settings::traversal.hiddenGuess; 0.5 in every preset, 0 = a miss)",
       cxxopts::value<std::string>())
      ("max-luminance", "HDR-safe radiance: hit colours brighter than this luminance (display units) are scaled "
                        "down to it before the blur and temporal reuse (Settings::radianceClamp; default 0 = off)",
       cxxopts::value<std::string>())
      ("ffx-thickness", "--method ffx-sssr: FidelityFX SSSR's depth buffer thickness, view units (default 0.015, "
                        "its sample's)", cxxopts::value<std::string>())
      ("dda-stride", "--method dda: pixels per step (default 2), with steps enough to cross about 1024 pixels "
                     "(sslr-bench's grid)", cxxopts::value<std::string>())
      ("dda-thickness", "--method dda: depth assumed behind every visible surface, view units (default 0.5)",
       cxxopts::value<std::string>())
      ("object-thickness", "assumed depth of what the screen shows, fraction of its view depth (hierarchical traversal)", cxxopts::value<std::string>());
}

cxxopts::Options renderOptions() {
  cxxopts::Options options("sslr-render", "Headless render with Screen Space Local Reflections (depth-only SSLR).");
  std::string sceneHelp = "built-in scene (";
  for (const auto& n : builtinSceneNames()) sceneHelp += n + (n == builtinSceneNames().back() ? "" : ", ");
  for (const auto& n : assetSceneNames()) sceneHelp += ", " + n;
  sceneHelp += ", reflective-N for N% of the screen reflecting) or a .gltf/.glb file";
  options.add_options()
      ("scene", sceneHelp, cxxopts::value<std::string>()->default_value("mirror-room"))
      ("size", "output size WxH", cxxopts::value<std::string>()->default_value("960x540"))
      ("out", "output directory", cxxopts::value<std::string>()->default_value("out"))
      ("dump", "also write every buffer as EXR (color, normal, depth, position, hit, reflection, iterations, resolved)");
  addTracerOptions(options);
  options.add_options()
      ("depth", "depth convention: reversed, reversed-infinite, zero-to-one, gl-default",
       cxxopts::value<std::string>()->default_value("reversed"))
      ("normals", "normal packing: octahedral (RGBA16) or xyz (RGBA8, the article's)",
       cxxopts::value<std::string>()->default_value("octahedral"))
      ("eye", "camera position x,y,z", cxxopts::value<std::string>())
      ("target", "camera target x,y,z", cxxopts::value<std::string>())
      ("up", "camera up x,y,z", cxxopts::value<std::string>())
      ("fovy", "vertical field of view, degrees", cxxopts::value<std::string>())
      ("near", "near plane distance", cxxopts::value<std::string>())
      ("far", "far plane distance", cxxopts::value<std::string>())
      ("ortho", "orthographic camera with this view height", cxxopts::value<std::string>())
      ("device", "EGL device: auto, hardware, software, surfaceless or an index (default $SSLR_EGL_DEVICE or auto)",
       cxxopts::value<std::string>()->default_value(""))
      ("back-depth", "also render the back-face depth (front faces culled) and hand it to sslr "
                     "(FrameInputs::backDepthTexture): measured object thickness instead of --object-thickness")
      ("stage", "stage the scene's model for reflections: on-mirror (a mirror floor, a wall and boxes around it, a "
                "low camera) or as-mirror (the same, every material of the model a sharp mirror, seen from above)",
       cxxopts::value<std::string>())
      ("export-gltf", "write the scene (with the camera as given) as a self-contained glTF 2.0 file and exit, without rendering", cxxopts::value<std::string>())
      ("stats", "print tiles, traced pixels and depth (or position) fetches")
      ("frames", "render the same view N times; with --stats the pass times are the median of frames 2..N "
                 "(the first compiles shaders)", cxxopts::value<int>()->default_value("1"))
      ("temporal", "temporal reuse (Settings::temporal) from the second frame on")
      ("views", "views traced in the same dispatches by one context (ContextDesc::views, 1..4): cameras side by "
                "side along the camera's right axis, --eye-separation apart; writes DIR/final-viewN.png",
       cxxopts::value<std::string>()->default_value("1"))
      ("eye-separation", "--views: distance between neighbouring views' cameras, view units (default 0.064)",
       cxxopts::value<std::string>())
      ("no-prepare", "skip Context::prepare() before the first frame (to see the compile hitch it removes; --stats times both)")
      ("score", "score the traced hits against Embree ground truth (recall, error, false hits), print them and write DIR/error.png (and DIR/truth.exr with --dump)")
      ("h,help", "show this help");
  return options;
}

// What one run renders and writes, from the command line.
struct RenderJob {
  GBufferOptions gopt;
  Settings settings;
  bool reflections = true;
  CompositeMode compositeMode = CompositeMode::BlendOverFallback;
  Camera camera;
  Scene scene;
  fs::path outDir;
  bool dump = false, score = false;
  int frames = 1;
  int views = 1;                                    // --views: one context of this many views
  double eyeSeparation = 0.064;                     // --eye-separation
  bool prepare = true;                              // Context::prepare() before the first frame
  std::string device;                               // EGL device (--device)
  ContextDesc shapes;  // sslr's pass shapes (--device-profile, --traversal-pass, --one-body-traversal)
};

// --views and --eye-separation (throws UsageError).
void parseViews(const cxxopts::ParseResult& args, RenderJob& job) {
  const std::string views = args["views"].as<std::string>();
  if (views.size() != 1 || views[0] < '1' || views[0] > char('0' + kMaxViews))
    throw UsageError{"--views must be 1.." + std::to_string(kMaxViews) + " (got '" + views + "')"};
  job.views = views[0] - '0';
  if (args.count("eye-separation")) {
    if (job.views == 1) throw UsageError{"--eye-separation needs --views 2 or more"};
    job.eyeSeparation = parsePositive("eye-separation", args["eye-separation"].as<std::string>());
  }
  if (job.views > 1 && (job.dump || job.score))
    throw UsageError{"--views writes each view's final image only: --dump and --score need one view"};
}

// The G-buffer layout, the tracer and its settings (throws UsageError).
void parseTracing(const cxxopts::ParseResult& args, RenderJob& job) {
  parseSize(args["size"].as<std::string>(), job.gopt.width, job.gopt.height);
  if (!parseDepthMode(args["depth"].as<std::string>(), job.gopt.depth))
    throw UsageError{"--depth must be reversed, reversed-infinite, zero-to-one or gl-default (got '" +
                     args["depth"].as<std::string>() + "')"};
  const std::string normals = args["normals"].as<std::string>();
  if (normals == "octahedral") job.gopt.normals = NormalEncoding::Octahedral;
  else if (normals == "xyz") job.gopt.normals = NormalEncoding::XyzUnorm;
  else throw UsageError{"--normals must be octahedral or xyz (got '" + normals + "')"};
  job.gopt.withBackDepth = args.count("back-depth") > 0;
  Settings& settings = job.settings;
  settings = parseSettings(args);
  if (args.count("device-profile")) {
    const std::string profile = args["device-profile"].as<std::string>();
    if (profile == "auto") job.shapes.device = DeviceProfile::Auto;
    else if (profile == "gpu") job.shapes.device = DeviceProfile::Gpu;
    else if (profile == "software") job.shapes.device = DeviceProfile::Software;
    else throw UsageError{"--device-profile must be auto, gpu or software (got '" + profile + "')"};
  }
  if (args.count("traversal-pass")) {
    const std::string pass = args["traversal-pass"].as<std::string>();
    if (pass == "auto") job.shapes.traversalPass = TraversalPass::Auto;
    else if (pass == "inline") job.shapes.traversalPass = TraversalPass::Inline;
    else if (pass == "deferred") job.shapes.traversalPass = TraversalPass::Deferred;
    else throw UsageError{"--traversal-pass must be auto, inline or deferred (got '" + pass + "')"};
  }
  const std::string method = args["method"].as<std::string>();
  if (method == "none") {
    job.reflections = false;
  } else if (method == "position-buffer") {
    settings.method = Method::PositionBuffer;
    job.gopt.withPosition = true;  // its G-buffer adds an RGBA32F view-space position texture
  } else if (method == "hiz") {
    settings.method = Method::HierarchicalDepth;
  } else if (method == "dda") {
    settings.method = Method::ScreenSpaceDDA;
  } else if (method == "ffx-sssr") {
    settings.method = Method::FidelityFxSssr;
  } else if (method != "adaptive-l") {
    throw UsageError{"--method must be adaptive-l, hiz, dda, ffx-sssr, position-buffer or none (got '" + method + "')"};
  }
  const std::string composite = args["composite"].as<std::string>();
  if (composite == "blend") job.compositeMode = CompositeMode::BlendOverFallback;
  else if (composite == "add") job.compositeMode = CompositeMode::Add;
  else throw UsageError{"--composite must be blend or add (got '" + composite + "')"};
  if (args.count("no-hiz-fallback")) settings.traversal.maxSteps = 0;  // adaptive L alone: no traversal
  if (args.count("half-res")) settings.halfResolution = true;
  if (args.count("one-body-traversal")) job.shapes.oneBodyTraversal = true;
  if (args.count("occupancy-exit")) job.shapes.occupancyExit = true;
  settings.debug.outputs = job.dump || job.score;
  settings.debug.collectStats = args.count("stats") > 0;
  if (args.count("temporal")) settings.temporal.enabled = true;
  if (std::string why = validate(settings); !why.empty()) throw UsageError{why};  // after every flag
  job.frames = args["frames"].as<int>();
  job.prepare = args.count("no-prepare") == 0;
  if (job.frames < 1 || job.frames > 10000)
    throw UsageError{"--frames must be 1..10000 (got " + std::to_string(job.frames) + ")"};
  parseViews(args, job);
  checkMemory(job.gopt.width, job.gopt.height, job.views, job.dump);
}

// The scene (loaded, staged) and the camera (throws UsageError).
void parseScene(const cxxopts::ParseResult& args, RenderJob& job) {
  auto loaded = loadScene(args["scene"].as<std::string>());
  if (!loaded) throw UsageError{loaded.error()};
  Scene& scene = job.scene;
  scene = std::move(loaded.value());
  for (const auto& w : scene.warnings) std::cerr << "sslr-render: warning: " << w << "\n";
  if (args.count("stage")) {
    const std::string stage = args["stage"].as<std::string>();
    if (stage != "on-mirror" && stage != "as-mirror")
      throw UsageError{"--stage must be on-mirror or as-mirror (got '" + stage + "')"};
    auto staged = stageModel(std::move(scene), stage == "on-mirror" ? ModelStage::OnMirror : ModelStage::AsMirror);
    if (!staged) throw UsageError{"--stage: " + staged.error()};
    scene = std::move(staged.value());
  }
  if (std::string why = scene.checkExtent(); !why.empty()) throw UsageError{args["scene"].as<std::string>() + ": " + why};
  Camera& camera = job.camera;
  camera = scene.camera ? *scene.camera : scene.defaultCamera();
  if (args.count("eye")) camera.eye = parseVec3("eye", args["eye"].as<std::string>());
  if (args.count("target")) camera.target = parseVec3("target", args["target"].as<std::string>());
  // A moved camera sees the scene from elsewhere: its clip planes are fitted to the scene as seen
  // from the new eye (the scene's own planes would clip a close look at a small model away).
  if (args.count("eye") || args.count("target")) fitClipPlanes(camera, scene.worldBounds());
  if (args.count("up")) camera.up = parseVec3("up", args["up"].as<std::string>());
  if (args.count("fovy")) camera.fovyDegrees = parsePositive("fovy", args["fovy"].as<std::string>());
  if (args.count("near")) camera.nearPlane = parsePositive("near", args["near"].as<std::string>());
  if (args.count("far")) camera.farPlane = parsePositive("far", args["far"].as<std::string>());
  if (args.count("ortho")) {
    camera.orthographic = true;
    camera.orthoHeight = parsePositive("ortho", args["ortho"].as<std::string>());
  }
  if (std::string why = camera.validate(); !why.empty()) throw UsageError{"camera: " + why};
  if (job.views > 1)  // each eye, --eye-separation apart, must be a camera too
    for (const Camera& eye : sideBySideCameras(camera, job.views, job.eyeSeparation))
      if (std::string why = eye.validate(); !why.empty())
        throw UsageError{(std::ostringstream() << "--eye-separation " << job.eyeSeparation << ": an eye's camera: " << why).str()};
}

// --export-gltf: the scene with the camera as given, instead of rendering.
int exportGltf(const RenderJob& job, const std::string& file) {
  Scene exported = job.scene;
  exported.camera = job.camera;
  auto text = gltfFromScene(exported);
  if (!text) {
    std::cerr << "sslr-render: --export-gltf: " << text.error() << "\n";
    return kExitUsage;
  }
  if (Status st = writeFiles({{file, std::vector<unsigned char>(text.value().begin(), text.value().end())}}); !st)
    return writeFailed(st);
  std::cout << "wrote " << file << "\n";
  return 0;
}

using NamedImages = std::vector<std::pair<std::string, std::pair<Image, std::vector<std::string>>>>;

// final.png, and with --dump every buffer as EXR.
NamedImages collectImages(const RenderJob& job, FrameRenderer& r) {
  NamedImages files;
  files.push_back({"final.png", {r.readFinal(), {}}});
  if (!job.dump) return files;
  GBuffer& g = r.gbuffer();
  const Image depth = g.readDepth();
  files.push_back({"color.exr", {g.readColor(), {"R", "G", "B"}}});
  files.push_back({"fallback.exr", {g.readFallbackSpecular(), {"R", "G", "B"}}});
  files.push_back({"normal.exr", {decodeNormals(g.readNormalPacked(), job.gopt.normals), {"R", "G", "B"}}});
  files.push_back({"depth.exr", {depth, {"Z"}}});
  if (job.gopt.withBackDepth) files.push_back({"back-depth.exr", {g.readBackDepth(), {"Z"}}});
  files.push_back({"position.exr",
                   {reconstructPositions(depth, g.clipFromView(), depthConvention(job.gopt.depth)), {"R", "G", "B", "A"}}});
  if (job.reflections) {
    files.push_back({"hit.exr", {r.readHit(), {"R", "G", "B", "A"}}});
    files.push_back({"reflection.exr", {r.readReflection(), {"R", "G", "B", "A"}}});
    files.push_back({"iterations.exr", {r.readIterations(), {"Y"}}});
    files.push_back({"resolved.exr", {r.readResolved(), {"R", "G", "B", "A"}}});
  }
  return files;
}

// Every file encoded first, then all written under temporary names and renamed into place: a
// failed write (disk full) leaves no partial output behind.
Status writeImages(const NamedImages& files, const fs::path& outDir) {
  std::vector<std::pair<std::string, std::vector<unsigned char>>> encoded;
  for (const auto& [name, image] : files) {
    auto bytes = encodeImage((outDir / name).string(), image.first, image.second);
    if (!bytes) return Status::error(bytes.error());
    encoded.emplace_back((outDir / name).string(), std::move(bytes.value()));
  }
  return writeFiles(encoded);
}

// --stats: tiles, traced pixels, fetches, the commands per pass, and the pass times.
void printStats(const FrameStats& st, const std::vector<FrameStats>& laterStats, int frames, bool software,
                DeviceProfile profile, const ContextDesc& shapes, const Settings& settings) {
  std::cout << "  tiles " << st.tiles << " (blurred " << st.blurTiles << "), traced pixels " << st.tracedPixels << ", fetches "
            << st.fetches << " (" << (st.tracedPixels ? double(st.fetches) / st.tracedPixels : 0.0)
            << " per traced pixel), hierarchical traversal on " << st.hierarchicalPixels << " ("
            << (st.tracedPixels ? 100.0 * st.hierarchicalPixels / st.tracedPixels : 0.0) << "% of traced"
            << (st.hierarchicalPixels ? (st.traversalDeferred ? ", in a pass of its own" : ", inline") : "") << ")"
            << (st.followedEmptyFrame ? "; the pyramid's level 1 in a pass of its own (the frame before listed no tile)" : "")
            << "\n";
  // The commands each pass recorded (the same on every device of a profile: what a GPU pays for
  // per frame).
  std::printf("  commands (%s profile; dispatches + indirect / barriers / programs / uploads):",
              profile == DeviceProfile::Gpu ? "gpu" : "software");
  printPassCommands(st);
  const PassCommands total = st.totalCommands();
  std::printf("; frame %u + %u / %u / %u / %u\n", total.dispatches, total.indirectDispatches, total.barriers,
              total.programs, total.uploads);
  // The ray work per trace dispatch (FrameStats::RayWork): what SIMT hardware pays for the rays.
  std::printf("  ray work (dependent steps; lanes / 32-lane groups' slowest / 64-lane groups' slowest / longest chain):");
  const std::pair<const char*, const RayWork*> work[] = {
      {"trace", &st.traceWork}, {"retrace", &st.retraceWork}, {"quads", &st.quadWork}, {"quad retrace", &st.quadRetraceWork}};
  for (const auto& [name, w] : work)
    if (w->groups > 0)
      std::printf(" %s %llu / %llu / %llu / %u,", name, static_cast<unsigned long long>(w->laneSteps),
                  static_cast<unsigned long long>(w->simt32), static_cast<unsigned long long>(w->simt64), w->longestChain);
  const RayWork frameWork = st.totalRayWork();
  std::printf(" frame %llu / %llu / %llu / %u (%.1f steps per traced pixel)\n",
              static_cast<unsigned long long>(frameWork.laneSteps), static_cast<unsigned long long>(frameWork.simt32),
              static_cast<unsigned long long>(frameWork.simt64), frameWork.longestChain,
              st.tracedPixels ? double(frameWork.laneSteps) / st.tracedPixels : 0.0);
  // What that work would cost an H100 (the model fitted to one; sslr_host/cost_model.hpp).
  if (const std::optional<double> ms = predictedH100FrameMs(frameShapeOf(settings, profile, shapes, st), frameWork))
    std::printf("  predicted on an NVIDIA H100 (ray-work model, docs/results/gpu-h100.md): %.3f ms a frame\n", *ms);
  else
    std::printf("  predicted on an NVIDIA H100: not for this frame's shape (the model is fitted to the gpu profile, "
                "full resolution, the traversal inline in two phases without the occupancy exit; --device-profile gpu)\n");
  // The texture memory each pass touched (FrameStats::*Traffic: a model from the counts and formats).
  std::printf("  texture traffic (MB read / written, modelled):");
  printPassTraffic(st);
  if (st.classifyMs >= 0.0 && laterStats.empty())
    std::printf("  pass times (GL_TIMESTAMP%s): classify %.2f ms, pyramid %.2f ms, trace %.2f ms, blur %.2f ms\n",
                software ? "; a software renderer: CPU work; the first frame, with shader compilation"
                         : "; the first frame, with shader compilation",
                st.classifyMs, st.pyramidMs, st.traceMs, st.blurMs);
  if (st.classifyMs >= 0.0 && !laterStats.empty()) {
    auto median = [&](double FrameStats::*field) {
      std::vector<double> v;
      for (const FrameStats& f : laterStats) v.push_back(f.*field);
      std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    std::printf("  pass times (GL_TIMESTAMP, median of frames 2..%d%s): classify %.3f ms, pyramid %.3f ms, "
                "trace %.3f ms, blur %.3f ms, temporal %.3f ms\n",
                frames, software ? "; a software renderer: CPU work" : "", median(&FrameStats::classifyMs),
                median(&FrameStats::pyramidMs), median(&FrameStats::traceMs), median(&FrameStats::blurMs),
                median(&FrameStats::temporalMs));
  }
}

// --stats: what prepare() took, and the frames after it (G-buffer, trace, composite), wall clock
// around glFinish: the first frame is the one a load-time prepare() should leave no hitch in.
struct FrameTimes {
  double prepareMs = -1.0;
  std::vector<double> frameMs;
};
double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}
void printFrameTimes(const FrameTimes& t) {
  if (t.frameMs.empty()) return;
  if (t.prepareMs >= 0.0) std::printf("  frame times (wall clock around glFinish): prepare() %.1f ms,", t.prepareMs);
  else std::printf("  frame times (wall clock around glFinish): prepare() skipped (--no-prepare),");
  std::printf(" first frame %.1f ms", t.frameMs.front());
  if (t.frameMs.size() > 1) {
    std::vector<double> later(t.frameMs.begin() + 1, t.frameMs.end());
    std::nth_element(later.begin(), later.begin() + static_cast<long>(later.size() / 2), later.end());
    std::printf(", later frames median %.1f ms (%zu frames)", later[later.size() / 2], later.size());
  }
  std::printf("\n");
}

// RGB of `image` with alpha 1 where `scored` marks a compared pixel, else 0.
Image withScoredAlpha(const Image& image, const std::vector<std::uint8_t>& scored) {
  Image out;
  out.width = image.width;
  out.height = image.height;
  out.channels = 4;
  out.pixels.resize(static_cast<size_t>(image.width) * image.height * 4);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const size_t i = static_cast<size_t>(y) * image.width + x;
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = c < image.channels ? image.at(x, y, c) : 0.0f;
      out.at(x, y, 3) = i < scored.size() && scored[i] != 0 ? 1.0f : 0.0f;
    }
  return out;
}

// --score: the hits against Embree's truth and, for a weighted composite over the fallback, the
// final image against the ray-traced reference (the reference replaces that fallback).
struct Scores {
  std::optional<HitMetrics> hits;
  std::optional<ImageError> composite;
  std::optional<CompositeBreakdown> breakdown;
};

// Scores the frame `r` rendered (one Embree scene for the truth and the reference) and adds the
// error images to `files`.
Expected<Scores> scoreFrame(const RenderJob& job, FrameRenderer& r, NamedImages& files) {
  auto tracer = RayTracer::create(job.scene, r.gbuffer().viewFromWorld());
  if (!tracer) return Status::error("ground truth: " + tracer.error());
  const GroundTruth truth = groundTruthFor(*tracer.value(), r.gbuffer(), job.settings);
  Scores scores;
  const Image color = r.gbuffer().readColor(), hit = r.readHit();
  scores.hits = compareHits(truth, hit, kReportedConfidence, &color);
  files.push_back({"error.png", {hitErrorImage(truth, hit), {}}});
  if (job.dump) files.push_back({"truth.exr", {truthImage(truth), {"R", "G", "B", "A"}}});
  if (job.compositeMode == CompositeMode::BlendOverFallback && job.settings.output == OutputMode::Weighted) {
    const ReferenceImage reference = referenceComposite(job.scene, *tracer.value(), r.gbuffer(), truth);
    const Image final = r.readFinal();
    scores.composite = compositeError(reference, final);
    scores.breakdown = compositeBreakdown(reference, final, truth, hit, color);  // a miss shows the colour
    files.push_back({"reference.png", {reference.composite, {}}});
    files.push_back({"composite-error.png", {compositeErrorMap(reference, final), {}}});
    if (job.dump) {  // the compared images in linear float, A = 1 on the scored pixels
      files.push_back({"reference.exr", {withScoredAlpha(reference.composite, reference.scored), {"R", "G", "B", "A"}}});
      files.push_back({"final.exr", {withScoredAlpha(final, reference.scored), {"R", "G", "B", "A"}}});
    }
  }
  return scores;
}

// The truth's classes and the scores.
void printScores(const Scores& scores) {
  if (!scores.hits) return;
  const HitMetrics& m = *scores.hits;
  std::printf("  truth: %zu visible (A; %zu of them shown by no pixel within 1 px), %zu occluded (B), %zu off "
              "screen (C), %zu escaped (D)\n",
              m.visible, m.unshown, m.occluded, m.offScreen, m.escaped);
  std::printf("  recall@1px %.4f (of the shown: %.4f) @2px %.4f @4px %.4f  median %.3f px  p95 %.3f px  false hits "
              "%.4f (%.4f beyond 1 px of the true hit)  reflection RMSE %.4f  non-finite %zu\n",
              m.recall1px, m.recallShown1px, m.recall2px, m.recall4px, m.medianErrorPx, m.p95ErrorPx, m.falseHitRate,
              m.falseHitRateBeyond1px, m.reflectionRmse, m.nonFinite);
  if (scores.composite && scores.composite->pixels == 0)
    std::printf("  composite against the ray-traced reference: no mirror pixel to score\n");
  else if (scores.composite)
    std::printf("  composite against the ray-traced reference: RMSE %.4f, PSNR %.1f dB over %zu mirror pixels\n",
                scores.composite->rmse, scores.composite->psnr, scores.composite->pixels);
  if (!scores.breakdown) return;
  const CompositeBreakdown& b = *scores.breakdown;
  std::printf("  its error by pixel (RMSE, share of the squared error, pixels):");
  const std::pair<const char*, const CompositeBreakdown::Kind*> kinds[] = {
      {"hits within 1 px", &b.hit}, {"wrong hits", &b.wrong}, {"guesses", &b.guessed}, {"missed", &b.missed},
      {"unreachable", &b.unreachable}};
  for (const auto& [name, k] : kinds) std::printf(" %s %.4f, %.0f%%, %zu;", name, k->rmse, 100.0 * k->share, k->pixels);
  std::printf("\n  by where the true reflection lies (the same):");
  const CompositeBreakdown::ByTruth& t = b.byTruth;
  const std::pair<const char*, const CompositeBreakdown::Kind*> truths[] = {
      {"on the screen", &t.visible}, {"a hidden side", &t.occluded}, {"off the screen", &t.offScreen},
      {"escaped", &t.escaped}};
  for (const auto& [name, k] : truths) std::printf(" %s %.4f, %.0f%%, %zu;", name, k->rmse, 100.0 * k->share, k->pixels);
  std::printf("\n");
  if (b.wrong.pixels > 0)
    std::printf("  the wrong hits' pixels as misses (the fallback instead): RMSE %.4f, %.0f%% of today's squared error\n",
                b.wrongAsMisses.rmse, 100.0 * b.wrongAsMisses.share);
}

// A frame in which no pixel shows the scene (a model scaled to nothing, a zero node scale, only
// degenerate triangles, a camera looking away) renders the background alone: said, not silent.
void warnIfNothingShows(const RenderJob& job, const GBuffer& gbuffer) {
  if (!gbuffer.showsNothing(gbuffer.readDepth())) return;
  std::cerr << "sslr-render: warning: no pixel of the " << job.gopt.width << "x" << job.gopt.height << " frame shows "
            << job.scene.name << " (" << job.scene.triangleCount() << " triangles): the geometry projects to nothing "
            << "from this camera (a zero or tiny scale, degenerate triangles, or a camera looking away); the images "
            << "show the background alone\n";
}

// The job's prepare() (when tracing) and frames, through one renderer's `prepare` and `frame`
// calls; with --stats each frame is timed and every frame's stats after the first kept.
template <typename Prepare, typename Frame>
Status runFrames(const RenderJob& job, Context& ctx, Prepare&& prepare, Frame&& frame, FrameTimes& times,
                 std::vector<FrameStats>& laterStats) {
  const bool stats = job.settings.debug.collectStats && job.reflections;
  // As an engine does at load time: every program compiled and run once before the first frame.
  if (job.reflections && job.prepare) {
    const auto start = std::chrono::steady_clock::now();
    if (Status s = prepare(); !s) return s;
    times.prepareMs = millisecondsSince(start);
  }
  for (int k = 0; k < job.frames; ++k) {
    const auto start = std::chrono::steady_clock::now();
    if (Status s = frame(); !s) return s;
    if (stats) {
      glFinish();
      times.frameMs.push_back(millisecondsSince(start));
    }
    if (k > 0 && stats) laterStats.push_back(ctx.waitForStats());  // (the first compiles the shaders)
  }
  return {};
}

// --views N: every view's G-buffer, one dispatch of a context of N views, each view's composite
// (without a tracer: each view's lit colour).
int renderViews(const RenderJob& job, HeadlessContext& gl) {
  auto renderer = ViewsRenderer::create(job.gopt, job.views, nullptr, job.shapes);
  if (!renderer) {
    std::cerr << "sslr-render: " << renderer.error() << "\n";
    return kExitFailure;
  }
  ViewsRenderer& r = *renderer.value();
  GpuScene gpuScene(job.scene);
  const std::vector<Camera> cameras = sideBySideCameras(job.camera, job.views, job.eyeSeparation);
  const Settings* settings = job.reflections ? &job.settings : nullptr;
  const bool stats = job.settings.debug.collectStats && job.reflections;
  FrameTimes times;
  std::vector<FrameStats> laterStats;
  if (Status s = runFrames(
          job, r.sslr(), [&] { return r.prepare(gpuScene, cameras, job.settings); },
          [&] { return r.render(gpuScene, cameras, settings); }, times, laterStats);
      !s) {
    std::cerr << "sslr-render: " << s.message() << "\n";
    return kExitFailure;
  }
  for (int v = 0; v < job.views; ++v) warnIfNothingShows(job, r.gbuffer(v));
  NamedImages files;
  for (int v = 0; v < job.views; ++v)
    files.push_back({"final-view" + std::to_string(v) + ".png", {r.readFinal(v), {}}});
  if (gl.glErrorCount() > 0) {
    std::cerr << "sslr-render: " << gl.glErrorCount() << " GL error(s) were reported; no output written\n";
    return kExitFailure;
  }
  if (Status s = writeImages(files, job.outDir); !s) return writeFailed(s);
  std::cout << "sslr-render: " << job.scene.name << " " << job.views << " views of " << job.gopt.width << "x"
            << job.gopt.height << " (" << toString(job.gopt.depth) << " depth, " << job.scene.triangleCount()
            << " triangles) -> " << (job.outDir / "final-view0.png").string() << " .. final-view" << job.views - 1
            << ".png\n";
  if (stats) {
    printStats(r.sslr().waitForStats(), laterStats, job.frames, gl.isSoftware(), r.sslr().device(), job.shapes,
               job.settings);
    printFrameTimes(times);
  }
  return 0;
}

// Renders the job's frames, scores them if asked, writes the images and prints the summary.
int render(const RenderJob& job) {
  EglOptions eopt;
  eopt.device = job.device;
  auto gl = HeadlessContext::create(eopt);
  if (!gl) {
    std::cerr << "sslr-render: cannot create a headless OpenGL 4.5 context: " << gl.error() << "\n";
    return kExitFailure;
  }
  if (job.views > 1) return renderViews(job, *gl.value());
  auto renderer = FrameRenderer::create(job.gopt, nullptr, job.shapes);
  if (!renderer) {
    std::cerr << "sslr-render: " << renderer.error() << "\n";
    return kExitFailure;
  }
  FrameRenderer& r = *renderer.value();
  r.setCompositeMode(job.compositeMode);
  GpuScene gpuScene(job.scene);
  const Settings* settings = job.reflections ? &job.settings : nullptr;
  const bool stats = job.settings.debug.collectStats && job.reflections;
  FrameTimes times;
  std::vector<FrameStats> laterStats;
  if (Status s = runFrames(
          job, r.sslr(), [&] { return r.prepare(gpuScene, job.camera, job.settings); },
          [&] { return r.render(gpuScene, job.camera, settings); }, times, laterStats);
      !s) {
    std::cerr << "sslr-render: " << s.message() << "\n";
    return kExitFailure;
  }
  warnIfNothingShows(job, r.gbuffer());
  NamedImages files = collectImages(job, r);
  Scores scores;
  if (job.score && job.reflections) {
    auto scored = scoreFrame(job, r, files);
    if (!scored) {
      std::cerr << "sslr-render: " << scored.error() << "\n";
      return kExitFailure;
    }
    scores = scored.value();
  }
  if (gl.value()->glErrorCount() > 0) {
    std::cerr << "sslr-render: " << gl.value()->glErrorCount() << " GL error(s) were reported; no output written\n";
    return kExitFailure;
  }
  if (Status s = writeImages(files, job.outDir); !s) return writeFailed(s);
  std::cout << "sslr-render: " << job.scene.name << " " << job.gopt.width << "x" << job.gopt.height << " ("
            << toString(job.gopt.depth) << " depth, " << job.scene.triangleCount() << " triangles) -> "
            << (job.outDir / "final.png").string() << (job.dump ? " + buffers" : "") << "\n";
  if (stats) {
    printStats(r.sslr().waitForStats(), laterStats, job.frames, gl.value()->isSoftware(), r.sslr().device(),
               job.shapes, job.settings);
    printFrameTimes(times);
  }
  printScores(scores);
  return 0;
}

int run(int argc, char** argv) {
  cxxopts::Options options = renderOptions();
  cxxopts::ParseResult args;
  try {
    args = options.parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "sslr-render: " << e.what() << "\nTry 'sslr-render --help'.\n";
    return kExitUsage;
  }
  if (args.count("help")) {
    std::cout << options.help() << "\n"
              << "Writes DIR/final.png; --dump adds DIR/{color,normal,depth,position,hit,reflection,\n"
              << "iterations,resolved}.exr. Exit codes: 0 ok, 1 rendering failed, 2 bad arguments or input.\n";
    return 0;
  }
  if (!args.unmatched().empty()) {
    std::cerr << "sslr-render: unexpected argument '" << args.unmatched().front() << "'\n";
    return kExitUsage;
  }
  RenderJob job;
  try {
    job.outDir = args["out"].as<std::string>();
    job.dump = args.count("dump") > 0;
    job.score = args.count("score") > 0;
    job.device = args["device"].as<std::string>();
    parseTracing(args, job);
    parseScene(args, job);
    if (args.count("export-gltf")) {
      const std::string file = args["export-gltf"].as<std::string>();
      if (Status st = checkOutputFile(file); !st) throw UsageError{"--export-gltf " + st.message()};
      return exportGltf(job, file);
    }
    if (Status st = HeadlessContext::checkDevice(job.device); !st) throw UsageError{"--device: " + st.message()};
    checkOutputDirectory(job.outDir, job.views);
  } catch (const UsageError& e) {
    std::cerr << "sslr-render: " << e.message << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {  // cxxopts type errors (e.g. --iterations abc)
    std::cerr << "sslr-render: " << e.what() << "\n";
    return kExitUsage;
  }
  return render(job);
}

}  // namespace

int main(int argc, char** argv) {
  sslr::host::removeTemporariesOnSignal();
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "sslr-render: unexpected error: " << e.what() << "\n";
    return kExitFailure;
  }
}
