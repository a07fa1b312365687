// The glossy study (internal to sslr_bench_engine): see glossy_study.cpp.
#pragma once

#include <string>
#include <vector>

#include "bench_timer.hpp"
#include "sslr_host/benchmark.hpp"

namespace sslr::host {

// Appends one GlossyPoint per configuration on `sceneSpec` ("name" or "name@roughR") and writes
// the reference and each configuration's error map to reportDir.
Status runGlossyStudy(const std::string& sceneSpec, const BenchOptions& options, Timer& timer,
                      const std::string& reportDir, std::vector<GlossyPoint>& out);

}  // namespace sslr::host
