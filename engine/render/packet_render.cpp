// 8-wide render path: packets of camera, bounce and shadow rays through a traversal backend,
// shading lane by lane with the scalar integrators' operations in the scalar order.
#include "engine/render/packet_render.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "engine/bvh/intersect1.h"
#include "engine/render/integrator_common.h"
#include "engine/render/interaction.h"

namespace ptlab {
namespace {

using integrator::Emitted;
using integrator::EmitterPdf;
using integrator::EmitterSampleRequest;
using integrator::EmitterSampleResult;
using integrator::Escaped;
using integrator::kInfinity;
using integrator::kWhittedContinuation;
using integrator::kWhittedMaxDepth;
using integrator::MisWeight;
using integrator::Next2D;
using integrator::PrepareEmitterSample;
using integrator::SpawnOrigin;
using Type = IntegratorDesc::Type;

constexpr int kLanes = static_cast<int>(kPacketWidth);

inline bool Lane(Mask8 m, int j) { return ((m >> j) & 1u) != 0; }

// Sends up to eight rays to the backend as one packet and counts them.
class PacketTracer {
 public:
  PacketTracer(const TraversalBackend8& backend, uint64_t* rays) : backend_(backend), rays_(rays) {}

  Mask8 Intersect(const Ray* rays, Mask8 active, Hit* hits) {
    if (active == 0) return 0;
    const RayPacket8 p = Pack(rays, active);
    HitPacket8 h;
    const Mask8 got = backend_.intersect8(backend_.accel, p, active, &h) & active;
    for (Mask8 m = got; m != 0; m &= m - 1) {
      const int j = std::countr_zero(m);
      hits[j] = Hit{h.t[j], h.b1[j], h.b2[j], h.prim[j]};
    }
    *rays_ += static_cast<uint64_t>(std::popcount(active));
    return got;
  }

  Mask8 Occluded(const Ray* rays, Mask8 active) {
    if (active == 0) return 0;
    *rays_ += static_cast<uint64_t>(std::popcount(active));
    return backend_.occluded8(backend_.accel, Pack(rays, active), active) & active;
  }

 private:
  static RayPacket8 Pack(const Ray* rays, Mask8 active) {
    RayPacket8 p{};
    for (int j = 0; j < kLanes; ++j) {
      if (!Lane(active, j)) continue;
      const Ray& r = rays[j];
      p.org_x[j] = r.o.x, p.org_y[j] = r.o.y, p.org_z[j] = r.o.z;
      p.dir_x[j] = r.d.x, p.dir_y[j] = r.d.y, p.dir_z[j] = r.d.z;
      p.t_min[j] = r.t_min, p.t_max[j] = r.t_max;
    }
    return p;
  }

