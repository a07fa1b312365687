// Pass 1's state: classification (1_classify.comp, 1_classify_wide.comp) and the clean-up of the
// previous frame's tiles (1_clear_untraced.comp). It writes the frame's tile list (the context's
// tile buffer) and, with the pyramid, its levels 0 and 1 (PyramidPass::texture); it owns no
// resource of its own. Code: classify.cpp.
#pragma once

#include "../gl_functions.hpp"

namespace sslr {

struct ClassifyPass {
  // The programs a frame runs (FramePlan::programs).
  struct Programs {
    GLuint classify = 0;
    GLuint cleanup = 0;  // DeviceProfile::Software (the wide classification cleans up itself)
  };
};

}  // namespace sslr
