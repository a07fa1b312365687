// Context::Impl: sslr's GL objects and the steps of a frame, shared by the files that implement
// them: context.cpp (lifetime, targets, the public Context), programs.cpp (shader programs),
// inputs.cpp (checks of the host's textures), frame.cpp (a frame's plan, its start and end) and
// one file per pass in passes/ (classify -> pyramid -> trace -> blur -> temporal), each next to
// the header of its state (resources and programs), and composite.cpp.
#pragma once

#include <algorithm>
#include <cstdint>
#include <array>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "gl_functions.hpp"
#include "passes/blur.hpp"
#include "passes/classify.hpp"
#include "passes/pyramid.hpp"
#include "passes/temporal.hpp"
#include "passes/trace.hpp"
#include "sslr/sslr.hpp"
#include "sslr_shared.h"

namespace sslr {

// The tile buffer (common/tiles.glsl): a header of indirect commands (shared::SslrTileHeader),
// then the per-tile arrays. Byte offsets of its commands:
constexpr GLintptr kHizDispatchOffset = offsetof(shared::SslrTileHeader, hizDispatch);  // per pyramid level
constexpr GLintptr kDrawArgsOffset = offsetof(shared::SslrTileHeader, drawCount);       // the composite's draw
constexpr GLintptr kBlurDispatchOffset = offsetof(shared::SslrTileHeader, blurDispatchX);
constexpr GLintptr kQuadDispatchOffset = offsetof(shared::SslrTileHeader, quadDispatchX);  // DeviceProfile::Gpu's quad pass
constexpr GLintptr kCleanupDispatchOffset = offsetof(shared::SslrTileHeader, cleanupDispatchX);  // the previous trace's
// The part of the header the CPU writes each frame (all but the clean-up dispatch).
constexpr GLsizeiptr kHeaderUploadBytes = kCleanupDispatchOffset;
constexpr GLsizeiptr kTileHeader = sizeof(shared::SslrTileHeader) / 4;  // uints before the tile lists
constexpr GLsizeiptr kTileArrays = 6;                                   // per-tile arrays after it
// 2_pyramid_levels2to7.comp's work group builds levels 2..kHizBlockTop of one kHizBlockTop cell (its shared arrays
// are sized for 7: 64x64 level-1 cells); a level above it has a single-level dispatch of its own.
constexpr int kHizBlockTop = 7;
// TraversalPass::Auto on a software renderer runs the traversal inline above this share of the
// traced tiles' pixels needing it (+-0.05 hysteresis; docs/design-notes.md, "Where the
// traversal runs").
constexpr double kInlineTraversalShare = 0.5;

// What sslr needs to know of a host texture's internal format.
struct FormatInfo {
  enum Kind { Unsupported, Color, Depth } kind = Unsupported;
  int channels = 0;
  const char* name = "unsupported";
  int bytes = 0;  // per texel
};

// What FrameStats' traffic model needs to know of a frame (stats.cpp, estimateTraffic): the
// screen, the bytes per texel of each input (0 where absent) and which passes and paths ran.
struct TrafficModel {
  int width = 0, height = 0;
  int depthBytes = 0, normalBytes = 0, materialBytes = 0, maskBytes = 0, backDepthBytes = 0;
  int colorBytes = 0, positionBytes = 0, motionBytes = 0, baseColorBytes = 0;
  int materialGathers = 0;      // material channels classification gathers from a texture (0..2)
  int normalGathers = 0;        // curved solids: normal channels gathered per quad (0, 2 or 3)
  bool classifyLevels01 = false;  // classification writes the pyramid's levels 0 and 1
  bool levels01Pass = false;      // ... a pass of their own does (after an empty frame)
  bool pyramid = false;           // the pyramid is built and traced
  std::uint64_t level1Cells = 0;  // level-1 cells over the screen
  std::uint64_t upperCells = 0;   // cells of levels 2 and up
  int fetchBytes = 0;             // bytes of one counted fetch (depth, position, or pyramid texel)
  bool halfResolution = false, hitRecord = false, iterations = false, hitDistance = false, temporal = false;
  bool stochasticFilter = false;  // the temporal blend reads its 3x3 neighbours' depth, normal and material
  int blurTaps = 0;               // taps on each side at the blur's widest (0: no blur)
};
// FrameStats' PassTraffic from the model and the frame's counts (tiles, traced pixels, fetches).
void estimateTraffic(const TrafficModel& model, FrameStats& stats);
FormatInfo formatInfo(GLint internalFormat);

struct Context::Impl {
  detail::Gl gl;
  LogCallback log;
  bool softwareRenderer = false;  // DeviceProfile::Software (ContextDesc::device, or Auto on a CPU rasterizer)
  TraversalPass traversalPass = TraversalPass::Auto;  // ContextDesc's pass shapes
  bool oneBodyTraversal = false;
  bool occupancyExit = false;
  int width = 0, height = 0;  // the textures' (inputs and outputs)
  // ContextDesc::views: with more than one, every texture and image is a 2D array of one layer a
  // view, the tile lists hold every view's entries and the full-screen dispatches have z = views.
  int views = 1;
  GLenum textureTarget() const { return views > 1 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D; }
  // A texture of the context's kind (a 2D array of `views` layers when views > 1).
  GLuint createTexture(GLenum format, int levels, int w, int h) const {
    GLuint t = 0;
    gl.CreateTextures(textureTarget(), 1, &t);
    if (views > 1) gl.TextureStorage3D(t, levels, format, w, h, views);
    else gl.TextureStorage2D(t, levels, format, w, h);
    return t;
  }
  // Binds level `level` of one of sslr's textures (every layer) to image unit `unit`, write-only.
  void bindImage(GLuint unit, GLuint texture, int level, GLenum format) const {
    gl.BindImageTexture(unit, texture, level, views > 1 ? GL_TRUE : GL_FALSE, 0, GL_WRITE_ONLY, format);
  }

