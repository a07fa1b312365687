// sslr-bench's timing, shared by the benchmark's parts (internal to the sslr_bench_engine library).
#pragma once

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "sslr_host/gl.hpp"

namespace sslr::host {

// Times one call: wall clock around glFinish on software renderers (timer queries are
// meaningless on llvmpipe), GL_TIME_ELAPSED on hardware.
class Timer {
 public:
  explicit Timer(bool software) : software_(software) {
    if (!software_) glCreateQueries(GL_TIME_ELAPSED, 1, &query_);
  }
  ~Timer() {
    if (query_ != 0) glDeleteQueries(1, &query_);
  }
  bool software() const { return software_; }
  // Calls per sample: `requested`, or by default 8 on a GPU (a lone dispatch there also times the
  // CPU issuing it: up to 3x the GPU's time on the H100) and 1 on a software renderer.
  int repeats(int requested) const { return requested > 0 ? requested : (software_ ? 1 : 8); }
  std::string method() const {
    return software_ ? "wall clock around glFinish (software renderer)" : "GL_TIME_ELAPSED";
  }
  // The time of one call of `fn`, from `repeats` calls back to back. On a GPU a lone call on an
  // idle GPU also times the CPU issuing its commands (the GPU runs each as it arrives); repeated,
  // the issuing of one call overlaps the GPU work of the previous ones.
  template <typename Fn>
  double timeMs(Fn&& fn, int repeats = 1) {
    if (software_) {
      glFinish();
      const auto t0 = std::chrono::steady_clock::now();
      for (int i = 0; i < repeats; ++i) fn();
      glFinish();
      return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / repeats;
    }
    glBeginQuery(GL_TIME_ELAPSED, query_);
    for (int i = 0; i < repeats; ++i) fn();
    glEndQuery(GL_TIME_ELAPSED);
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query_, GL_QUERY_RESULT, &ns);
    return static_cast<double>(ns) * 1e-6 / repeats;
  }

 private:
  bool software_;
  GLuint query_ = 0;
};

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace sslr::host
