// sslr-view (see viewer.hpp). The renderer is the tools' FrameRenderer, the reference
// integration docs/integration.md walks through: this file adds the window, the camera, the
// panel and the present pass.
#include "sslr_host/viewer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "sslr_host/embedded_shaders.hpp"
#include "sslr_host/frame_renderer.hpp"
#include "sslr_host/views_renderer.hpp"
#include "sslr_host/gl.hpp"
#include "sslr_host/ground_truth.hpp"
#include "sslr_host/image_io.hpp"
#include "sslr_host/reference_image.hpp"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

namespace fs = std::filesystem;

namespace sslr::host {

namespace {

// What the window shows of each view (present.frag's modes).
enum class Source { Final, Reflection, Resolved, Hit, Iterations, HitDistance, Error, ImageError };
struct View {
  const char* name;
  Source source;
  int mode;  // PRESENT_* in present.frag
  float scale;
};
constexpr View kViews[] = {
    {"final", Source::Final, 0, 1.0f},
    {"reflection", Source::Reflection, 0, 1.0f},
    {"blur-weight", Source::Reflection, 1, 1.0f},
    {"resolved", Source::Resolved, 0, 1.0f},
    {"coverage", Source::Resolved, 1, 1.0f},
    {"confidence", Source::Hit, 2, 1.0f},
    {"length", Source::Hit, 3, 10.0f},
    {"iterations", Source::Iterations, 4, 16.0f},
    {"hit-distance", Source::HitDistance, 4, 10.0f},  // Context::hitDistanceTexture() / 10 view units
    {"hit-uv", Source::Hit, 5, 1.0f},
    {"error", Source::Error, 0, 1.0f},
    {"image-error", Source::ImageError, 0, 1.0f},
};
constexpr int kErrorView = IM_ARRAYSIZE(kViews) - 2;

const char* kMethods[] = {"adaptive-l", "hiz", "dda", "position-buffer", "none"};

std::vector<std::string> namesOf(auto first, auto last, auto name) {
  std::vector<std::string> out;
  for (; first != last; ++first) out.push_back(name(*first));
  return out;
}
const char* kPresets[] = {"low", "medium", "high", "ultra"};
const char* kDepths[] = {"reversed", "reversed-infinite", "zero-to-one", "gl-default"};

// One side of the split: its settings and its own renderer (so each keeps its own history).
struct Side {
  int method = 0;  // kMethods
  int preset = 2;
  Settings settings = Settings::preset(Preset::High);
  std::unique_ptr<FrameRenderer> renderer;
  GLuint errorTexture = 0;       // the error view, computed on demand
  GLuint imageErrorTexture = 0;  // the image-error view, computed on demand
  std::string error;             // the last dispatch's error, shown in the panel
  std::string errorSummary;      // the error view's metrics
  std::string imageErrorSummary;  // the image-error view's
  FrameStats stats;
};

Settings settingsFor(const Side& s) {
  Settings out = s.settings;
  out.method = s.method == 1 ? Method::HierarchicalDepth
               : s.method == 2 ? Method::ScreenSpaceDDA
               : s.method == 3 ? Method::PositionBuffer
                               : Method::AdaptiveL;
  // The traversal alone needs steps (0 turns AdaptiveL's traversal off, e.g. Preset::Low's).
  if (out.method == Method::HierarchicalDepth && out.traversal.maxSteps == 0)
    out.traversal.maxSteps = Settings{}.traversal.maxSteps;
  out.debug.outputs = true;  // the debug views read hit and iterations
  out.hitDistance = true;    // ... and the hit distance output
  out.debug.collectStats = true;
  return out;
}

// Orbit and fly camera over the scene's camera.
struct CameraControl {
  Camera camera;
  bool fly = false;
  void orbit(double yawDegrees, double pitchDegrees) {
    glm::dvec3 offset = camera.eye - camera.target;
    const glm::dmat4 yaw = glm::rotate(glm::dmat4(1.0), glm::radians(yawDegrees), glm::dvec3(0, 1, 0));
    offset = glm::dvec3(yaw * glm::dvec4(offset, 0.0));
    const glm::dvec3 right = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), offset));
    const glm::dmat4 pitch = glm::rotate(glm::dmat4(1.0), glm::radians(pitchDegrees), right);
    const glm::dvec3 pitched = glm::dvec3(pitch * glm::dvec4(offset, 0.0));
    // Stop short of the poles (the up vector would flip).
    if (std::abs(glm::dot(glm::normalize(pitched), glm::dvec3(0, 1, 0))) < 0.98) offset = pitched;
    camera.eye = camera.target + offset;
  }
  void zoom(double factor) { camera.eye = camera.target + (camera.eye - camera.target) * factor; }
  void look(double yawDegrees, double pitchDegrees) {  // fly: turn the target about the eye
    glm::dvec3 forward = camera.target - camera.eye;
    const glm::dmat4 yaw = glm::rotate(glm::dmat4(1.0), glm::radians(-yawDegrees), glm::dvec3(0, 1, 0));
    forward = glm::dvec3(yaw * glm::dvec4(forward, 0.0));
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
    const glm::dvec3 pitched =
        glm::dvec3(glm::rotate(glm::dmat4(1.0), glm::radians(-pitchDegrees), right) * glm::dvec4(forward, 0.0));
    if (std::abs(glm::dot(glm::normalize(pitched), glm::dvec3(0, 1, 0))) < 0.98) forward = pitched;
    camera.target = camera.eye + forward;
  }
  void move(glm::dvec3 local) {  // fly: x right, y up, z forward, in units of the target distance
    const glm::dvec3 forward = camera.target - camera.eye;
    const double step = glm::length(forward);
    const glm::dvec3 f = glm::normalize(forward), r = glm::normalize(glm::cross(f, glm::dvec3(0, 1, 0)));
    const glm::dvec3 d = (r * local.x + glm::dvec3(0, 1, 0) * local.y + f * local.z) * step;
    camera.eye += d;
    camera.target += d;
  }
};