  // This frame's rectangle of the textures (FrameInputs::viewport) and what follows from its
  // size: the tile grid and the pyramid's shape (allocations are the context's: the largest).
  // Set by dispatch(); `changed`: it differs from the last dispatch's.
  struct FrameArea {
    Viewport rect;
    int tilesX = 0, tilesY = 0;
    int levels = 0;                         // the pyramid's levels above level 0 (sslrHiZLevelCount)
    int level1Width = 0, level1Height = 0;  // level 1's cells, padded so that every level halves exactly
    bool changed = false;
  } area;
  Viewport lastRect;  // the rectangle the last frame run wrote (its outputs and tile arrays)
  static FrameArea areaOf(const Viewport& rect);

  // The outputs, written by the trace and rewritten by the blur and temporal reuse, and the
  // intermediate image those two write before their final pass.
  GLuint reflection = 0, resolved = 0;
  GLuint scratch = 0;
  // Each pass's own resources (passes/*.hpp).
  PyramidPass pyramid;
  TracePass trace;
  TemporalPass temporal;
  // The last frame's counts, fed back without a stall: `buffer` holds (listed tiles, 0, 0, pixels
  // that needed the traversal), fenced, read without waiting at the next dispatch (readFeedback).
  struct Feedback {
    GLuint buffer = 0;
    GLsync fence = nullptr;
    bool hasTraversal = false;                           // the pending copy has the traversal's count
    int cellsPerTile = SSLR_TILE_SIZE * SSLR_TILE_SIZE;  // that count is of pixels, or quads
    // Classification then leaves the pyramid's levels 0 and 1 to a pass of their own (an empty
    // frame after an empty one only reads the G-buffer).
    bool lastFrameListedNoTile = false;
    // TraversalPass::Auto on a software renderer: the current choice, from the share of pixels (at
    // half resolution: quads) of the listed tiles that needed the traversal.
    bool traversalInline = false;
  } feedback;
  GLuint frameUbo = 0, tileBuffer = 0;
  // Stats without a stall: a ring of slots, each a counter buffer (traced pixels, fetches,
  // hierarchical pixels, pad, tiles, blur tiles), GL_TIMESTAMP queries (before classification,
  // after it, after the pyramid, after the trace, after the blur, after temporal reuse) and a fence.
  static constexpr int kTimestamps = 6;
  // The commands of the dispatch being recorded, by pass (FrameStats' order: classify, pyramid,
  // trace, blur, temporal, finish); the passes issue their GL commands through the wrappers below.
  static constexpr int kPasses = 6;
  mutable std::array<PassCommands, kPasses> recording{};
  mutable int recordingPass = 0;
  void useProgram(GLuint program) const { gl.UseProgram(program); ++recording[recordingPass].programs; }
  void dispatchCompute(GLuint x, GLuint y, GLuint z) const { gl.DispatchCompute(x, y, z); ++recording[recordingPass].dispatches; }
  void dispatchComputeIndirect(GLintptr offset) const {
    gl.DispatchComputeIndirect(offset);
    ++recording[recordingPass].indirectDispatches;
  }
  void memoryBarrier(GLbitfield bits) const { gl.MemoryBarrier(bits); ++recording[recordingPass].barriers; }
  void bufferSubData(GLuint buffer, GLintptr offset, GLsizeiptr size, const void* data) const {
    gl.NamedBufferSubData(buffer, offset, size, data);
    ++recording[recordingPass].uploads;
  }
  void copyBufferSubData(GLuint from, GLuint to, GLintptr fromOffset, GLintptr toOffset, GLsizeiptr size) const {
    gl.CopyNamedBufferSubData(from, to, fromOffset, toOffset, size);
    ++recording[recordingPass].uploads;
  }
  void clearTexImage(GLuint texture, GLenum format, GLenum type, const void* data) const {
    gl.ClearTexImage(texture, 0, format, type, data);
    ++recording[recordingPass].uploads;
  }

