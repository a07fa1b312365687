// Pass 5's state (Settings::temporal): the previous frame's output and its keys. Code:
// temporal.cpp.
#pragma once

#include "../gl_functions.hpp"

namespace sslr {

struct TemporalPass {
  // The history and its keys (sslrHistoryKey; 0 = none), created on first use. valid: the last
  // dispatch stored them.
  GLuint color = 0, key = 0;
  GLuint confidence = 0;  // Settings::temporal.outputConfidence: history's share per pixel
  bool valid = false;

  // The programs a frame runs (FramePlan::programs).
  struct Programs {
    GLuint blend = 0;    // 5_temporal_blend.comp
    GLuint store = 0;    // 5_temporal_store.comp
    GLuint cleanup = 0;  // 5_clear_untraced_history.comp
  };

  void destroy(const detail::Gl& gl);
};

}  // namespace sslr
