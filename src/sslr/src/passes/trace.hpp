// Pass 3's state: the trace's own images and lists (half resolution's quad records, the retrace
// list) and the debug and engine outputs it writes besides the reflection. Code: trace.cpp.
#pragma once

#include "../gl_functions.hpp"

namespace sslr {

struct TracePass {
  // Half resolution: per 2x2 quad, its ray's hit and surfaces (created on first use).
  GLuint quadHit = 0, quadSurface = 0;
  // The retrace list (passes/retrace_list.glsl): half resolution and the deferred traversal.
  GLuint retraceList = 0;
  // Written where a frame asks for them (created on first use): the hit record (debug outputs,
  // temporal reuse), the iterations (debug outputs) and the hit distance (Settings::hitDistance).
  GLuint hit = 0, iterations = 0, hitDistance = 0;

  // The programs a frame runs (FramePlan::programs).
  struct Programs {
    GLuint trace = 0;        // 3_trace.comp, or at half resolution 3_shade_from_quads.comp
    GLuint quads = 0;        // 3_trace_quads.comp (half resolution)
    GLuint quadRetrace = 0;  // 3_trace_quads.comp's retrace role (half resolution, deferred traversal)
    GLuint retrace = 0;      // 3_trace.comp's retrace role (half resolution or deferred traversal)
    bool retraceRole = false;      // trace is the retrace's program too, played in its tile role
    bool quadRetraceRole = false;  // quads is the quad retrace's program too, likewise
  };

  void destroy(const detail::Gl& gl);
};

}  // namespace sslr
