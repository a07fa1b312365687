// Pass 2's state: the min-max depth pyramid the traversal reads (sslr_shared.h, "Min-max depth
// pyramid") and the curved solids' quad list. Code: pyramid.cpp.
#pragma once

#include "../gl_functions.hpp"

namespace sslr {

struct PyramidPass {
  // Mip m holds level m (level 0 also holds the pixels' curved extra depths). Its base is padded
  // so that every mip halves exactly: mip m has at least ceil(size / 2^m) cells per axis. Created
  // by the first dispatch that traces it.
  GLuint texture = 0;
  int levels = 0;                         // levels above level 0
  int level1Width = 0, level1Height = 0;  // level 1's size (padded)
  // The curved solids (thickness.h): the list of quads whose normals turn, whose level-1 cells
  // and level-0 texels the curved pass (2_pyramid_curved.comp) writes (created on first use).
  GLuint curvedQuads = 0;

  // The programs a frame runs (FramePlan::programs).
  struct Programs {
    GLuint arguments = 0;  // 2_pyramid_arguments.comp (Software; the wide classification sets them)
    GLuint level1 = 0;     // 2_pyramid_levels01.comp (after a frame that listed no tile)
    GLuint curved = 0;     // 2_pyramid_curved.comp
    GLuint block = 0;      // 2_pyramid_levels2to7.comp
    GLuint single = 0;     // 2_pyramid_top_level.comp (a screen 2048 px or more across)
  };

  void destroy(const detail::Gl& gl);
};

}  // namespace sslr
