// Bidirectional path tracing and the particle tracer (see bdpt.h): the batch driver. Written
// from Veach's thesis, ch. 10; the pieces are bdpt_walk (the subpaths), bdpt_connect (the
// strategies), bdpt_mis (densities and MIS weights).
#include "engine/render/bdpt.h"

#include <algorithm>

#include "engine/bvh/intersect1.h"
#include "engine/render/bdpt_batch.h"
#include "engine/render/bdpt_connect.h"
#include "engine/render/bdpt_walk.h"
#include "engine/wavefront/kernels.h"

namespace ptlab {

void BidirectionalTracer::Intersect(std::span<const Ray> r, Hit* hits, uint8_t* hit) {
  rays += r.size();
  if (kernels == nullptr) {
    for (size_t i = 0; i < r.size(); ++i) hit[i] = Intersect1(*bvh, r[i], &hits[i]) ? 1 : 0;
    return;
  }
  RayPacket8 packet;
  HitPacket8 hp;
  for (size_t k = 0; k < r.size(); k += kPacketWidth) {
    const int lanes = int(std::min(kPacketWidth, r.size() - k));
    for (int j = 0; j < lanes; ++j) SetLaneRay(&packet, j, r[k + size_t(j)]);
    const Mask8 active = (Mask8{1} << lanes) - 1;
    const Mask8 m = kernels->intersect8(kernels->accel, packet, active, &hp) & active;
    for (int j = 0; j < lanes; ++j) {
      hit[k + size_t(j)] = LaneActive(m, j) ? 1 : 0;
      if (LaneActive(m, j)) hits[k + size_t(j)] = Hit{hp.t[j], hp.b1[j], hp.b2[j], hp.prim[j]};
    }
    ++packets;
  }
}

void BidirectionalTracer::Occluded(std::span<const Ray> r, uint8_t* occluded) {
  rays += r.size();
  if (kernels == nullptr) {
    for (size_t i = 0; i < r.size(); ++i) occluded[i] = Occluded1(*bvh, r[i]) ? 1 : 0;
    return;
  }
  RayPacket8 packet;
  for (size_t k = 0; k < r.size(); k += kPacketWidth) {
    const int lanes = int(std::min(kPacketWidth, r.size() - k));
    for (int j = 0; j < lanes; ++j) SetLaneRay(&packet, j, r[k + size_t(j)]);
    const Mask8 active = (Mask8{1} << lanes) - 1;
    const Mask8 m = kernels->occluded8(kernels->accel, packet, active) & active;
    for (int j = 0; j < lanes; ++j) occluded[k + size_t(j)] = LaneActive(m, j) ? 1 : 0;
    ++packets;
  }
}

namespace {

using bdpt::Connection;
using bdpt::Subpath;
using bdpt::Vertex;
using bdpt::Walk;

// A thread's batch state, kept from batch to batch (cleared, never shrunk).
struct BatchState {
  std::vector<Subpath> camera, light;
  std::vector<Walk> walks;
  std::vector<uint32_t> active;
  std::vector<Ray> rays;
  std::vector<Hit> hits;
  std::vector<uint8_t> flags;
  // Connections in sample order, then (t, s) order: their sample, shadow ray and endpoint.
  std::vector<Connection> connections;
  std::vector<uint32_t> owner, shadow_of, endpoint_of;
  std::vector<Vertex> endpoints;
  std::vector<int> nc, nl;  // vertices of each sample's camera and light subpath
};

constexpr uint32_t kNone = 0xffffffffu;

// Advances the walks of every sample until all have ended, tracing each bounce's rays as one
// batch; sample i's walk extends paths[i].
void WalkAll(const Scene& scene, const BidirectionalSetup& setup, BidirectionalTracer* tracer,
             std::span<BidirectionalSampleInput> samples, std::vector<Subpath>& paths,
             BatchState* b) {
  for (;;) {
    b->active.clear(), b->rays.clear();
    for (uint32_t i = 0; i < samples.size(); ++i)
      if (b->walks[i].active) b->active.push_back(i), b->rays.push_back(b->walks[i].ray);
    if (b->active.empty()) return;
    b->hits.resize(b->rays.size()), b->flags.resize(b->rays.size());
    tracer->Intersect(b->rays, b->hits.data(), b->flags.data());
    for (size_t k = 0; k < b->active.size(); ++k) {
      const uint32_t i = b->active[k];
      bdpt::StepWalk(scene, setup, b->flags[k] ? &b->hits[k] : nullptr, samples[i].sampler,
                     &paths[i], &b->walks[i]);
    }
  }
}

}  // namespace

void TraceBidirectionalBatch(const RenderContext& ctx, const BidirectionalSetup& setup,
                             BidirectionalTracer* tracer,
                             std::span<BidirectionalSampleInput> samples, Color3f* L,
                             std::vector<LightSplat>* splats,
                             std::vector<StrategyContribution>* strategies) {
  const Scene& scene = ctx.scene;
  const bool ptracer = scene.integrator.type == IntegratorDesc::Type::kPtracer;
  const int max_depth = scene.integrator.max_depth;
  // s + t - 2 <= maxDepth bounces; the particle tracer's camera subpath only finds emitters.
  const int max_camera = ptracer ? 2 : (max_depth >= 0 ? max_depth + 2 : kBidirectionalMaxVertices);
  const int max_light = max_depth >= 0 ? max_depth + 1 : kBidirectionalMaxVertices;
  thread_local BatchState state;
  BatchState* b = &state;
  const size_t n = samples.size();
  if (b->camera.size() < n) b->camera.resize(n), b->light.resize(n);
  b->walks.resize(n);

  for (size_t i = 0; i < n; ++i)
    bdpt::StartCameraWalk(setup, samples[i].ray, max_camera, &b->camera[i], &b->walks[i]);
  WalkAll(scene, setup, tracer, samples, b->camera, b);
  std::vector<int>& nc = b->nc;
  std::vector<int>& nl = b->nl;
  nc.resize(n), nl.resize(n);
  for (size_t i = 0; i < n; ++i) nc[i] = b->walks[i].n;
  for (size_t i = 0; i < n; ++i)
    bdpt::StartLightWalk(scene, setup, max_light, samples[i].sampler, &b->light[i], &b->walks[i]);
  WalkAll(scene, setup, tracer, samples, b->light, b);
  for (size_t i = 0; i < n; ++i) nl[i] = b->walks[i].n;

  // Every strategy's contribution and shadow ray, in the oracle's (t, s) order per sample.
  b->connections.clear(), b->owner.clear(), b->shadow_of.clear(), b->endpoint_of.clear();
  b->rays.clear(), b->endpoints.clear();
  Connection c;
  Ray shadow;
  Vertex endpoint;
  for (uint32_t i = 0; i < n; ++i) {
    // s = 1 draws its own light sample, so it runs even when the light subpath is empty.
    const int s_max = std::max(nl[i], ptracer ? 0 : std::min(1, max_light));
    for (int t = 1; t <= nc[i]; ++t) {
      for (int s = 0; s <= s_max; ++s) {
        const int depth = s + t - 2;
        if ((s == 1 && t == 1) || depth < 0 || (max_depth >= 0 && depth > max_depth)) continue;
        if (ptracer && !(t == 1 && s >= 2) && !(s == 0 && t == 2)) continue;
        if (!bdpt::PrepareConnection(scene, setup, b->light[i], s, b->camera[i], t,
                                     samples[i].sampler, ptracer, &c, &shadow, &endpoint))
          continue;
        b->connections.push_back(c);
        b->owner.push_back(i);
        b->shadow_of.push_back(c.shadow ? uint32_t(b->rays.size()) : kNone);
        if (c.shadow) b->rays.push_back(shadow);
        const bool sampled = s == 1 || t == 1;
        b->endpoint_of.push_back(sampled ? uint32_t(b->endpoints.size()) : kNone);
        if (sampled) b->endpoints.push_back(endpoint);
      }
    }
  }
  b->flags.resize(b->rays.size());
  tracer->Occluded(b->rays, b->flags.data());

  for (size_t i = 0; i < n; ++i) L[i] = Color3f{};
  for (size_t k = 0; k < b->connections.size(); ++k) {
    if (b->shadow_of[k] != kNone && b->flags[b->shadow_of[k]]) continue;
    const uint32_t i = b->owner[k];
    const Vertex& e = b->endpoint_of[k] != kNone ? b->endpoints[b->endpoint_of[k]] : endpoint;
    const Connection& c = b->connections[k];
    const size_t splats_before = splats->size();
    const Color3f term =
        bdpt::FinishConnection(scene, setup, b->light[i], b->camera[i], c, e, ptracer, splats);
    L[i] += term;
    if (strategies == nullptr) continue;
    if (c.t == 1 && splats->size() > splats_before) {
      const LightSplat& sp = splats->back();
      strategies->push_back({i, c.s, c.t, sp.sx, sp.sy, sp.value});
    } else if (c.t > 1) {
      strategies->push_back({i, c.s, c.t, 0.0f, 0.0f, term});
    }
  }
}

Color3f LiBidirectional(const RenderContext& ctx, const BidirectionalSetup& setup, const Ray& ray,
                        PathSampler& sampler, RayCounters* counters,
                        std::vector<LightSplat>* splats) {
  BidirectionalTracer tracer{.bvh = &ctx.bvh};
  BidirectionalSampleInput sample{ray, sampler};
  Color3f L;
  TraceBidirectionalBatch(ctx, setup, &tracer, {&sample, 1}, &L, splats);
  sampler = sample.sampler;
  counters->rays += tracer.rays;
  return L;
}

}  // namespace ptlab
