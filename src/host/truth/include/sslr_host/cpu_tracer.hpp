// The tracers of shaders/sslr_trace*.h run on the CPU over a read-back G-buffer: the very code
// the GPU runs (one source of truth), used to check GPU/CPU agreement and to compare the
// depth-only representation with stored positions under the same tracer.
#pragma once

#include "sslr/sslr.hpp"
#include "sslr_host/ground_truth.hpp"
#include "sslr_host/image_io.hpp"

namespace sslr::host {

struct CpuGBuffer {
  const Image* depth = nullptr;         // 1 channel, raw window depth
  const Image* normalPacked = nullptr;  // 4 channels as stored
  const Image* positions = nullptr;     // optional RGBA view positions (w = 1 on geometry)
  const Image* backDepth = nullptr;     // FrameInputs::backDepthTexture's contents, when it is given
};

enum class SurfaceSource {
  Depth,            // rebuild positions from depth (sslr's depth-only representation)
  StoredPositions,  // read them from the position texture (the tutorial's representation)
};

// Runs settings.method's tracer for every pixel; returns the hit image (RG uv, B confidence, A L).
// The tracer reads surfaces from `source` (AdaptiveL only; PositionBuffer always reads positions).
Image traceOnCpu(const CpuGBuffer& g, const FrameInputs& in, const Settings& settings,
                 SurfaceSource source = SurfaceSource::Depth);

// The reflection a tracer that found every visible reflection exactly would write (rgb, before
// the blur): the colour at the true hit (bilinear) x the shared header's weights for that hit
// (Fresnel term and fades; confidence 1); 0 where the truth has nothing visible to reflect.
Image idealReflection(const CpuGBuffer& g, const Image& color, const GroundTruth& truth, const FrameInputs& in,
                      const Settings& settings);

}  // namespace sslr::host