struct App {
  ViewerOptions options;
  GLFWwindow* window = nullptr;
  Scene scene;
  std::unique_ptr<GpuScene> gpu;
  CameraControl control;
  Side sides[2];
  bool compare = false;
  // Stereo: side A's settings trace two eyes through one context of two views (ViewsRenderer);
  // the window wipes from the left eye's final image to the right eye's at `split`.
  bool stereo = false;
  float eyeSeparation = 0.064f;
  std::unique_ptr<ViewsRenderer> eyes;
  float split = 0.5f;
  int editing = 0;
  int view = 0;
  int depth = 0;
  int normals = 0;  // 0 octahedral, 1 xyz
  int composite = 0;  // 0 blend over fallback, 1 add
  int width = 0, height = 0;
  GLuint presentProgram = 0, presentVao = 0, presentSampler = 0;
  std::string pendingScene;  // dropped on the window
  std::string status;        // last message in the panel
  double frameMs = 0.0;
  bool software = false;
  bool lastMouseValid = false;
  double lastX = 0, lastY = 0;

  Status loadSceneNamed(const std::string& name) {
    auto loaded = loadScene(name);
    if (!loaded) return Status::error(loaded.error());
    if (options.mirrorFloor) addMirrorFloor(loaded.value());
    if (std::string why = loaded.value().checkExtent(); !why.empty()) return Status::error(name + ": " + why);
    scene = std::move(loaded.value());
    gpu = std::make_unique<GpuScene>(scene);
    control.camera = scene.camera ? *scene.camera : scene.defaultCamera();
    fitClipPlanes(control.camera, scene.worldBounds());
    for (Side& s : sides) s.renderer.reset();  // fresh histories
    eyes.reset();
    return {};
  }

  GBufferOptions gbufferOptions() const {
    GBufferOptions g;
    g.width = width;
    g.height = height;
    const DepthMode modes[] = {DepthMode::Reversed, DepthMode::ReversedInfinite, DepthMode::ZeroToOne,
                               DepthMode::GlDefault};
    g.depth = modes[depth];
    g.normals = normals == 0 ? NormalEncoding::Octahedral : NormalEncoding::XyzUnorm;
    g.withPosition = true;  // the position-buffer method reads it
    return g;
  }

  Status ensureRenderers() {
    if (stereo && !(eyes && eyes->gbuffer(0).width() == width && eyes->gbuffer(0).height() == height)) {
      auto r = ViewsRenderer::create(gbufferOptions(), 2, reinterpret_cast<GetProcAddress>(&glfwGetProcAddress));
      if (!r) return Status::error(r.error());
      eyes = std::move(r.value());
    }
    for (Side& s : sides) {
      if (s.renderer && s.renderer->gbuffer().width() == width && s.renderer->gbuffer().height() == height) continue;
      auto r = FrameRenderer::create(gbufferOptions(), reinterpret_cast<GetProcAddress>(&glfwGetProcAddress));
      if (!r) return Status::error(r.error());
      s.renderer = std::move(r.value());
      for (GLuint* t : {&s.errorTexture, &s.imageErrorTexture}) {
        if (*t != 0) glDeleteTextures(1, t);
        *t = 0;
      }
      s.imageErrorSummary.clear();
    }
    return {};
  }