  const TraversalBackend8& backend_;
  uint64_t* rays_;
};

// Shadow tests for one prepared emitter sample per lane in `lanes`; returns the occluded lanes.
Mask8 TraceShadows(PacketTracer& tracer, const EmitterSampleRequest* req, Mask8 lanes) {
  Ray shadow[kLanes];
  Mask8 traced = 0;
  for (Mask8 m = lanes; m != 0; m &= m - 1) {
    const int j = std::countr_zero(m);
    if (!req[j].traced) continue;
    shadow[j] = req[j].shadow;
    traced |= 1u << j;
  }
  return tracer.Occluded(shadow, traced);
}

// Each Shade* function mirrors the scalar Li* of integrator.cpp for the lanes in `active`,
// with every Trace / Occluded1 replaced by a packet over the lanes that need it.

void ShadeNormals(const Scene& scene, PacketTracer& tracer, const Ray* rays, Mask8 active,
                  Color3f* L) {
  Hit hits[kLanes];
  const Mask8 hit = tracer.Intersect(rays, active, hits);
  for (Mask8 m = active; m != 0; m &= m - 1) {
    const int j = std::countr_zero(m);
    if (!Lane(hit, j)) {
      L[j] = {};
      continue;
    }
    const Vec3f n = Abs(MakeInteraction(scene, hits[j]).frame.n);
    L[j] = {n.x, n.y, n.z};
  }
}

void ShadeDirect(const Scene& scene, PacketTracer& tracer, const Ray* rays, Pcg32* rng,
                 Mask8 active, Type type, Color3f* L) {
  const bool mis = type == Type::kDirectMis;
  Hit hits[kLanes];
  const Mask8 hit = tracer.Intersect(rays, active, hits);
  SurfaceInteraction its[kLanes];
  EmitterSampleRequest req[kLanes];
  BsdfSample bs[kLanes];
  Ray next[kLanes];
  Vec3f wi[kLanes];
  Mask8 emitter_lanes = 0, bounce_lanes = 0;
  for (Mask8 m = active; m != 0; m &= m - 1) {
    const int j = std::countr_zero(m);
    const Ray& ray = rays[j];
    if (!Lane(hit, j)) {
      L[j] = Escaped(scene, ray.d / Length(ray.d), false, 0.0f);
      continue;
    }
    its[j] = MakeInteraction(scene, hits[j]);
    const Vec3f wo_world = -ray.d / Length(ray.d);
    L[j] = Emitted(scene, its[j], wo_world);
    const Vec3f wo = its[j].frame.ToLocal(wo_world);
    if (type != Type::kDirectMats) {
      req[j] = PrepareEmitterSample(scene, its[j], wo, mis, rng[j]);
      emitter_lanes |= 1u << j;
    }
    if (type == Type::kDirectEms) continue;
    const float u1 = rng[j].NextFloat();
    if (!BsdfSampleDirection(scene.materials, its[j].material, wo, u1, Next2D(rng[j]), &bs[j])) {
      continue;
    }
    wi[j] = its[j].frame.ToWorld(bs[j].wi);
    next[j] = Ray{SpawnOrigin(its[j], wi[j]), wi[j], 0.0f, kInfinity};
    bounce_lanes |= 1u << j;
  }
  const Mask8 occluded = TraceShadows(tracer, req, emitter_lanes);
  Hit hits2[kLanes];
  const Mask8 hit2 = tracer.Intersect(next, bounce_lanes, hits2);
  for (Mask8 m = emitter_lanes; m != 0; m &= m - 1) {
    const int j = std::countr_zero(m);
    L[j] += EmitterSampleResult(req[j], Lane(occluded, j));
  }
  for (Mask8 m = bounce_lanes; m != 0; m &= m - 1) {
    const int j = std::countr_zero(m);
    if (!Lane(hit2, j)) {
      if (type == Type::kDirectMats) {
        L[j] = L[j] + bs[j].weight * Escaped(scene, wi[j], false, 0.0f);
      } else {
        L[j] = L[j] + bs[j].weight * Escaped(scene, wi[j], mis && !bs[j].delta, bs[j].pdf);
      }
      continue;
    }
    const SurfaceInteraction light = MakeInteraction(scene, hits2[j]);
    const Color3f Le = Emitted(scene, light, -wi[j]);
    if (IsBlack(Le)) continue;
    float weight = 1.0f;
    if (mis && !bs[j].delta) {
      const float pdf_light = EmitterPdf(scene, light, its[j].p);
      weight = MisWeight(bs[j].pdf, pdf_light, scene.integrator.power_heuristic);
    }
    L[j] = L[j] + bs[j].weight * Le * weight;
  }
}

// Whitted recursion unrolled: each lane keeps its chain of (Le, weight) through delta
// bounces and folds it from the innermost level outwards, as the recursion's returns do.
void ShadeWhitted(const Scene& scene, PacketTracer& tracer, const Ray* camera_rays, Pcg32* rng,
                  Mask8 active, Color3f* L) {
  struct Level {
    Color3f Le, weight;
  };
  static thread_local std::vector<Level> chain(size_t{kLanes} * (kWhittedMaxDepth + 1));
  int depth_of[kLanes] = {};
  Color3f terminal[kLanes];
  Ray ray[kLanes];
  for (int j = 0; j < kLanes; ++j) ray[j] = camera_rays[j];
  Mask8 alive = active;
  while (alive != 0) {
    Hit hits[kLanes];
    const Mask8 hit = tracer.Intersect(ray, alive, hits);
    EmitterSampleRequest req[kLanes];
    Mask8 emitter_lanes = 0;
    for (Mask8 m = alive; m != 0; m &= m - 1) {
      const int j = std::countr_zero(m);
      const int depth = depth_of[j];
      if (!Lane(hit, j)) {
        terminal[j] = Escaped(scene, ray[j].d / Length(ray[j].d), false, 0.0f);
        alive &= ~(1u << j);
        continue;
      }
      const SurfaceInteraction its = MakeInteraction(scene, hits[j]);
      const Vec3f wo_world = -ray[j].d / Length(ray[j].d);
      const Color3f Le = Emitted(scene, its, wo_world);
      const Vec3f wo = its.frame.ToLocal(wo_world);
      if (!IsDeltaMaterial(its.material.tag())) {
        terminal[j] = Le;
        req[j] = PrepareEmitterSample(scene, its, wo, /*mis=*/false, rng[j]);
        emitter_lanes |= 1u << j;
        alive &= ~(1u << j);
        continue;
      }
      if (depth >= kWhittedMaxDepth || rng[j].NextFloat() >= kWhittedContinuation) {
        terminal[j] = Le;
        alive &= ~(1u << j);
        continue;
      }
      BsdfSample bs;
      const float u1 = rng[j].NextFloat();
      if (!BsdfSampleDirection(scene.materials, its.material, wo, u1, Next2D(rng[j]), &bs)) {
        terminal[j] = Le;
        alive &= ~(1u << j);
        continue;
      }
      const Vec3f wi = its.frame.ToWorld(bs.wi);
      chain[size_t{kLanes} * depth + j] = {Le, bs.weight};
      ray[j] = Ray{SpawnOrigin(its, wi), wi, 0.0f, kInfinity};
      depth_of[j] = depth + 1;
    }
    const Mask8 occluded = TraceShadows(tracer, req, emitter_lanes);
    for (Mask8 m = emitter_lanes; m != 0; m &= m - 1) {
      const int j = std::countr_zero(m);
      terminal[j] = terminal[j] + EmitterSampleResult(req[j], Lane(occluded, j));
    }
  }
  for (Mask8 m = active; m != 0; m &= m - 1) {
    const int j = std::countr_zero(m);
    Color3f acc = terminal[j];
    for (int k = depth_of[j] - 1; k >= 0; --k) {
      const Level& level = chain[size_t{kLanes} * k + j];
      acc = level.Le + level.weight * acc * (1.0f / kWhittedContinuation);
    }
    L[j] = acc;
  }
}

void ShadePath(const Scene& scene, PacketTracer& tracer, const Ray* camera_rays, Pcg32* rng,
               Mask8 active, Type type, Color3f* L) {
  const IntegratorDesc& desc = scene.integrator;
  const bool nee = type != Type::kPathMats, mis = type == Type::kPathMis;
  const int light_samples = std::max(1, desc.light_samples);
  static thread_local std::vector<EmitterSampleRequest> requests;
  requests.resize(size_t(light_samples) * kLanes);
  Ray ray[kLanes];
  Color3f throughput[kLanes];
  float eta[kLanes];
  bool specular_bounce[kLanes];
  float prev_pdf[kLanes];
  Vec3f prev_p[kLanes];
  for (int j = 0; j < kLanes; ++j) {
    ray[j] = camera_rays[j];
    L[j] = {};
    throughput[j] = {1, 1, 1};
    eta[j] = 1.0f;
    specular_bounce[j] = true;  // the camera ray counts as specular: emission is always seen
    prev_pdf[j] = 0.0f;
  }
  Mask8 alive = active;
  for (int depth = 0; alive != 0; ++depth) {
    Hit hits[kLanes];
    const Mask8 hit = tracer.Intersect(ray, alive, hits);
    Mask8 nee_lanes = 0;
    Color3f nee_throughput[kLanes];
    for (Mask8 m = alive; m != 0; m &= m - 1) {
      const int j = std::countr_zero(m);
      const Mask8 bit = 1u << j;
      if (!Lane(hit, j)) {
        // Escaped: environment light, counted unless emitter sampling already did (ems after
        // a non-specular bounce), MIS-weighted for path_mis.
        const Vec3f w = ray[j].d / Length(ray[j].d);
        if (!nee || specular_bounce[j])
          L[j] += throughput[j] * Escaped(scene, w, false, 0.0f);
        else if (mis)
          L[j] += throughput[j] * Escaped(scene, w, true, prev_pdf[j]);
        alive &= ~bit;
        continue;
      }
      const SurfaceInteraction its = MakeInteraction(scene, hits[j]);
      const Vec3f wo_world = -ray[j].d / Length(ray[j].d);
      const Color3f Le = Emitted(scene, its, wo_world);
      if (!IsBlack(Le)) {
        float w = 1.0f;
        if (nee && !specular_bounce[j]) {
          // Emitter sampling already counted this light from the previous vertex.
          w = mis ? MisWeight(prev_pdf[j], EmitterPdf(scene, its, prev_p[j]), desc.power_heuristic)
                  : 0.0f;
        }
        L[j] += throughput[j] * Le * w;
      }
      if (desc.max_depth >= 0 && depth >= desc.max_depth) {
        alive &= ~bit;
        continue;
      }
      const Vec3f wo = its.frame.ToLocal(wo_world);
      const bool delta = IsDeltaMaterial(its.material.tag());
      if (nee && !delta) {
        // The shadow tests wait for the packet; the sum is added before the next vertex.
        for (int i = 0; i < light_samples; ++i) {
          requests[size_t(i) * kLanes + j] = PrepareEmitterSample(scene, its, wo, mis, rng[j]);
        }
        nee_throughput[j] = throughput[j];
        nee_lanes |= bit;
      }
      if (depth >= 3) {
        const float q = std::min(MaxComponent(throughput[j]) * eta[j] * eta[j], 0.99f);
        if (!(rng[j].NextFloat() < q)) {
          alive &= ~bit;
          continue;
        }
        throughput[j] *= 1.0f / q;
      }
      BsdfSample bs;
      const float u1 = rng[j].NextFloat();
      if (!BsdfSampleDirection(scene.materials, its.material, wo, u1, Next2D(rng[j]), &bs)) {
        alive &= ~bit;
        continue;
      }
      throughput[j] *= bs.weight;
      eta[j] *= bs.eta;
      if (IsBlack(throughput[j])) {
        alive &= ~bit;
        continue;
      }
      specular_bounce[j] = bs.delta;
      prev_pdf[j] = bs.pdf;
      prev_p[j] = its.p;
      const Vec3f wi = its.frame.ToWorld(bs.wi);
      ray[j] = Ray{SpawnOrigin(its, wi), wi, 0.0f, kInfinity};
    }
    if (nee_lanes == 0) continue;
    Mask8 occluded[64];
    std::vector<Mask8> occluded_many;
    Mask8* occ = occluded;
    if (light_samples > 64) {
      occluded_many.resize(size_t(light_samples));
      occ = occluded_many.data();
    }
    for (int i = 0; i < light_samples; ++i) {
      occ[i] = TraceShadows(tracer, &requests[size_t(i) * kLanes], nee_lanes);
    }
    for (Mask8 m = nee_lanes; m != 0; m &= m - 1) {
      const int j = std::countr_zero(m);
      Color3f direct;
      for (int i = 0; i < light_samples; ++i) {
        direct += EmitterSampleResult(requests[size_t(i) * kLanes + j], Lane(occ[i], j));
      }
      L[j] += nee_throughput[j] * direct * (1.0f / float(light_samples));
    }
  }
}

void ShadePacket(const RenderContext& ctx, PacketTracer& tracer, const Ray* rays, Pcg32* rng,
                 Mask8 active, Color3f* L) {
  const Scene& scene = ctx.scene;
  const Type type = scene.integrator.type;
  switch (type) {
    case Type::kNormals:
      return ShadeNormals(scene, tracer, rays, active, L);
    case Type::kDirectEms:
    case Type::kDirectMats:
    case Type::kDirectMis:
      return ShadeDirect(scene, tracer, rays, rng, active, type, L);
    case Type::kWhitted:
      return ShadeWhitted(scene, tracer, rays, rng, active, L);
    case Type::kPathMats:
    case Type::kPathEms:
    case Type::kPathMis:
      return ShadePath(scene, tracer, rays, rng, active, type, L);
  }
}

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

void RenderTilePacket8(const RenderContext& ctx, const TraversalBackend8& backend,
                       const Camera& camera, const PixelFilter& filter, int x0, int y0, int x1,
                       int y1, uint32_t s_begin, uint32_t s_end, uint64_t seed, FilmBlock* block,
                       TileSampleStats* stats) {
  if (x1 <= x0 || y1 <= y0 || s_end <= s_begin) return;
  PacketTracer tracer(backend, &stats->rays);
  const uint64_t width = uint64_t(camera.width());
  const size_t samples = s_end - s_begin;
  const size_t tile_w = size_t(x1 - x0);
  struct Sample {
    float sx, sy;
    Color3f L;
  };
  // One band of two pixel rows at a time: every sample of the band is traced (in packets of
  // 4x2 pixels) before any is splatted, then they are splatted in the scalar loop's order.
  std::vector<Sample> band(2 * tile_w * samples);
  for (int y = y0; y < y1; y += 2) {
    for (int bx = x0; bx < x1; bx += 4) {
      for (uint32_t s = s_begin; s < s_end; ++s) {
        Ray rays[kLanes];
        Pcg32 rng[kLanes];
        float sx[kLanes], sy[kLanes];
        Mask8 active = 0;
        for (int j = 0; j < kLanes; ++j) {
          const int px = bx + (j & 3), py = y + (j >> 2);
          if (px >= x1 || py >= y1) continue;
          const uint64_t pixel = uint64_t(py) * width + uint64_t(px);
          rng[j] = Pcg32(PixelSeed(seed, pixel), s);
          const float jx = rng[j].NextFloat(), jy = rng[j].NextFloat();
          const float lx = rng[j].NextFloat(), ly = rng[j].NextFloat();
          sx[j] = float(px) + jx, sy[j] = float(py) + jy;
          rays[j] = camera.GenerateRay(sx[j], sy[j], {lx, ly});
          active |= 1u << j;
        }
        Color3f L[kLanes];
        ShadePacket(ctx, tracer, rays, rng, active, L);
        for (Mask8 m = active; m != 0; m &= m - 1) {
          const int j = std::countr_zero(m);
          const size_t px = size_t(bx + (j & 3) - x0), row = size_t(j >> 2);
          band[(row * tile_w + px) * samples + (s - s_begin)] = {sx[j], sy[j], L[j]};
        }
      }
    }
    for (int row = 0; row < 2 && y + row < y1; ++row) {
      for (size_t px = 0; px < tile_w; ++px) {
        for (size_t k = 0; k < samples; ++k) {
          const Sample& smp = band[(size_t(row) * tile_w + px) * samples + k];
          if (!IsFinite(smp.L)) {
            if (stats->nonfinite++ == 0) stats->first_x = x0 + int(px), stats->first_y = y + row;
            continue;
          }
          block->Splat(filter, smp.sx, smp.sy, smp.L);
        }
      }
    }
  }
}

void RenderTileScalar(const RenderContext& ctx, const Camera& camera, const PixelFilter& filter,
                      int x0, int y0, int x1, int y1, uint32_t s_begin, uint32_t s_end,
                      uint64_t seed, FilmBlock* block, TileSampleStats* stats) {
  RayCounters counters;
  const uint64_t width = uint64_t(camera.width());
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const uint64_t pixel = uint64_t(y) * width + uint64_t(x);
      for (uint32_t s = s_begin; s < s_end; ++s) {
        Pcg32 rng(PixelSeed(seed, pixel), s);
        const float jx = rng.NextFloat(), jy = rng.NextFloat();
        const float lx = rng.NextFloat(), ly = rng.NextFloat();
        const float sx = float(x) + jx, sy = float(y) + jy;
        const Ray ray = camera.GenerateRay(sx, sy, {lx, ly});
        const Color3f L = Li(ctx, ray, rng, &counters);
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
