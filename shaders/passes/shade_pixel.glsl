// Shading one pixel of a trace pass: its hit (from the entry file's sslrPixelHit), weighted
// (sslrReflectionWeights) and written to the reflection, the resolved output, the debug images
// and the stats; a tile with a pixel to blur is listed for the blur.

// The entry file's: the hit of pixel px (traced, reused or first-stage), false when the pixel was
// handed to a later pass, which writes its outputs. `ranTracer`: whether a ray was traced here.
bool sslrPixelHit(ivec2 px, SslrPixel q, out SslrHit hit, out bool ranTracer);

#ifdef SSLR_STOCHASTIC  // only a ray drawn from the lobe reads it (the mirror ray: a bilinear read)
// The colour at a hit vsQ, read at uvColor from the texels whose surface holds it. A plain
// bilinear read also mixes in whatever lies across a silhouette within half a pixel. Where the four
// texels around uvColor are geometry within 2% of vsQ's depth of each other, nothing does: that read.
// Elsewhere each texel counts at its bilinear weight times whether vsQ lies on its tangent plane
// (sslrGapToTexelPlane up to 3, faded out by 6); where none holds vsQ, the plain read again.
vec3 sslrSurfaceColor(vec2 uvColor, vec3 vsQ) {
  vec3 blended = textureLod(uColor, sslrTextureUv(uvColor), 0.0f).rgb;
  SslrBilinear b = sslrBilinearTexels(uvColor);
  vec3 vsTexel[4];
  bool geometry[4];
  float zNear = 1e30f, zFar = 0.0f;
  bool oneSurface = true;
  for (int i = 0; i < 4; ++i) {
    float depth = sslrLoadDepth(b.texel[i]);
    geometry[i] = sslrIsGeometryDepth(frame.surface, depth);
    vsTexel[i] = geometry[i] ? sslrViewAtPixel(b.texel[i], depth) : vec3(0.0f);
    oneSurface = oneSurface && geometry[i];
    zNear = min(zNear, abs(vsTexel[i].z));
    zFar = max(zFar, abs(vsTexel[i].z));
  }
  if (oneSurface && zFar - zNear <= 0.02f * abs(vsQ.z)) return blended;
  vec3 sum = vec3(0.0f);
  float weightSum = 0.0f;
  for (int i = 0; i < 4; ++i) {
    vec3 vsN;
    if (!(b.weight[i] > 0.0f) || !geometry[i] || !sslrDecodeNormal(frame.surface, sslrLoadNormal(b.texel[i]), vsN))
      continue;
    float w = b.weight[i] *
              (1.0f - smoothstep(3.0f, 6.0f, sslrGapToTexelPlane(frame.proj, frame.surface, vsQ, vsTexel[i], vsN)));
    sum += texelFetch(uColor, sslrTexel(b.texel[i]), 0).rgb * w;
    weightSum += w;
  }
  return weightSum > 1e-4f ? sum / weightSum : blended;
}
#endif

// Returns the dependent steps of the tracer run here (0 where none ran: FrameStats' ray work).
uint sslrShadePixel(ivec2 px) {
  SslrHit hit = sslrNoHit(SSLR_STATUS_NOT_TRACED);
  vec4 reflection = vec4(0.0f);
  float coverage = 0.0f;
  bool ranTracer = false;  // stats: half resolution answers most pixels from their quad's ray

  SslrPixel q;
  if (sslrPixelToTrace(px, q)) {
    if (!sslrPixelHit(px, q, hit, ranTracer)) {
#ifdef SSLR_COLLECT_STATS
      atomicAdd(stats.fetches, gFetches);
#endif
      return uint(hit.iterations);  // the first stage's steps (0 where none ran)
    }
    if (hit.status == SSLR_STATUS_HIT) {
      float reflectance = sslrReflectance(frame.surface, q.material);
      SslrWeights w = sslrReflectionWeights(frame.proj, frame.surface, frame.trace, hit, q.vsP, q.vsV, q.vsR,
                                            q.cosVN, reflectance, sslrRoughness(frame.surface, q.material));
      vec2 uvColor = sslrColorUv(frame.proj, frame.surface, q.vsP, q.vsR, hit.uvHit);
      // A ray drawn from the lobe is one sample of many that temporal reuse (or the host's
      // denoiser) averages: it reads the surface it hit, unmixed (sslrSurfaceColor). A mirror
      // ray's answer stands alone: the bilinear read, whose blend across a silhouette hedges a
      // hit that lands on the wrong side of it (docs/design-notes.md, "A surface-aware colour read at
      // the hit").
#ifdef SSLR_STOCHASTIC
      vec3 color = q.stochastic ? sslrSurfaceColor(uvColor, q.vsP + q.vsR * hit.L)
                                : textureLod(uColor, sslrTextureUv(uvColor), 0.0f).rgb;
#else
      vec3 color = textureLod(uColor, sslrTextureUv(uvColor), 0.0f).rgb;
#endif
      // Poisoned colour must not spread through the blur: NaN/Inf become 0, and the value is
      // kept inside RGBA16F's range.
      if (any(isnan(color)) || any(isinf(color))) color = vec3(0.0f);
      color = clamp(color, vec3(0.0f), vec3(60000.0f));
      color = sslrClampLuminance(color, frame.trace.maxLuminance);
      float blurWeight = sslrFilteredByTemporalBlend(q) ? 0.0f : w.blurWeight;
#ifdef SSLR_COLORED_F0
      vec3 f0 = sslrColoredF0At(px, q.material, reflectance);
      reflection = vec4(color * (sslrFresnelColored(frame.trace, f0, q.cosVN) * w.coverage), blurWeight);
#else
      reflection = vec4(color * w.reflection, blurWeight);
#endif
      coverage = w.coverage;
    }
  }
  imageStore(uReflection, sslrTexel(px), reflection);
  // Resolved before the blur: the same rgb with the coverage in alpha (the blur reads it from here).
  imageStore(uResolved, sslrTexel(px), vec4(reflection.rgb, coverage));
#if defined(SSLR_DEBUG_OUTPUTS) || defined(SSLR_TEMPORAL_HITS)
  imageStore(uHit, sslrTexel(px), vec4(hit.uvHit, hit.confidence, hit.L));
#endif
#ifdef SSLR_DEBUG_OUTPUTS
  imageStore(uIterations, sslrTexel(px), vec4(float(hit.iterations)));
#endif
#ifdef SSLR_HIT_DISTANCE
  // A guess (sslrHiddenGuess, sslrSlabGuess) is stored negated: |value| is where the ray went out
  // of sight, short of the hidden point it meets, and a denoiser can tell it from a crossing.
  imageStore(uHitDistance, sslrTexel(px), vec4(coverage > 0.0f ? (hit.guessed != 0 ? -hit.L : hit.L) : 0.0f));
#endif
#ifdef SSLR_COLLECT_STATS
  if (ranTracer) atomicAdd(stats.tracedPixels, 1u);
  atomicAdd(stats.fetches, gFetches);
  if (hit.hierarchical != 0) atomicAdd(stats.hierarchicalPixels, 1u);
#endif
  // The first pixel of a tile that needs blurring lists the tile (no group barrier: on CPU
  // rasterizers barriers split the shader and cost more than this atomic).
  if (reflection.a * frame.trace.maxRadiusPx >= 0.5f) sslrListTileForBlur(px);
  return ranTracer ? uint(hit.iterations) : 0u;
}
