// Pass 2, the min-max depth pyramid (passes/pyramid.hpp; sslr_shared.h, "Min-max depth
// pyramid"): its arguments, level 1 where classification left it, the curved quads' cells,
// levels 2 and up.
#include <algorithm>

#include "../context_impl.hpp"

namespace sslr {

// The pyramid (~10.7 B per pixel) and the curved quads' list, on first use: a host that never
// traces the pyramid (the tutorial's method, adaptive L alone) never pays for it.
void Context::Impl::createPyramidResources(const FramePlan& f) {
  if (f.curvedSolids && pyramid.curvedQuads == 0) {
    gl.CreateBuffers(1, &pyramid.curvedQuads);  // header (passes/curved_quads.glsl) + one entry per quad
    gl.NamedBufferStorage(pyramid.curvedQuads, static_cast<GLsizeiptr>((8 + static_cast<size_t>(pyramid.level1Width) * pyramid.level1Height * views) * sizeof(GLuint)),
                          nullptr, GL_DYNAMIC_STORAGE_BIT);
    label(GL_BUFFER, pyramid.curvedQuads, "sslr.curvedQuads");
  }
  if (!f.pyramid || pyramid.texture != 0) return;
  pyramid.texture = createTexture(GL_RG32F, pyramid.levels + 1, 2 * pyramid.level1Width, 2 * pyramid.level1Height);
  label(GL_TEXTURE, pyramid.texture, "sslr.depthPyramid");
  // Levels 0 and 1 past the screen (padding) are never written: neutral once and for all (level
  // 0's are never read either: the traversal stays on the screen).
  const float hizEmpty[4] = {2.0f, -1.0f, 0.0f, 0.0f};  // sslrHiZEmpty
  for (int mip = 0; mip <= 1; ++mip) gl.ClearTexImage(pyramid.texture, mip, GL_RG, GL_FLOAT, hizEmpty);
}

void PyramidPass::destroy(const detail::Gl& gl) {
  gl.DeleteTextures(1, &texture);
  gl.DeleteBuffers(1, &curvedQuads);
  texture = curvedQuads = 0;
}

// Pass 2: the depth pyramid, when the trace reads it: its dispatch arguments (zero groups unless a
// tile was listed), level 1 where classification left it, the curved quads' cells, levels 2+.
void Context::Impl::runPyramid(const FramePlan& f) const {
  beginPass(f, 1);
  if (!f.pyramid) return;
  if (!f.wideClassify) {  // (Gpu: classification set the arguments)
    useProgram(f.programs.pyramid.arguments);
    dispatchCompute(1, 1, 1);
    memoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  }
  if (f.level1Pass) {  // level 1 (2_pyramid_levels01.comp) through level 1's pyramid arguments
    useProgram(f.programs.pyramid.level1);
    bindPyramidLevels01();  // (the clean-up pass took image unit 0)
    dispatchComputeIndirect(kHizDispatchOffset);
    memoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                  GL_COMMAND_BARRIER_BIT);
  }
  if (f.curvedSolids) {  // the listed quads' cells with their solids (2_pyramid_curved.comp)
    useProgram(f.programs.pyramid.curved);
    bindPyramidLevels01();
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, pyramid.curvedQuads);
    dispatchComputeIndirect(0);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileBuffer);
    memoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  buildPyramid(f.programs.pyramid.block, f.programs.pyramid.single);
}

// Levels 0 and 1 of the pyramid, as classification, the level-1 pass and the curved pass write
// them (passes/pyramid_levels01.glsl): image units 1 and 0.
void Context::Impl::bindPyramidLevels01() const {
  bindImage(SSLR_IMAGE_PYRAMID_LEVEL1, pyramid.texture, 1, GL_RG32F);
  bindImage(SSLR_IMAGE_PYRAMID_LEVEL0, pyramid.texture, 0, GL_RG32F);
}

// The min-max depth pyramid above level 1, indirect: the group counts are zero unless
// classification listed a tile (common/tiles.glsl). One dispatch builds levels 2..7 (2_pyramid_levels2to7.comp, a
// work group per level-7 cell), a second level 8 where the screen has one.
void Context::Impl::buildPyramid(GLuint blockProgram, GLuint singleProgram) const {
  const int blockTop = std::min(area.levels, kHizBlockTop);
  useProgram(blockProgram);
  gl.bindTexture2D(SSLR_UNIT_PYRAMID, pyramid.texture);
  gl.BindSampler(SSLR_UNIT_PYRAMID, nearestSampler);
  gl.ProgramUniform1i(blockProgram, 0, area.levels);  // uTopLevel
  for (int level = 2; level <= kHizBlockTop; ++level)  // above the top: the top's image, never stored to
    bindImage(static_cast<GLuint>(SSLR_IMAGE_PYRAMID_BLOCK + level - 2), pyramid.texture, std::min(level, blockTop), GL_RG32F);
  dispatchComputeIndirect(kHizDispatchOffset + 3 * 4 * 1);  // level 2's arguments: the blocks
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  const int single = kHizBlockTop + 1;  // (SSLR_HIZ_MAX_LEVELS is 8: one level at most above the blocks)
  if (area.levels < single) return;
  useProgram(singleProgram);
  gl.ProgramUniform1i(singleProgram, 0, single);
  bindImage(SSLR_IMAGE_PYRAMID_BLOCK, pyramid.texture, single, GL_RG32F);
  dispatchComputeIndirect(kHizDispatchOffset + 3 * 4 * (single - 1));  // its level's arguments
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace sslr
