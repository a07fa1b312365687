// The temporal study (internal to sslr_bench_engine): see temporal_study.cpp.
#pragma once

#include <string>
#include <vector>

#include "bench_timer.hpp"
#include "sslr_host/benchmark.hpp"

namespace sslr::host {

// Appends one TemporalPoint per configuration and frame of the camera path on `sceneName`.
Status runTemporalStudy(const std::string& sceneName, const BenchOptions& options, Timer& timer,
                        std::vector<TemporalPoint>& out);

}  // namespace sslr::host