  void renderSide(Side& s) {
    s.renderer->setCompositeMode(composite == 0 ? CompositeMode::BlendOverFallback : CompositeMode::Add);
    const bool none = s.method == 4;
    const Settings settings = settingsFor(s);
    if (stereo) {  // both eyes in one dispatch (the window shows their final images)
      eyes->setCompositeMode(composite == 0 ? CompositeMode::BlendOverFallback : CompositeMode::Add);
      const Status st = eyes->render(*gpu, sideBySideCameras(control.camera, 2, eyeSeparation), none ? nullptr : &settings);
      s.error = st ? "" : st.message();
      if (!none) s.stats = eyes->sslr().lastStats();
      return;
    }
    const Status st = s.renderer->render(*gpu, control.camera, none ? nullptr : &settings);
    s.error = st ? "" : st.message();
    if (!none) s.stats = s.renderer->sslr().lastStats();
  }

  GLuint textureOf(Side& s, Source source) {
    Context& c = s.renderer->sslr();
    switch (source) {
      case Source::Final: return s.renderer->finalTexture();
      case Source::Reflection: return c.reflectionTexture();
      case Source::Resolved: return c.resolvedTexture();
      case Source::Hit: return c.hitTexture();
      case Source::Iterations: return c.iterationsTexture();
      case Source::HitDistance: return c.hitDistanceTexture();
      case Source::Error: return s.errorTexture != 0 ? s.errorTexture : s.renderer->finalTexture();
      case Source::ImageError: return s.imageErrorTexture != 0 ? s.imageErrorTexture : s.renderer->finalTexture();
    }
    return 0;
  }

  // The error view of one side: Embree truth for the current camera against its hits.
  void computeError(Side& s) {
    if (s.method == 4) return;
    auto truth = groundTruthFor(scene, s.renderer->gbuffer(), settingsFor(s));
    if (!truth) {
      status = "error view: " + truth.error();
      return;
    }
    const Image hit = s.renderer->readHit();
    const Image map = hitErrorImage(truth.value(), hit);
    const HitMetrics m = compareHits(truth.value(), hit);
    upload(s.errorTexture, map);
    char line[256];
    std::snprintf(line, sizeof line, "%s: recall@1px %.4f, p95 %.2f px, false hits %.2f%%", kMethods[s.method],
                  m.recall1px, m.p95ErrorPx, 100.0 * m.falseHitRate);
    s.errorSummary = line;
  }

  // The image-error view of one side: what the user sees, its composite over the fallback, against
  // the ray-traced reference (reference_image.hpp): |error| x 4 on the mirror pixels, the RMSE, and
  // the share of the squared error by what the method reported there.
  void computeImageError(Side& s) {
    if (s.method == 4) return;
    const Settings settings = settingsFor(s);
    if (composite != 0 || settings.output != OutputMode::Weighted) {
      s.imageErrorSummary = std::string(kMethods[s.method]) +
                            ": the image error needs the blend over the fallback and weighted output";
      if (s.imageErrorTexture != 0) glDeleteTextures(1, &s.imageErrorTexture);  // no stale map
      s.imageErrorTexture = 0;
      return;
    }
    const GBuffer& g = s.renderer->gbuffer();
    auto truth = groundTruthFor(scene, g, settings);
    if (!truth) {
      status = "image-error view: " + truth.error();
      return;
    }
    auto reference = referenceFor(scene, g, truth.value());
    if (!reference) {
      status = "image-error view: " + reference.error();
      return;
    }
    const Image final = s.renderer->readFinal();
    const ImageError e = compositeError(reference.value(), final);
    const CompositeBreakdown b = compositeBreakdown(reference.value(), final, truth.value(), s.renderer->readHit(),
                                                    g.readColor());  // a miss shows the colour
    upload(s.imageErrorTexture, compositeErrorMap(reference.value(), final));
    char line[320];
    if (e.pixels == 0)
      std::snprintf(line, sizeof line, "%s: no mirror pixel to score", kMethods[s.method]);
    else
      std::snprintf(line, sizeof line,
                    "%s: image RMSE %.4f over %zu mirror pixels; hits %.0f%%, wrong %.0f%%, guessed %.0f%%, "
                    "missed %.0f%%, unreachable %.0f%%",
                    kMethods[s.method], e.rmse, e.pixels, 100.0 * b.hit.share, 100.0 * b.wrong.share,
                    100.0 * b.guessed.share, 100.0 * b.missed.share, 100.0 * b.unreachable.share);
    s.imageErrorSummary = line;
  }