  struct StatsSlot {
    GLuint buffer = 0;
    std::array<PassCommands, kPasses> commands{};
    GLuint queries[kTimestamps] = {};
    GLsync fence = nullptr;
    std::uint64_t frame = 0;
    bool traversalDeferred = false;
    bool followedEmptyFrame = false;
    TrafficModel traffic;
  };
  static constexpr int kStatsRing = 4;
  mutable StatsSlot statsRing[kStatsRing];
  bool timestamps = false;         // GL_TIMESTAMP has counter bits
  std::uint64_t dispatches = 0;    // dispatches that got as far as the GPU
  mutable FrameStats stats;        // the newest harvested
  GLuint nearestSampler = 0, linearSampler = 0, vao = 0;
  std::map<std::string, GLuint> programs;  // key: entry files + defines
  // Programs handed to the driver and not yet waited on (prepare()'s first phase: a driver that
  // compiles in parallel, GL_KHR_parallel_shader_compile, works on all of them at once). Their
  // shaders stay attached until program() reads the result.
  struct PendingProgram {
    GLuint program = 0;
    std::vector<std::pair<GLuint, const char*>> shaders;  // shader, its entry file
  };
  std::map<std::string, PendingProgram> pendingPrograms;  // key: as `programs`
  bool issueProgramsOnly = false;  // program() hands a new program over without waiting on it
  // The current dispatch's optional inputs as #defines, prefixed to every compute program
  // (SSLR_HAS_MASK, SSLR_SEPARATE_MATERIAL: common/gbuffer.glsl).
  std::string inputDefines;
  bool haveFrame = false;  // a dispatch filled the tile list, so composite has work to draw
  mutable GLName warnedFloatNormals = 0;  // the float normal texture last warned of (checkNormalDecode)
  bool frameIsRadiance = false;  // ... traced with OutputMode::Radiance (composite refuses it)
  int frameIndex = 0;      // per-dispatch stamp for the blur tile list (1, 2, ...)

  ~Impl() { destroy(); }

