// The views study (internal to sslr_bench_engine): see views_study.cpp.
#pragma once

#include <string>
#include <vector>

#include "bench_timer.hpp"
#include "sslr_host/benchmark.hpp"

namespace sslr::host {

// Appends the three ViewsPoints (one view, a context a view, one context of every view) of
// `sceneName` seen by BenchOptions::viewsCount eyes.
Status runViewsStudy(const std::string& sceneName, const BenchOptions& options, Timer& timer,
                     std::vector<ViewsPoint>& out);

}  // namespace sslr::host