  // An RGB image of the window's size into `texture` (RGBA16F, made on first use).
  void upload(GLuint& texture, const Image& rgb) {
    if (texture == 0) {
      glCreateTextures(GL_TEXTURE_2D, 1, &texture);
      glTextureStorage2D(texture, 1, GL_RGBA16F, width, height);
    }
    std::vector<float> rgba(static_cast<size_t>(width) * height * 4, 1.0f);
    for (size_t i = 0; i < static_cast<size_t>(width) * height; ++i)
      for (int k = 0; k < 3; ++k) rgba[i * 4 + k] = rgb.pixels[i * 3 + k];
    glTextureSubImage2D(texture, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba.data());
  }

  void present() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glUseProgram(presentProgram);
    glBindVertexArray(presentVao);
    const View& v = stereo ? kViews[0] : kViews[view];  // stereo: the eyes' final images
    Side& b = compare ? sides[1] : sides[0];
    glBindTextureUnit(0, stereo ? eyes->finalTexture(0) : textureOf(sides[0], v.source));
    glBindTextureUnit(1, stereo ? eyes->finalTexture(1) : textureOf(b, v.source));
    glBindSampler(0, presentSampler);
    glBindSampler(1, presentSampler);
    glProgramUniform1i(presentProgram, 0, v.mode);
    glProgramUniform1f(presentProgram, 1, compare || stereo ? split : 1.0f);
    glProgramUniform1f(presentProgram, 2, v.scale);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
    for (GLuint u = 0; u < 2; ++u) {
      glBindSampler(u, 0);
      glBindTextureUnit(u, 0);
    }
  }

  // The method, its preset and the tracer order of one side.
  void methodControls(Side& s) {
    ImGui::Combo("method", &s.method, kMethods, IM_ARRAYSIZE(kMethods));
    if (ImGui::Combo("preset", &s.preset, kPresets, IM_ARRAYSIZE(kPresets))) {
      const Settings keep = s.settings;
      s.settings = Settings::preset(static_cast<Preset>(s.preset));
      s.settings.halfResolution = keep.halfResolution;
      s.settings.temporal.enabled = keep.temporal.enabled;
    }
    Settings& t = s.settings;
    if (s.method != 0) return;
    // traversal.maxSteps = 0: adaptive L alone; on again at the default step cap.
    bool traversal = t.traversal.maxSteps > 0;
    if (ImGui::Checkbox("hierarchical traversal", &traversal))
      t.traversal.maxSteps = traversal ? Settings{}.traversal.maxSteps : 0;
  }

  // The modes: half resolution, temporal reuse, blur, Fresnel, rough surfaces.
  static void modeControls(Settings& t) {
    ImGui::Checkbox("half resolution", &t.halfResolution);
    ImGui::SameLine();
    ImGui::Checkbox("temporal", &t.temporal.enabled);
    ImGui::SameLine();
    // blur.maxRadiusPx = 0: no blur; on again at the default radius.
    bool blur = t.blur.maxRadiusPx > 0.0f;
    if (ImGui::Checkbox("blur", &blur)) t.blur.maxRadiusPx = blur ? Settings{}.blur.maxRadiusPx : 0.0f;
    int fresnel = t.fresnel == FresnelMode::Classic ? 0 : 1;
    const char* fresnels[] = {"classic", "schlick"};
    if (ImGui::Combo("fresnel", &fresnel, fresnels, 2)) t.fresnel = fresnel == 0 ? FresnelMode::Classic : FresnelMode::Schlick;
    // Rough surfaces: the cone blur or stochastic rays (which need temporal reuse to converge and
    // exclude half resolution: choosing one turns the other off).
    int glossy = t.glossy.mode == GlossyMode::ConeBlur ? 0 : 1;
    const char* glossyModes[] = {"cone blur", "stochastic"};
    if (ImGui::Combo("glossy", &glossy, glossyModes, 2)) {
      t.glossy.mode = glossy == 0 ? GlossyMode::ConeBlur : GlossyMode::Stochastic;
      if (glossy == 1) t.halfResolution = false;
    }
    if (t.halfResolution) t.glossy.mode = GlossyMode::ConeBlur;
    // HDR-safe radiance: 0 = off; bright emitters' hits scaled down to this luminance.
    ImGui::SliderFloat("radianceClamp.maxLuminance", &t.radianceClamp.maxLuminance, 0.0f, 1000.0f, "%.1f",
                       ImGuiSliderFlags_Logarithmic);
  }

  static void tracerTree(Settings& t) {
    if (!ImGui::TreeNode("tracer")) return;
    ImGui::SliderInt("adaptiveL.maxIterations", &t.adaptiveL.maxIterations, 1, 64);
    ImGui::SliderInt("traversal.maxSteps", &t.traversal.maxSteps, 0, 256);
    ImGui::SliderFloat("traversal.objectDepthRelative", &t.traversal.objectDepthRelative, 0.0f, 0.5f);
    ImGui::SliderFloat("traversal.hiddenGuess", &t.traversal.hiddenGuess, 0.0f, 1.0f);
    ImGui::SliderFloat("adaptiveL.convergenceEps", &t.adaptiveL.convergenceEps, 0.0001f, 0.05f, "%.4f");
    ImGui::SliderFloat("adaptiveL.initialLengthScreen", &t.adaptiveL.initialLengthScreen, 0.005f, 0.2f);
    ImGui::SliderFloat("fades.errorK", &t.fades.errorK, 0.0f, 1.0f);
    ImGui::SliderFloat("fades.maxDistance", &t.fades.maxDistance, 0.1f, 1.0e30f, "%.3g", ImGuiSliderFlags_Logarithmic);
    ImGui::TreePop();
  }

  // Fades, material selection, blur and temporal reuse, and the comparison methods' own settings.
  static void otherTrees(int method, Settings& t) {
    if (ImGui::TreeNode("fades and material")) {
      ImGui::SliderFloat("fades.screenEdge", &t.fades.screenEdge, 0.0f, 0.5f);
      ImGui::SliderFloat("fades.cameraStart", &t.fades.cameraStart, -1.0f, 1.0f);
      ImGui::SliderFloat("fades.cameraEnd", &t.fades.cameraEnd, -1.0f, 1.0f);
      ImGui::SliderFloat("selection.roughnessCutoff", &t.selection.roughnessCutoff, 0.0f, 1.0f);
      ImGui::SliderFloat("selection.minReflectance", &t.selection.minReflectance, 0.0f, 0.5f);
      ImGui::TreePop();
    }
    if (ImGui::TreeNode("blur and temporal")) {
      ImGui::SliderFloat("blur.maxRadiusPx", &t.blur.maxRadiusPx, 0.0f, 32.0f);
      ImGui::SliderFloat("blur.coneScale", &t.blur.coneScale, 0.0f, 4.0f);
      ImGui::SliderFloat("blur.depthSigma", &t.blur.depthSigma, 0.001f, 0.2f);
      ImGui::SliderFloat("blur.normalPower", &t.blur.normalPower, 1.0f, 64.0f);
      ImGui::SliderFloat("temporal.historyWeight", &t.temporal.historyWeight, 0.0f, 0.98f);
      ImGui::TreePop();
    }
    if (method == 2 && ImGui::TreeNode("dda (McGuire-Mara)")) {
      ImGui::SliderFloat("dda.stride", &t.dda.stride, 1.0f, 16.0f);
      ImGui::SliderFloat("dda.objectDepth", &t.dda.objectDepth, 0.0f, 2.0f);
      ImGui::SliderInt("dda.maxSteps", &t.dda.maxSteps, 1, 1024);
      ImGui::Checkbox("dda.jitter", &t.dda.jitter);
      ImGui::Checkbox("dda.refine", &t.dda.refine);
      ImGui::TreePop();
    }
    if (method == 3 && ImGui::TreeNode("position buffer (tutorial)")) {
      ImGui::SliderFloat("positionBuffer.maxDistance", &t.positionBuffer.maxDistance, 0.5f, 64.0f);
      ImGui::SliderFloat("positionBuffer.resolution", &t.positionBuffer.resolution, 0.05f, 1.0f);
      ImGui::SliderInt("positionBuffer.steps", &t.positionBuffer.steps, 0, 32);
      ImGui::SliderFloat("positionBuffer.hitTolerance", &t.positionBuffer.hitTolerance, 0.0f, 2.0f);
      ImGui::TreePop();
    }
  }

  void sidePanel(Side& s) {
    methodControls(s);
    modeControls(s.settings);
    tracerTree(s.settings);
    otherTrees(s.method, s.settings);
    if (!s.error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", s.error.c_str());
    if (s.method != 4) {
      const FrameStats& f = s.stats;
      ImGui::Text("tiles %u, traced %u, fetches %u", f.tiles, f.tracedPixels, f.fetches);
      ImGui::Text("ms: classify %.2f  pyramid %.2f  trace %.2f", f.classifyMs, f.pyramidMs, f.traceMs);
      ImGui::Text("    blur %.2f  temporal %.2f (frame %llu)", f.blurMs, f.temporalMs,
                  static_cast<unsigned long long>(f.frame));
    }
  }

  void panel() {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(390, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("sslr");
    ImGui::Text("%s (%zu triangles)", scene.name.c_str(), scene.triangleCount());
    ImGui::Text("%.1f ms per frame (wall clock around glFinish)", frameMs);
    if (software) ImGui::TextDisabled("llvmpipe: pass times below measure the CPU");
    if (ImGui::Button(control.fly ? "fly (F)" : "orbit (F)")) control.fly = !control.fly;
    ImGui::SameLine();
    if (ImGui::Button("screenshot (P)")) writeSnapshot();
    ImGui::SameLine();
    ImGui::BeginDisabled(stereo);  // (the error views score one view's frame)
    if (ImGui::Button("error view")) {
      for (int i = 0; i < (compare ? 2 : 1); ++i) computeError(sides[i]);
      view = kErrorView;
    }
    ImGui::SameLine();
    if (ImGui::Button("image error")) {
      for (int i = 0; i < (compare ? 2 : 1); ++i) computeImageError(sides[i]);
      view = kErrorView + 1;
    }
    ImGui::EndDisabled();
    std::vector<const char*> names;
    for (const View& v : kViews) names.push_back(v.name);
    ImGui::Combo("view", &view, names.data(), static_cast<int>(names.size()));
    bool rebuild = ImGui::Combo("depth", &depth, kDepths, IM_ARRAYSIZE(kDepths));
    const char* encodings[] = {"octahedral (RGBA16)", "xyz (RGBA8)"};
    rebuild |= ImGui::Combo("normals", &normals, encodings, 2);
    if (rebuild) {
      for (Side& s : sides) s.renderer.reset();
      eyes.reset();
    }
    const char* modes[] = {"blend over fallback", "add"};
    ImGui::Combo("composite", &composite, modes, 2);
    if (ImGui::Checkbox("stereo (two eyes, one context)", &stereo) && stereo) compare = false;
    if (stereo) {
      ImGui::SliderFloat("eye separation", &eyeSeparation, 0.0f, 1.0f);
      ImGui::SliderFloat("split", &split, 0.0f, 1.0f);
      ImGui::TextDisabled("left of the split: the left eye; right: the right eye (final images only)");
    }
    if (ImGui::Checkbox("compare (split screen)", &compare) && compare) stereo = false;
    if (compare) {
      ImGui::Text("left A: %s, right B: %s", kMethods[sides[0].method], kMethods[sides[1].method]);
      ImGui::SliderFloat("split", &split, 0.0f, 1.0f);
      ImGui::RadioButton("edit left (A)", &editing, 0);
      ImGui::SameLine();
      ImGui::RadioButton("edit right (B)", &editing, 1);
    } else {
      editing = 0;
    }
    sidePanel(sides[editing]);
    for (int i = 0; i < (compare ? 2 : 1); ++i) {
      if (!sides[i].errorSummary.empty())
        ImGui::Text("%s %s", compare ? (i == 0 ? "A" : "B") : "error view:", sides[i].errorSummary.c_str());
      if (!sides[i].imageErrorSummary.empty())
        ImGui::TextWrapped("%s %s", compare ? (i == 0 ? "A" : "B") : "image error:", sides[i].imageErrorSummary.c_str());
    }
    if (!status.empty()) ImGui::TextWrapped("%s", status.c_str());
    ImGui::End();
  }

  // Writes the window (PNG) and view A's buffers (EXR; stereo: each eye's final image) into a new
  // folder sslr-view-N.
  void writeSnapshot() {
    int n = 1;
    while (fs::exists("sslr-view-" + std::to_string(n))) ++n;
    const fs::path dir = "sslr-view-" + std::to_string(n);
    fs::create_directories(dir);
    FrameRenderer& r = *sides[0].renderer;
    Status st = writeImage((dir / "window.png").string(), readWindow());
    if (stereo) {
      for (int v = 0; v < 2 && st; ++v)
        st = writeImage((dir / ("final-view" + std::to_string(v) + ".exr")).string(), eyes->readFinal(v), {"R", "G", "B"});
      status = st ? "wrote " + dir.string() : st.message();
      return;
    }
    if (st && sides[0].method != 4) {
      st = writeImage((dir / "resolved.exr").string(), r.readResolved(), {"R", "G", "B", "A"});
      if (st) st = writeImage((dir / "hit.exr").string(), r.readHit(), {"R", "G", "B", "A"});
    }
    if (st) st = writeImage((dir / "final.exr").string(), r.readFinal(), {"R", "G", "B"});
    status = st ? "wrote " + dir.string() : st.message();
  }

  // The back buffer as linear float (it holds sRGB bytes: decoded, so that writing it as PNG,
  // which encodes linear to sRGB, gives the same bytes back).
  Image readWindow() const {
    std::vector<unsigned char> bytes(static_cast<size_t>(width) * height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    Image img{width, height, 3, std::vector<float>(static_cast<size_t>(width) * height * 3)};
    for (size_t i = 0; i < static_cast<size_t>(width) * height; ++i)
      for (int k = 0; k < 3; ++k) {
        const float c = bytes[i * 4 + k] / 255.0f;
        img.pixels[i * 3 + k] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
      }
    return img;
  }

  void handleInput() {
    ImGuiIO& io = ImGui::GetIO();
    double x = 0, y = 0;
    glfwGetCursorPos(window, &x, &y);
    const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (!io.WantCaptureMouse && lastMouseValid && (left || right)) {
      const double dx = x - lastX, dy = y - lastY;
      if (control.fly) control.look(dx * 0.2, dy * 0.2);
      else control.orbit(-dx * 0.3, -dy * 0.3);
    }
    lastX = x, lastY = y;
    lastMouseValid = true;
    if (!io.WantCaptureMouse && io.MouseWheel != 0.0f) control.zoom(std::pow(0.9, io.MouseWheel));
    if (io.WantCaptureKeyboard) return;
    if (ImGui::IsKeyPressed(GLFW_KEY_F)) control.fly = !control.fly;
    if (ImGui::IsKeyPressed(GLFW_KEY_P)) writeSnapshot();
    if (control.fly) {
      const double s = 0.02;
      glm::dvec3 m(0.0);
      if (ImGui::IsKeyDown(GLFW_KEY_W)) m.z += s;
      if (ImGui::IsKeyDown(GLFW_KEY_S)) m.z -= s;
      if (ImGui::IsKeyDown(GLFW_KEY_D)) m.x += s;
      if (ImGui::IsKeyDown(GLFW_KEY_A)) m.x -= s;
      if (ImGui::IsKeyDown(GLFW_KEY_E)) m.y += s;
      if (ImGui::IsKeyDown(GLFW_KEY_Q)) m.y -= s;
      if (m != glm::dvec3(0.0)) control.move(m);
    }
  }
};

App* gApp = nullptr;  // for GLFW's C callbacks

}  // namespace

const std::vector<std::string>& viewerViewNames() {
  static const std::vector<std::string> names =
      namesOf(std::begin(kViews), std::end(kViews), [](const View& v) { return std::string(v.name); });
  return names;
}

const std::vector<std::string>& viewerMethodNames() {
  static const std::vector<std::string> names =
      namesOf(std::begin(kMethods), std::end(kMethods), [](const char* m) { return std::string(m); });
  return names;
}

namespace {

// A window with an OpenGL 4.5 core context, current, its functions loaded; false (said on stderr,
// GLFW terminated) when the display offers none.
bool openWindow(App& app, const ViewerOptions& options) {
  glfwSetErrorCallback([](int, const char* text) { std::fprintf(stderr, "sslr-view: GLFW: %s\n", text); });
  if (!glfwInit()) {
    std::fprintf(stderr,
                 "sslr-view: cannot open a window: no display (set DISPLAY, or run headless under "
                 "xvfb-run -a -s '-screen 0 1920x1080x24' sslr-view ...)\n");
    return false;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  app.window = glfwCreateWindow(options.width, options.height, "sslr-view", nullptr, nullptr);
  if (app.window == nullptr) {
    std::fprintf(stderr, "sslr-view: the display offers no OpenGL 4.5 core context (sslr needs one)\n");
    glfwTerminate();
    return false;
  }
  glfwMakeContextCurrent(app.window);
  glfwSwapInterval(options.frames > 0 ? 0 : 1);
  if (gladLoadGL(reinterpret_cast<GLADloadfunc>(&glfwGetProcAddress)) == 0) {
    std::fprintf(stderr, "sslr-view: loading OpenGL 4.5 functions failed\n");
    glfwTerminate();
    return false;
  }
  return true;
}

enum class FrameResult { Next, Stop };

// One frame of the window: events, a dropped scene, both sides rendered, the panel; the scripted
// run's last frame writes its screenshot. exitCode: set on failure.
FrameResult drawFrame(App& app, const ViewerOptions& options, int frame, int& exitCode) {
  glfwPollEvents();
  if (!app.pendingScene.empty()) {
    const Status st = app.loadSceneNamed(app.pendingScene);
    app.status = st ? "loaded " + app.pendingScene : st.message();
    app.pendingScene.clear();
  }
  glfwGetFramebufferSize(app.window, &app.width, &app.height);
  if (app.width <= 0 || app.height <= 0) return FrameResult::Next;  // minimized
  if (Status st = app.ensureRenderers(); !st) {
    std::fprintf(stderr, "sslr-view: %s\n", st.message().c_str());
    exitCode = 1;
    return FrameResult::Stop;
  }
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  app.handleInput();
  if (options.orbitDegrees != 0.0) app.control.orbit(options.orbitDegrees, 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  app.renderSide(app.sides[0]);
  if (app.compare) app.renderSide(app.sides[1]);
  glFinish();
  app.frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  // The error views are computed when first shown (and by their buttons after the camera moved);
  // stereo shows the eyes' final images only.
  for (int i = 0; i < (app.compare ? 2 : 1) && !app.stereo; ++i) {
    Side& s = app.sides[i];
    if (s.method == 4) continue;
    if (kViews[app.view].source == Source::Error && s.errorTexture == 0) app.computeError(s);
    if (kViews[app.view].source == Source::ImageError && s.imageErrorTexture == 0 && s.imageErrorSummary.empty()) {
      app.computeImageError(s);
      if (options.frames > 0) std::printf("sslr-view: %s %s\n", i == 0 ? "A" : "B", s.imageErrorSummary.c_str());
    }
  }
  app.present();
  if (!options.hideUi) app.panel();
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (options.frames > 0 && frame + 1 >= options.frames) {
    if (!options.screenshot.empty()) {
      const Status st = writeImage(options.screenshot, app.readWindow());
      if (!st) {
        std::fprintf(stderr, "sslr-view: %s\n", st.message().c_str());
        exitCode = 1;
      }
      for (const Side& s : app.sides)
        if (!s.error.empty()) {
          std::fprintf(stderr, "sslr-view: %s\n", s.error.c_str());
          exitCode = 1;
        }
    }
    glfwSwapBuffers(app.window);
    return FrameResult::Stop;
  }
  glfwSwapBuffers(app.window);
  return FrameResult::Next;
}

// Everything the viewer made on the GL context and in Dear ImGui, released.
void releaseViewer(App& app) {
  gApp = nullptr;
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  app.eyes.reset();
  for (Side& s : app.sides) {
    s.renderer.reset();
    for (GLuint t : {s.errorTexture, s.imageErrorTexture})
      if (t != 0) glDeleteTextures(1, &t);
  }
  app.gpu.reset();
  glDeleteProgram(app.presentProgram);
  glDeleteVertexArrays(1, &app.presentVao);
  glDeleteSamplers(1, &app.presentSampler);
}

}  // namespace

int runViewer(const ViewerOptions& options) {
  App app;
  app.options = options;
  if (!openWindow(app, options)) return 1;
  const std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  app.software = renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
  std::fprintf(stderr, "sslr-view: %s | %s\n", renderer.c_str(), reinterpret_cast<const char*>(glGetString(GL_VERSION)));

  int exitCode = 0;
  {
    auto program = linkHostProgram({{GL_VERTEX_SHADER, "host/present.vert"}, {GL_FRAGMENT_SHADER, "host/present.frag"}});
    if (!program) {
      std::fprintf(stderr, "sslr-view: %s\n", program.error().c_str());
      glfwTerminate();
      return 1;
    }
    app.presentProgram = program.value();
    glCreateVertexArrays(1, &app.presentVao);
    glCreateSamplers(1, &app.presentSampler);
    glSamplerParameteri(app.presentSampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(app.presentSampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (Status st = app.loadSceneNamed(options.scene); !st) {
      std::fprintf(stderr, "sslr-view: %s\n", st.message().c_str());
      exitCode = 2;
    }
    for (int i = 0; i < IM_ARRAYSIZE(kViews); ++i)
      if (options.debugView == kViews[i].name) app.view = i;
    app.stereo = options.stereo;
    if (!options.split.empty()) {
      app.compare = true;
      for (int i = 0; i < IM_ARRAYSIZE(kMethods); ++i)
        if (options.split == kMethods[i]) app.sides[1].method = i;
    }
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left behind
    ImGui_ImplGlfw_InitForOpenGL(app.window, true);
    ImGui_ImplOpenGL3_Init("#version 450");
    gApp = &app;
    glfwSetDropCallback(app.window, [](GLFWwindow*, int count, const char** paths) {
      if (count > 0 && gApp != nullptr) gApp->pendingScene = paths[0];
    });

    for (int frame = 0; exitCode == 0 && !glfwWindowShouldClose(app.window); ++frame) {
      if (drawFrame(app, options, frame, exitCode) == FrameResult::Stop) break;
    }
    releaseViewer(app);
  }
  glfwDestroyWindow(app.window);
  glfwTerminate();
  return exitCode;
}

}  // namespace sslr::host
