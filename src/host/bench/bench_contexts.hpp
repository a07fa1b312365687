// sslr-bench's contexts, one per configuration (internal to the sslr_bench_engine library).
#pragma once

#include <memory>
#include <vector>

#include "sslr/sslr.hpp"
#include "sslr_host/egl_context.hpp"

namespace sslr::host {

// One sslr context per timed configuration, created on first use (at one size). A context keeps
// state from frame to frame, as a host's does: TraversalPass::Auto follows the traversal share
// its previous frames fed back, the clean-up the tiles they listed. Timed through one shared
// context, each configuration would run in the state the one before it left (integration.md,
// "ContextDesc::traversalPass").
class ConfigContexts {
 public:
  ConfigContexts(int width, int height) : width_(width), height_(height) {}
  // `shapes`: the pass shapes (ContextDesc's device, traversalPass, oneBodyTraversal, occupancyExit).
  Expected<Context*> get(size_t config, const ContextDesc& shapes = {}) {
    if (contexts_.size() <= config) contexts_.resize(config + 1);
    if (!contexts_[config]) {
      ContextDesc d = shapes;
      d.width = width_;
      d.height = height_;
      d.views = 1;
      d.getProcAddress = HeadlessContext::getProcAddress();
      auto c = Context::create(d);
      if (!c) return Status::error(c.error());
      contexts_[config] = std::move(c.value());
    }
    return contexts_[config].get();
  }

 private:
  int width_, height_;
  std::vector<std::unique_ptr<Context>> contexts_;
};

}  // namespace sslr::host
