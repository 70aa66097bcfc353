// The scalar tile loop (Li per sample) and the oracle traversal backend of the packet path;
// the packet path itself (the wavefront) is in wavefront.cpp.
#include "engine/render/packet_render.h"

#include "engine/bvh/intersect1.h"

namespace ptlab {
namespace {

constexpr int kLanes = static_cast<int>(kPacketWidth);

inline bool Lane(Mask8 m, int j) { return ((m >> j) & 1u) != 0; }

// Lane j of a packet as a single ray.
Ray LaneRay(const RayPacket8& rays, int j) {
  return Ray{{rays.org_x[j], rays.org_y[j], rays.org_z[j]},
             {rays.dir_x[j], rays.dir_y[j], rays.dir_z[j]},
             rays.t_min[j],
             rays.t_max[j]};
}

Mask8 ScalarIntersect8(const void* accel, const RayPacket8& rays, Mask8 active, HitPacket8* hits) {
  const Bvh& bvh = *static_cast<const Bvh*>(accel);
  Mask8 got = 0;
  for (int j = 0; j < kLanes; ++j) {
    if (!Lane(active, j)) continue;
    const Ray r = LaneRay(rays, j);
    Hit h;
    if (!Intersect1(bvh, r, &h)) continue;
    hits->t[j] = h.t, hits->b1[j] = h.b1, hits->b2[j] = h.b2, hits->prim[j] = h.prim;
    got |= 1u << j;
  }
  return got;
}

Mask8 ScalarOccluded8(const void* accel, const RayPacket8& rays, Mask8 active) {
  const Bvh& bvh = *static_cast<const Bvh*>(accel);
  Mask8 got = 0;
  for (int j = 0; j < kLanes; ++j) {
    if (!Lane(active, j)) continue;
    const Ray r = LaneRay(rays, j);
    if (Occluded1(bvh, r)) got |= 1u << j;
  }
  return got;
}

}  // namespace

TraversalBackend8 ScalarTraversalBackend(const Bvh& bvh) {
  TraversalBackend8 b;
  b.accel = &bvh;
  b.intersect8 = ScalarIntersect8;
  b.occluded8 = ScalarOccluded8;
  b.name = "scalar-oracle";
  return b;
}

void RenderTileScalar(const RenderContext& ctx, const Camera& camera, const PixelFilter& filter,
                      int x0, int y0, int x1, int y1, uint32_t s_begin, uint32_t s_end,
                      uint64_t seed, FilmBlock* block, TileSampleStats* stats,
                      const PixelSampling* pixels) {
  RayCounters counters;
  const uint64_t width = uint64_t(camera.width());
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const uint64_t pixel = uint64_t(y) * width + uint64_t(x);
      if (pixels && pixels->active && !pixels->active[pixel]) continue;
      PixelMoments* moments = pixels && pixels->moments ? &pixels->moments[pixel] : nullptr;
      for (uint32_t s = s_begin; s < s_end; ++s) {
        PathSampler sampler(ctx.scene.sampler.type, PixelSeed(seed, pixel), s);
        const Vec2f jitter = sampler.Get2D(kDimensionPixel);
        const Vec2f lens = sampler.Get2D(kDimensionLens);
        const float sx = float(x) + jitter.x, sy = float(y) + jitter.y;
        const Ray ray = camera.GenerateRay(sx, sy, lens);
        const Color3f L = Li(ctx, ray, sampler, &counters);
        if (moments) AddPixelSample(L, moments);
        if (!IsFinite(L)) {
          if (stats->nonfinite++ == 0) stats->first_x = x, stats->first_y = y;
          continue;
        }
        block->Splat(filter, sx, sy, L);
      }
    }
  }
  stats->rays += counters.rays;
}

}  // namespace ptlab
