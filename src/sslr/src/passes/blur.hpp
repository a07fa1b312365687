// Pass 4's state: the separable blur's two programs. It blurs the context's resolved image
// through its scratch image (Context::Impl::scratch), and owns no resource of its own. Code:
// blur.cpp.
#pragma once

#include "../gl_functions.hpp"

namespace sslr {

struct BlurPass {
  // The programs a frame runs (FramePlan::programs): 4_blur.comp along each axis.
  struct Programs {
    GLuint horizontal = 0, vertical = 0;
  };
};

}  // namespace sslr
