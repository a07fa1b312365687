// The ray work of a trace dispatch (FrameStats::RayWork, Settings::debug.collectStats): each lane's
// dependent steps (the tracer's iterations: one fetch each whose result decides the next), and
// what SIMT hardware pays for them: a group of lanes runs as long as its slowest lane, so the work
// is the sum over 32- and over 64-lane groups, in the dispatch's own group shape (invocations
// 0-31 and 32-63 of a group form its 32-lane groups), of the group's largest count. A group
// smaller than 32 or 64 lanes fills one such group alone. Counted with a group barrier: called
// once by every invocation of the group, in uniform control flow. Without stats: a no-op.
#ifdef SSLR_COLLECT_STATS
shared uint sRayWorkMax[3];  // the two 32-lane halves, the whole group
shared uint sRayWorkSum;

void sslrCountRayWork(uint slot, uint steps) {
  uint lane = gl_LocalInvocationIndex;
  if (lane == 0u) {
    sRayWorkMax[0] = 0u;
    sRayWorkMax[1] = 0u;
    sRayWorkMax[2] = 0u;
    sRayWorkSum = 0u;
  }
  barrier();
  atomicMax(sRayWorkMax[min(lane / 32u, 1u)], steps);
  atomicMax(sRayWorkMax[2], steps);
  atomicAdd(sRayWorkSum, steps);
  barrier();
  if (lane == 0u && sRayWorkMax[2] > 0u) {
    uint base = slot * uint(SSLR_RAY_WORK_FIELDS);
    atomicAdd(stats.rayWork[base + SSLR_RAY_WORK_LANE_STEPS], sRayWorkSum);
    atomicAdd(stats.rayWork[base + SSLR_RAY_WORK_SIMT32], sRayWorkMax[0] + sRayWorkMax[1]);
    atomicAdd(stats.rayWork[base + SSLR_RAY_WORK_SIMT64], sRayWorkMax[2]);
    atomicMax(stats.rayWork[base + SSLR_RAY_WORK_CHAIN], sRayWorkMax[2]);
    atomicAdd(stats.rayWork[base + SSLR_RAY_WORK_GROUPS], 1u);
  }
}
#else
void sslrCountRayWork(uint slot, uint steps) {}
#endif