  void message(LogLevel level, const std::string& text) const {
    if (log) log(level, text);
  }
  // GL_MAX_LABEL_LENGTH is at least 256 (KHR_debug): a longer label (a program's defines) is cut
  // there, which would otherwise be a GL error.
  void label(GLenum type, GLuint name, const std::string& text) const {
    gl.ObjectLabel(type, name, static_cast<GLsizei>(std::min<size_t>(text.size(), 255)), text.c_str());
  }
  int tilesX() const { return (width + SSLR_TILE_SIZE - 1) / SSLR_TILE_SIZE; }
  int tilesY() const { return (height + SSLR_TILE_SIZE - 1) / SSLR_TILE_SIZE; }

  // context.cpp
  GLuint makeTexture(GLenum format, const char* name) const;
  void createTargets();
  void destroyTargets();
  void destroy();
  // The targets' contents, the tile list, the feedback, the history and the counters as after
  // create() or resize(), keeping every GL name (after prepare's warm-up frames).
  void resetFrameState(std::uint64_t dispatchesBefore, int frameIndexBefore);
  std::vector<GLuint> initialTileList() const;
  // programs.cpp: hands one stage from an embedded entry with #defines prepended to the compiler;
  // returns a linked program from the cache, building it on first use (or, while
  // issueProgramsOnly, only handing it over: pendingPrograms); checks a handed-over program's
  // compile and link, its logs naming the files.
  Expected<GLuint> compileStage(GLenum stage, const char* entry, const std::string& defines) const;
  Expected<GLuint> program(const std::vector<std::pair<GLenum, const char*>>& stages, const std::string& defines);
  Expected<GLuint> finishProgram(const std::string& key, const PendingProgram& pending);
  Expected<GLuint> computeProgram(const char* entry, const std::string& defines = {});
  // inputs.cpp
  // `perView`: one of the frame's inputs, a 2D array of a layer a view when views > 1 (else a 2D
  // texture whatever the views: the composite's fallback).
  Status checkTexture(GLName tex, const char* what, FormatInfo::Kind kind, int minChannels,
                      FormatInfo* infoOut = nullptr, bool perView = true) const;
  Status checkInputs(const FrameInputs& in, Method method, TrafficModel* formats = nullptr) const;
  Status checkSurfaceLayout(const FrameInputs& in, const FormatInfo& materialInfo, FormatInfo* baseColorInfo) const;
  Status checkNormalDecode(const SurfaceLayout& sl, const FormatInfo& info, GLName tex) const;
  // frame.cpp: a frame's plan (which passes run, their switches and programs), its start and end;
  // passes/*.cpp: one function per pass, in the order they run.
  struct FramePlan {
    shared::SslrFrame frame{};  // the constants the passes read (frameConstants): view 0's
    std::vector<shared::SslrFrame> otherViews;  // views 1.. (ContextDesc::views > 1)
    Method method = Method::AdaptiveL;
    bool halfResolution = false, temporal = false, debugOutputs = false, collectStats = false;
    bool hitDistance = false;      // Settings::hitDistance: the trace writes hitDistanceTexture()
    bool historyConfidence = false;  // Settings::temporal.outputConfidence: the blend writes it
    bool pyramid = false;          // the trace reads the depth pyramid
    bool curvedSolids = false;     // ... with the curved quads' pass
    bool level1Pass = false;       // level 1 in a pass of its own (the last frame listed no tile)
    bool feedback = false;         // TraversalPass::Auto on a software renderer
    bool feedbackWritten = false;  // this frame's counts go to the feedback buffer
    bool deferTraversal = false;   // the traversal in the retrace pass
    bool countTraversal = false, countQuads = false;  // Auto inline: count what needed it
    bool retracePass = false, quadRetracePass = false;
    bool blur = false;
    // GlossyMode::Stochastic with the blur and temporal reuse: in a frame with history the temporal
    // blend filters the stochastic rays in place of the blur (SSLR_STOCHASTIC_FILTER).
    bool stochasticFilter = false;
    bool wideClassify = false;     // DeviceProfile::Gpu: 2x2 tiles a group, clean-up and pyramid arguments inside
    bool useHistory = false;       // temporal: the previous frame stored a history
    StatsSlot* slot = nullptr;     // Settings::debug.collectStats: this frame's ring slot
    TrafficModel traffic;          // for FrameStats' traffic (checkInputs fills the formats)
    struct {
      ClassifyPass::Programs classify;
      PyramidPass::Programs pyramid;
      TracePass::Programs trace;
      BlurPass::Programs blur;
      TemporalPass::Programs temporal;
    } programs;
  };
  // frame.cpp
  Status dispatch(std::span<const FrameInputs> in, const Settings& settings);
  Status prepare(std::span<const FrameInputs> in, const Settings& settings, const PrepareOptions& options);
  // Every view's constants (validated), the first view's in `constants`, the others' in `others`;
  // views must agree on all but their matrices.
  Status viewConstants(std::span<const FrameInputs> in, const Settings& settings, const char* call,
                       shared::SslrFrame& constants, std::vector<shared::SslrFrame>& others) const;
  void warmUp(FramePlan& plan, const FrameInputs& in);
  void recordFrame(FramePlan& plan, const FrameInputs& in, const char* debugGroup);
  void readFeedback();
  FramePlan planFrame(const Settings& settings, const shared::SslrFrame& constants,
                      bool hadHistory);
  TrafficModel trafficModel(const FramePlan& plan, TrafficModel formats, const Settings& settings) const;
  Status buildPrograms(FramePlan& plan, const FrameInputs& in, const Settings& settings);
  Expected<GLuint> optionalProgram(bool wanted, const char* entry, const std::string& defines);
  void createFrameResources(const FramePlan& plan);
  void setArea(const FrameInputs& in);
  void bindInputs(const FrameInputs& in) const;
  void beginFrame(FramePlan& plan);
  void writeTileHeader() const;
  void startNewArea();
  void beginPass(const FramePlan& plan, int pass) const;
  void finishFrame(const FramePlan& plan);
  // passes/classify.cpp
  void runClassify(const FramePlan& plan, const FrameInputs& in) const;
  // passes/pyramid.cpp
  void createPyramidResources(const FramePlan& plan);
  void bindPyramidLevels01() const;
  void buildPyramid(GLuint blockProgram, GLuint singleProgram) const;
  void runPyramid(const FramePlan& plan) const;
  // passes/trace.cpp
  void createTraceResources(const FramePlan& plan);
  void runTrace(const FramePlan& plan) const;
  void runQuads(const FramePlan& plan) const;
  // passes/blur.cpp
  void runBlur(const FramePlan& plan) const;
  // passes/temporal.cpp
  void createTemporalResources(const FramePlan& plan);
  void runTemporal(const FramePlan& plan, const FrameInputs& in);
  // composite.cpp
  Status composite(GLName framebuffer, const CompositeOptions& options);
  Status checkCompositeOptions(const CompositeOptions& options) const;
  // The draw itself, into `framebuffer` (bound and checked by the caller's guard).
  void drawComposite(GLName framebuffer, GLuint addProgram, GLuint fallbackProgram, const CompositeOptions& options) const;
  Status warmUpComposite(const PrepareOptions& options);
  Status checkCompositeTarget(GLName framebuffer) const;
  struct DrawImage {
    GLint attachment = GL_NONE, type = GL_NONE, name = 0, level = 0, width = 0, height = 0, format = GL_NONE;
    GLint componentType = GL_NONE;  // GL_FLOAT, GL_UNSIGNED_NORMALIZED, GL_INT, ...
    bool deleted = false;           // its texture or renderbuffer name was deleted while attached
  };
  // The image's problem for composite() to draw into it ("" if none): deleted, or integer (GL
  // leaves a blended draw into it undefined).
  std::string drawImageProblem(const DrawImage& image) const;
  DrawImage drawBuffer0Image(GLName framebuffer) const;
  Expected<GLuint> compositeProgram(bool overFallback);
  // An error when no GL context is current on the calling thread (every GL call would then be
  // lost, and the first texture check would blame a texture).
  Status checkCurrentContext(const char* call) const;
  // stats.cpp: reads the slots whose fence has signalled (the newest wins); with `waitNewest`,
  // first waits for the newest pending one.
  void harvestStats(bool waitNewest) const;
};

}  // namespace sslr
