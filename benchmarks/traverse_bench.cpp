// Traversal throughput (rays/s) and BVH build time, single thread, on the very same rays: the
// scalar oracle, simd/ BVH8 single-ray and 8-wide packets, and (when found) Embree 3.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "benchmarks/bench_target.h"
#include "benchmarks/fractal_terrain.h"
#include "benchmarks/rock_field.h"
#include "engine/bvh/bvh.h"
#include "engine/bvh/bvh_build.h"
#include "engine/bvh/intersect1.h"
#include "engine/bvh/scene_bvh.h"
#include "engine/bvh/ray_offset.h"
#include "engine/core/frame.h"
#include "engine/core/ray.h"
#include "engine/core/rng.h"
#include "engine/io/xml_loader.h"
#include "engine/light/area_light.h"
#include "engine/render/camera.h"
#include "engine/render/film.h"
#include "engine/render/filter.h"
#include "engine/render/integrator.h"
#include "engine/render/packet_render.h"
#include "engine/wavefront/wavefront.h"
#include "engine/sampling/warp.h"
#include "engine/scene/scene.h"
#include "simd/bvh8.h"
#include "simd/dispatched_target.h"
#include "simd/traverse8.h"
#include "simd/render_setup.h"

#ifdef PTLAB_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace ptlab {
namespace {

constexpr size_t kSecondaryRays = size_t{1} << 18;

// ---------------------------------------------------------------------------------------------
// Scenes: the Nori table and veach_mi scenes (when ../shared/data is there), the fractal
// terrain of benchmarks/fractal_terrain.h (1,048,352 triangles, no data), the rock field of
// benchmarks/rock_field.h (2,359,298 triangles in 16,384 objects) and terrain16 (the terrain
// instanced 16 times).

CameraDesc LookAtCamera(const Vec3f& eye, const Vec3f& target, const Vec3f& up, float fov,
                        int width, int height) {
  // Camera space looks along +z with +y up and +x to the image's left (Nori).
  const Vec3f f = Normalize(target - eye);
  const Vec3f l = Normalize(Cross(up, f));
  const Vec3f u = Cross(f, l);
  Matrix4 m;
  for (int r = 0; r < 3; ++r) {
    m.m[r][0] = l[r], m.m[r][1] = u[r], m.m[r][2] = f[r], m.m[r][3] = eye[r];
  }
  CameraDesc c;
  c.camera_to_world = Transform(m);
  c.fov_deg = fov;
  c.width = width;
  c.height = height;
  return c;
}

struct LightSampler {
  // Either the scene's area lights or, for the terrain, a 0.6 x 0.6 quad at z = 1.5.
  const Scene* scene = nullptr;
  Vec3f Sample(Pcg32& rng, Vec3f* ng) const {
    if (scene == nullptr || scene->area_lights.size() == 0) {
      *ng = {0, 0, -1};
      return {0.3f + 0.6f * rng.NextFloat(), 0.5f + 0.6f * rng.NextFloat(), 1.5f};
    }
    const uint32_t n = static_cast<uint32_t>(scene->area_lights.size());
    const uint32_t k = std::min(n - 1, static_cast<uint32_t>(rng.NextFloat() * n));
    const float u_tri = rng.NextFloat();
    const Vec2f u{rng.NextFloat(), rng.NextFloat()};
    const AreaLightSample s =
        SampleAreaLight(*scene, k, Vec3f{}, TriangleSampling::kArea, {u_tri, u.x});
    *ng = s.ng;
    return s.p;
  }
};

struct RaySet {
  std::vector<Ray> rays;  // in packet order: rays [8k, 8k + 8) form packet k
  std::vector<RayPacket8> packets;
  std::vector<Mask8> masks;
};

struct BenchScene {
  std::string error;  // non-empty: the scene could not be made
  std::unique_ptr<Scene> scene;
  TriangleTable generated;  // the fractal terrain or the rock field (no scene file)
  const TriangleTable* triangles = nullptr;
  Bvh bvh;
  simd::Bvh8 bvh8;
  std::map<uint32_t, simd::Bvh8> merged;  // greedy BVH8s by merge_leaf_size (tuning)
  RaySet coherent, incoherent, shadow;
#ifdef PTLAB_HAVE_EMBREE
  RTCDevice device = nullptr;
  RTCScene rtc_scene = nullptr;
  RTCScene rtc_group = nullptr;  // terrain16: the instanced scene
#endif
};

void Pack(RaySet* set) {
  const size_t n = set->rays.size();
  for (size_t base = 0; base < n; base += 8) {
    RayPacket8 p{};
    Mask8 m = 0;
    for (int j = 0; j < 8 && base + j < n; ++j) {
      SetLaneRay(&p, j, set->rays[base + j]);
      m |= LaneBit(j);
    }
    set->packets.push_back(p);
    set->masks.push_back(m);
  }
}

#ifdef PTLAB_HAVE_EMBREE
RTCScene MakeEmbreeScene(RTCDevice device, const TriangleTable& t, bool commit) {
  RTCScene scene = rtcNewScene(device);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t n = t.size();
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (size_t i = 0; i < n; ++i) {
    const Vec3f p[3] = {t.V0(i), t.V1(i), t.V2(i)};
    for (int k = 0; k < 3; ++k) {
      v[9 * i + 3 * k + 0] = p[k].x, v[9 * i + 3 * k + 1] = p[k].y, v[9 * i + 3 * k + 2] = p[k].z;
      idx[3 * i + k] = static_cast<unsigned>(3 * i + k);
    }
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  if (commit) rtcCommitScene(scene);
  return scene;
}
#endif

// Camera rays through pixel centres in 4 x 2 pixel packets, then from their hits: cosine
// bounce rays that hit something, and shadow rays to a light sample.
void MakeRays(const CameraDesc& desc, const LightSampler& light, BenchScene* s) {
  const Camera camera(desc);
  const int w = desc.width, h = desc.height;
  for (int y0 = 0; y0 < h; y0 += 2) {
    for (int x0 = 0; x0 < w; x0 += 4) {
      for (int j = 0; j < 8; ++j) {
        const int x = std::min(w - 1, x0 + j % 4), y = std::min(h - 1, y0 + j / 4);
        s->coherent.rays.push_back(camera.GenerateRay(x + 0.5f, y + 0.5f, {0.5f, 0.5f}));
      }
    }
  }
  struct SurfacePoint {
    Vec3f p, n;  // n: unit geometric normal on the side the camera ray came from
  };
  std::vector<SurfacePoint> points;
  const TriangleTable& t = *s->triangles;
  for (const Ray& r : s->coherent.rays) {
    Hit hit;
    if (!Intersect1(s->bvh, r, &hit)) continue;
    Vec3f v0, v1, v2;
    if (s->scene && IsInstancedHit(hit.prim, t.size())) {  // terrain16: the world triangle
      const InstancedRow at = FindInstancedRow(s->scene->instances, t.size(), hit.prim);
      const Transform& w = s->scene->instances.to_world[at.instance];
      v0 = w.ApplyPoint(t.V0(at.row)), v1 = w.ApplyPoint(t.V1(at.row));
      v2 = w.ApplyPoint(t.V2(at.row));
    } else {
      v0 = t.V0(hit.prim), v1 = t.V1(hit.prim), v2 = t.V2(hit.prim);
    }
    const Vec3f p = v0 * (1.0f - hit.b1 - hit.b2) + v1 * hit.b1 + v2 * hit.b2;
    Vec3f n = Normalize(Cross(v1 - v0, v2 - v0));
    if (Dot(n, r.d) > 0) n = -n;
    points.push_back({p, n});
  }
  if (points.empty()) return;
  Pcg32 rng(7, 3);
  for (size_t i = 0; s->incoherent.rays.size() < kSecondaryRays && i < 64 * kSecondaryRays; ++i) {
    const SurfacePoint& sp = points[i % points.size()];
    const Frame frame(sp.n);
    const Vec3f d = frame.ToWorld(SampleCosineHemisphere({rng.NextFloat(), rng.NextFloat()}));
    const Ray r{OffsetRayOrigin(sp.p, sp.n), d, 0.0f, 1e30f};
    Hit hit;
    if (Intersect1(s->bvh, r, &hit)) s->incoherent.rays.push_back(r);
  }
  for (size_t i = 0; s->shadow.rays.size() < kSecondaryRays && i < kSecondaryRays; ++i) {
    const SurfacePoint& sp = points[i % points.size()];
    Vec3f lng;
    const Vec3f lp = light.Sample(rng, &lng);
    const Vec3f wi = lp - sp.p;
    if (Dot(wi, sp.n) <= 0) continue;  // the light is behind the surface: no shadow ray
    Ray r;
    r.o = OffsetRayOrigin(sp.p, sp.n);
    r.d = OffsetRayOrigin(lp, Dot(lng, wi) <= 0 ? lng : -lng) - r.o;
    r.t_min = 0.0f;
    r.t_max = 1.0f;
    s->shadow.rays.push_back(r);
  }
  Pack(&s->coherent);
  Pack(&s->incoherent);
  Pack(&s->shadow);
}

std::string DataPath(const char* rel) {
  return std::string(PTLAB_SOURCE_DIR) + "/../shared/data/nori/epfl/scenes/pa5/" + rel;
}

std::unique_ptr<BenchScene> MakeScene(const std::string& name) {
  auto s = std::make_unique<BenchScene>();
  CameraDesc camera;
  LightSampler light;
  if (name == "terrain" || name == "rocks") {
    // The rock field (many small objects: 16,384 closed rocks of 144 triangles over a ground
    // quad, 2.36 M triangles) is seen from the terrain's viewpoint and lit by its light.
    s->generated =
        name == "terrain" ? MakeFractalTerrain(kTerrainGridSize) : MakeRockField(kRockFieldRocks);
    s->triangles = &s->generated;
    const TerrainView& v = kTerrainView;
    camera = LookAtCamera(v.eye, v.target, v.up, v.fov_deg, v.width, v.height);
  } else if (name == "terrain16") {
    // The terrain as one shape group, instanced 16 times on a 4 x 4 grid: each turned about z
    // by a multiple of 90 degrees plus 10, every third one scaled by 0.8, one mirrored.
    s->scene = std::make_unique<Scene>();
    s->scene->triangles = MakeFractalTerrain(kTerrainGridSize);
    s->triangles = &s->scene->triangles;
    InstanceTable& in = s->scene->instances;
    const uint32_t g = in.AddGroup(0, uint32_t(s->triangles->size()));
    for (int i = 0; i < 16; ++i) {
      const Vec3f at{-3.3f + 2.2f * float(i % 4), 2.2f * float(i / 4), 0.0f};
      const float scale = i % 3 == 0 ? 0.8f : 1.0f;
      Transform t = Transform::Translate(at) * Transform::Rotate({0, 0, 1}, 90.0f * float(i % 4) + 10.0f) *
                    Transform::Scale({i == 5 ? -scale : scale, scale, scale});
      in.AddInstance(g, t);
    }
    camera = LookAtCamera({0.0f, -4.0f, 2.5f}, {0.0f, 3.0f, -0.2f}, {0, 0, 1}, 60.0f, 768, 512);
  } else {
    const std::string path =
        DataPath(name == "table" ? "table/table_mis.xml" : "veach_mi/veach_mis.xml");
    if (!std::filesystem::exists(path)) {
      s->error = "no shared data: " + path;
      return s;
    }
    StatusOr<Scene> loaded = LoadScene(path);
    if (!loaded.ok()) {
      s->error = loaded.status().message();
      return s;
    }
    s->scene = std::make_unique<Scene>(std::move(*loaded));
    s->triangles = &s->scene->triangles;
    camera = s->scene->camera;
    light.scene = s->scene.get();
  }
  s->bvh = s->scene ? BuildSceneBvh(*s->scene) : BuildBvh(*s->triangles);
  s->bvh8 = simd::BuildBvh8(s->bvh);
  MakeRays(camera, light, s.get());
#ifdef PTLAB_HAVE_EMBREE
  // PTLAB_EMBREE_CONFIG is appended to the device's configuration: "verbose=3" prints
  // Embree's statistics of each BVH it builds (nodes, leaves and their fill, bytes, SAH cost).
  std::string config = "threads=1,set_affinity=0";
  if (const char* extra = std::getenv("PTLAB_EMBREE_CONFIG"); extra != nullptr && *extra != 0) {
    config += std::string(",") + extra;
  }
  s->device = rtcNewDevice(config.c_str());
  s->rtc_scene = MakeEmbreeScene(s->device, *s->triangles, /*commit=*/true);
  if (s->scene && !s->scene->instances.empty()) {
    // Embree's own instancing: the group's scene once, one RTC_GEOMETRY_TYPE_INSTANCE each.
    s->rtc_group = s->rtc_scene;
    s->rtc_scene = rtcNewScene(s->device);
    const InstanceTable& in = s->scene->instances;
    for (size_t i = 0; i < in.size(); ++i) {
      RTCGeometry inst = rtcNewGeometry(s->device, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(inst, s->rtc_group);
      float xfm[12];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) xfm[4 * r + c] = in.to_world[i].matrix().m[r][c];
      rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
      rtcCommitGeometry(inst);
      rtcAttachGeometry(s->rtc_scene, inst);
      rtcReleaseGeometry(inst);
    }
    rtcCommitScene(s->rtc_scene);
  }
#endif
  return s;
}

BenchScene* GetScene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<BenchScene>> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, MakeScene(name)).first;
  return it->second.get();
}

const RaySet& GetRays(const BenchScene& s, const std::string& set) {
  return set == "coherent" ? s.coherent : (set == "incoherent" ? s.incoherent : s.shadow);
}

// ---------------------------------------------------------------------------------------------
// Cases.

enum class Case {
  kOracleIntersect1,
  kOracleOccluded1,
  kBvh8Intersect1,
  kBvh8Occluded1,
  kIntersect8,
  kOccluded8,
  kIntersectStream,
  kEmbreeIntersect1,
  kEmbreeIntersect8,
  kEmbreeOccluded1,
  kEmbreeOccluded8,
};

// Every benchmark reports the same counters (the CSV reporter of benchmarks/report needs a
// fixed set of columns).
void SetCounters(benchmark::State& state, double hit_fraction, double triangles,
                 double rays_per_second) {
  state.counters["hit_fraction"] = hit_fraction;
  state.counters["triangles"] = triangles;
  state.counters["rays_per_second"] = rays_per_second;
}

void Finish(benchmark::State& state, size_t rays, int64_t hits) {
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(rays));
  SetCounters(state, static_cast<double>(hits) / static_cast<double>(state.iterations() * rays),
              0.0, 0.0);
  state.counters["rays_per_second"] = benchmark::Counter(
      static_cast<double>(state.iterations() * rays), benchmark::Counter::kIsRate);
  state.SetLabel(simd::DispatchedTargetName());
}

// One pass of Intersect8 or Occluded8 over a set's packets (with `options`, else each kernel's
// defaults); the number of hits.
int64_t PacketPass(const simd::Bvh8& bvh8, const RaySet& set, bool occluded,
                   std::optional<simd::Traverse8Options> options = std::nullopt) {
  int64_t hits = 0;
  for (size_t k = 0; k < set.packets.size(); ++k) {
    if (occluded) {
      hits += std::popcount(simd::Occluded8(bvh8, set.packets[k], set.masks[k],
                                            options.value_or(simd::kOccluded8Options)));
    } else {
      HitPacket8 h;
      hits += std::popcount(simd::Intersect8(bvh8, set.packets[k], set.masks[k], &h,
                                             options.value_or(simd::Traverse8Options{})));
      benchmark::DoNotOptimize(h);
    }
  }
  return hits;
}

// The medians of a paired run (PairedTimes): b's time / a's, and each side's time (ms).
struct Paired {
  double ratio = 0.0, a_ms = 0.0, b_ms = 0.0;
};

// Times run_a and run_b once each per iteration, in alternating order, after an untimed
// prepare() (for what each pair must start from, e.g. an uncommitted scene), and returns the
// medians over iterations of b's time / a's (above 1: a is faster) and of each side's time. On
// a VM whose speed drifts over minutes, pairs this close in time compare where separate
// benchmarks did not.
template <class RunA, class RunB, class Prepare>
Paired PairedTimes(benchmark::State& state, RunA run_a, RunB run_b, Prepare prepare) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> ratios, a_ms, b_ms;
  bool a_first = true;
  for (auto _ : state) {  // the iteration's time includes prepare(); the medians do not
    prepare();
    double seconds[2] = {};  // a, b
    for (int turn = 0; turn < 2; ++turn) {
      const bool a = (turn == 0) == a_first;
      const auto t0 = Clock::now();
      a ? run_a() : run_b();
      seconds[a ? 0 : 1] = std::chrono::duration<double>(Clock::now() - t0).count();
    }
    ratios.push_back(seconds[1] / seconds[0]);
    a_ms.push_back(1e3 * seconds[0]), b_ms.push_back(1e3 * seconds[1]);
    a_first = !a_first;
  }
  const auto median = [](std::vector<double>& v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  return {median(ratios), median(a_ms), median(b_ms)};
}

// PairedTimes' ratio, with nothing to prepare.
template <class RunA, class RunB>
double PairedRatio(benchmark::State& state, RunA run_a, RunB run_b) {
  return PairedTimes(state, run_a, run_b, [] {}).ratio;
}

#ifdef PTLAB_HAVE_EMBREE
// One pass of rtcIntersect8 or rtcOccluded8 over a set's packets (the same packets our
// Intersect8 reads); the number of hits. Embree writes its results into the packet, so each call
// starts from a fresh copy (288 bytes).
int64_t EmbreePacketPass(const BenchScene& s, const RaySet& set, bool coherent, bool occluded) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags =
      coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  int64_t hits = 0;
  for (size_t k = 0; k < set.packets.size(); ++k) {
    const RayPacket8& p = set.packets[k];
    alignas(32) int valid[8];
    alignas(32) RTCRayHit8 rh;
    for (int j = 0; j < 8; ++j) valid[j] = LaneActive(set.masks[k], j) ? -1 : 0;
    std::memcpy(rh.ray.org_x, p.org_x, sizeof(float) * 8 * 3);
    std::memcpy(rh.ray.dir_x, p.dir_x, sizeof(float) * 8 * 3);
    std::memcpy(rh.ray.tnear, p.t_min, sizeof(float) * 8);
    std::memcpy(rh.ray.tfar, p.t_max, sizeof(float) * 8);
    for (int j = 0; j < 8; ++j) {
      rh.ray.time[j] = 0.0f, rh.ray.mask[j] = 0xffffffffu, rh.ray.id[j] = 0;
      rh.ray.flags[j] = 0, rh.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;
    }
    if (!occluded) {
      rtcIntersect8(valid, s.rtc_scene, &ctx, &rh);
      for (int j = 0; j < 8; ++j) hits += valid[j] && rh.hit.geomID[j] != RTC_INVALID_GEOMETRY_ID;
    } else {
      rtcOccluded8(valid, s.rtc_scene, &ctx, &rh.ray);
      for (int j = 0; j < 8; ++j) hits += valid[j] && rh.ray.tfar[j] < 0.0f;
    }
    benchmark::DoNotOptimize(rh);
  }
  return hits;
}

// Intersect8 (or Occluded8) against rtcIntersect8 (rtcOccluded8) on the same packets, paired
// (PairedRatio): `ratio` is Embree's time / ours (above 1: ours is faster). The report's main
// table times ours and Embree minutes apart, and on a VM whose speed drifts that moved its rows
// by up to ±0.15 between runs.
void RunEmbreePaired(benchmark::State& state, const std::string& scene_name,
                     const std::string& set_name, bool occluded) {
  BenchScene* s = GetScene(scene_name);
  if (!s->error.empty()) {
    state.SkipWithError(s->error.c_str());
    return;
  }
  const RaySet& set = GetRays(*s, set_name);
  // One untimed pass of each first: the first timed pass would otherwise pay for the caches.
  benchmark::DoNotOptimize(PacketPass(s->bvh8, set, occluded));
  benchmark::DoNotOptimize(EmbreePacketPass(*s, set, set_name == "coherent", occluded));
  int64_t hits_ours = 0, hits_embree = 0;
  state.counters["ratio"] = PairedRatio(
      state, [&] { hits_ours += PacketPass(s->bvh8, set, occluded); },
      [&] { hits_embree += EmbreePacketPass(*s, set, set_name == "coherent", occluded); });
  // Hit counts as a check that both ran the same rays: watertight tests may differ on edges.
  state.counters["hits_ours"] = double(hits_ours) / double(state.iterations());
  state.counters["hits_embree"] = double(hits_embree) / double(state.iterations());
  state.SetLabel(simd::DispatchedTargetName());
}
#endif

// The SAH collapse at `leaf_cost` against the greedy one (merge_leaf_size 8) on the same rays,
// paired (PairedRatio): `speedup` is the greedy tree's time / the SAH tree's.
void RunCollapsePaired(benchmark::State& state, const std::string& scene_name,
                       const std::string& set_name, bool occluded, float leaf_cost) {
  BenchScene* s = GetScene(scene_name);
  if (!s->error.empty()) {
    state.SkipWithError(s->error.c_str());
    return;
  }
  const simd::Bvh8 greedy = simd::BuildBvh8(s->bvh, {.merge_leaf_size = 8, .sah_leaf_cost = 0});
  const simd::Bvh8 sah = simd::BuildBvh8(s->bvh, {.sah_leaf_cost = leaf_cost});
  const RaySet& set = GetRays(*s, set_name);
  int64_t hits_greedy = 0, hits_sah = 0;
  state.counters["speedup"] = PairedRatio(
      state, [&] { hits_sah += PacketPass(sah, set, occluded); },
      [&] { hits_greedy += PacketPass(greedy, set, occluded); });
  if (hits_greedy != hits_sah) state.SkipWithError("the two trees' hit counts differ");
  state.SetLabel(simd::DispatchedTargetName());
}

void RunCase(benchmark::State& state, const std::string& scene_name, const std::string& set_name,
             Case c, std::optional<simd::Traverse8Options> tuning, int merge_leaf_size = -1) {
  BenchScene* s = GetScene(scene_name);
  if (!s->error.empty()) {
    state.SkipWithError(s->error.c_str());
    return;
  }
  const simd::Bvh8* bvh8 = &s->bvh8;
  if (merge_leaf_size >= 0) {
    const uint32_t merge = static_cast<uint32_t>(merge_leaf_size);
    auto it = s->merged.find(merge);
    if (it == s->merged.end()) {
      const simd::Bvh8BuildOptions greedy{.merge_leaf_size = merge, .sah_leaf_cost = 0};
      it = s->merged.emplace(merge, simd::BuildBvh8(s->bvh, greedy)).first;
    }
    bvh8 = &it->second;
  }
  // Without a tuning, each kernel runs with its defaults.
  const simd::Traverse8Options options =
      tuning ? *tuning
             : (c == Case::kOccluded8 ? simd::kOccluded8Options : simd::Traverse8Options{});
  const RaySet& set = GetRays(*s, set_name);
  const size_t n = set.rays.size();
  int64_t hits = 0;
  switch (c) {
    case Case::kOracleIntersect1:
      for (auto _ : state) {
        for (const Ray& r : set.rays) {
          Hit h;
          hits += Intersect1(s->bvh, r, &h);
          benchmark::DoNotOptimize(h);
        }
      }
      break;
    case Case::kOracleOccluded1:
      for (auto _ : state) {
        for (const Ray& r : set.rays) hits += Occluded1(s->bvh, r);
      }
      break;
    case Case::kBvh8Intersect1:
      for (auto _ : state) {
        for (const Ray& r : set.rays) {
          Hit h;
          hits += simd::Intersect1(*bvh8, r, &h);
          benchmark::DoNotOptimize(h);
        }
      }
      break;
    case Case::kBvh8Occluded1:
      for (auto _ : state) {
        for (const Ray& r : set.rays) hits += simd::Occluded1(*bvh8, r);
      }
      break;
    case Case::kIntersect8:
    case Case::kOccluded8:
      for (auto _ : state) hits += PacketPass(*bvh8, set, c == Case::kOccluded8, options);
      break;
    case Case::kIntersectStream: {
      std::vector<Hit> out(n);
      std::vector<uint8_t> mask(n);
      std::vector<uint32_t> scratch(n);
      for (auto _ : state) {
        simd::IntersectStream(*bvh8, set.rays.data(), n, out.data(), mask.data(), scratch.data(),
                              options);
        for (uint8_t m : mask) hits += m;
      }
      break;
    }
#ifdef PTLAB_HAVE_EMBREE
    case Case::kEmbreeIntersect1:
    case Case::kEmbreeOccluded1: {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      ctx.flags = set_name == "coherent" ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                         : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
      for (auto _ : state) {
        for (const Ray& r : set.rays) {
          RTCRayHit rh;
          rh.ray.org_x = r.o.x, rh.ray.org_y = r.o.y, rh.ray.org_z = r.o.z;
          rh.ray.dir_x = r.d.x, rh.ray.dir_y = r.d.y, rh.ray.dir_z = r.d.z;
          rh.ray.tnear = r.t_min, rh.ray.tfar = r.t_max;
          rh.ray.time = 0.0f, rh.ray.mask = 0xffffffffu, rh.ray.id = 0, rh.ray.flags = 0;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          if (c == Case::kEmbreeIntersect1) {
            rtcIntersect1(s->rtc_scene, &ctx, &rh);
            hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
          } else {
            rtcOccluded1(s->rtc_scene, &ctx, &rh.ray);
            hits += rh.ray.tfar < 0.0f;
          }
          benchmark::DoNotOptimize(rh);
        }
      }
      break;
    }
    case Case::kEmbreeIntersect8:
    case Case::kEmbreeOccluded8:
      for (auto _ : state) {
        hits += EmbreePacketPass(*s, set, set_name == "coherent", c == Case::kEmbreeOccluded8);
      }
      break;
#else
    default:
      state.SkipWithError("built without Embree");
      return;
#endif
  }
  Finish(state, n, hits);
}

// BVH build: ours = the oracle's binned SAH build plus the BVH8 collapse; Embree = one
// rtcCommitScene (geometry set up outside the timed region), both on `threads` threads (run
// the two-thread rows on two cores: taskset -c 0,1). Counter bytes_per_triangle: ours, the
// BVH8's heap bytes (its nodes and the leaf-packed triangles and scene rows, all that its
// traversal reads) per triangle, and binary_bytes_per_triangle the oracle's binary BVH kept
// beside it; Embree's, the bytes its memory monitor counts allocated by rtcCommitScene and
// still held after it (its BVH: nodes and leaves with their triangle copies; the geometry's
// vertex and index buffers, 48 bytes a triangle here, are set up before and not counted).
#ifdef PTLAB_HAVE_EMBREE
struct EmbreeBytes {
  std::atomic<int64_t> held{0};
};

bool CountEmbreeBytes(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<EmbreeBytes*>(user)->held += bytes;
  return true;
}

// One device per thread count for the build rows (the traversal rows' device has one thread),
// with the memory monitor on.
RTCDevice BuildDevice(int threads, EmbreeBytes** bytes) {
  static std::map<int, std::pair<RTCDevice, std::unique_ptr<EmbreeBytes>>> devices;
  auto it = devices.find(threads);
  if (it == devices.end()) {
    const std::string config = "threads=" + std::to_string(threads) + ",set_affinity=0";
    auto counter = std::make_unique<EmbreeBytes>();
    RTCDevice device = rtcNewDevice(config.c_str());
    rtcSetDeviceMemoryMonitorFunction(device, CountEmbreeBytes, counter.get());
    it = devices.emplace(threads, std::pair{device, std::move(counter)}).first;
  }
  *bytes = it->second.second.get();
  return it->second.first;
}
#endif

// Our build, timed by both build benchmarks: the binned SAH build on `threads` threads and the
// collapse to the BVH8.
struct BuiltOurs {
  Bvh bvh;
  simd::Bvh8 bvh8;
};
BuiltOurs BuildOurs(const TriangleTable& triangles, int threads) {
  BuiltOurs b;
  b.bvh = BuildBvh(triangles, SphereTable{}, threads);
  b.bvh8 = simd::BuildBvh8(b.bvh);
  benchmark::DoNotOptimize(b.bvh8.lines.data());
  return b;
}

void RunBuild(benchmark::State& state, const std::string& scene_name, bool embree, int threads) {
  BenchScene* s = GetScene(scene_name);
  if (!s->error.empty()) {
    state.SkipWithError(s->error.c_str());
    return;
  }
  const double triangles = static_cast<double>(s->triangles->size());
  if (!embree) {
    double bytes = 0.0, binary_bytes = 0.0;
    for (auto _ : state) {
      const BuiltOurs b = BuildOurs(*s->triangles, threads);
      bytes = static_cast<double>(simd::Bvh8Bytes(b.bvh8));
      binary_bytes = static_cast<double>(BvhBytes(b.bvh));
    }
    state.counters["bytes_per_triangle"] = bytes / triangles;
    state.counters["binary_bytes_per_triangle"] = binary_bytes / triangles;
  } else {
#ifdef PTLAB_HAVE_EMBREE
    EmbreeBytes* counter = nullptr;
    RTCDevice device = BuildDevice(threads, &counter);
    int64_t held = 0;
    for (auto _ : state) {
      state.PauseTiming();
      RTCScene scene = MakeEmbreeScene(device, *s->triangles, /*commit=*/false);
      const int64_t before = counter->held;
      state.ResumeTiming();
      rtcCommitScene(scene);
      state.PauseTiming();
      held = counter->held - before;
      rtcReleaseScene(scene);
      state.ResumeTiming();
    }
    state.counters["bytes_per_triangle"] = static_cast<double>(held) / triangles;
#else
    state.SkipWithError("built without Embree");
    return;
#endif
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s->triangles->size()));
  state.counters["triangles"] = triangles;
  state.counters["threads"] = threads;
}

// The build against Embree's paired in time, as BM_Pair_Embree pairs traversal: every iteration
// times one build of ours and one rtcCommitScene (the Embree scene is set up untimed first), in
// alternating order, on `threads` threads; counters: `ratio`, the median over iterations of
// Embree's time / ours (above 1: ours is faster), and the medians of each side's time (ms).
// On a loaded or drifting machine the separate BM_Traverse_Build rows time the two at moments
// whose speeds differ; the pairs cancel what changes slower than a pair.
void RunBuildPaired(benchmark::State& state, const std::string& scene_name, int threads) {
#ifdef PTLAB_HAVE_EMBREE
  BenchScene* s = GetScene(scene_name);
  if (!s->error.empty()) {
    state.SkipWithError(s->error.c_str());
    return;
  }
  EmbreeBytes* counter = nullptr;
  RTCDevice device = BuildDevice(threads, &counter);
  RTCScene scene = nullptr;  // a fresh, uncommitted one for each pair
  const Paired p = PairedTimes(
      state, [&] { BuildOurs(*s->triangles, threads); }, [&] { rtcCommitScene(scene); },
      [&] {
        if (scene != nullptr) rtcReleaseScene(scene);
        scene = MakeEmbreeScene(device, *s->triangles, /*commit=*/false);
      });
  if (scene != nullptr) rtcReleaseScene(scene);
  state.counters["ratio"] = p.ratio;
  state.counters["ours_ms"] = p.a_ms;
  state.counters["embree_ms"] = p.b_ms;
  state.counters["threads"] = threads;
#else
  state.SkipWithError("built without Embree");
#endif
}

// Rendering throughput, single thread: the Nori table scene with a direct-lighting (or path)
// integrator at 200 x 150 pixels, 4 samples per pixel, rendered tile by tile (32 x 32) with
// the scalar loop (RenderTileScalar, one Li per sample) or the wavefront on simd/'s kernels.
struct RenderBench {
  std::string error;
  std::unique_ptr<Scene> scene;
  std::optional<RenderSetup> setup;  // BVH, BVH8, triangle rows and the SIMD table
};

RenderBench* GetRenderScene(IntegratorDesc::Type type) {
  static std::map<int, std::unique_ptr<RenderBench>> cache;
  auto it = cache.find(static_cast<int>(type));
  if (it != cache.end()) return it->second.get();
  auto r = std::make_unique<RenderBench>();
  const std::string path = DataPath("table/table_mis.xml");
  StatusOr<Scene> loaded = std::filesystem::exists(path)
                               ? LoadScene(path)
                               : StatusOr<Scene>(Status::Error("no shared data: " + path));
  if (!loaded.ok()) {
    r->error = loaded.status().message();
  } else {
    r->scene = std::make_unique<Scene>(std::move(*loaded));
    r->scene->camera.width = 200;
    r->scene->camera.height = 150;
    r->scene->integrator.type = type;
    r->setup.emplace(*r->scene, KernelChoice::kSimd);
  }
  return cache.emplace(static_cast<int>(type), std::move(r)).first->second.get();
}

void RunRender(benchmark::State& state, IntegratorDesc::Type type, bool packets) {
  RenderBench* r = GetRenderScene(type);
  if (!r->error.empty()) {
    state.SkipWithError(r->error.c_str());
    return;
  }
  const Scene& scene = *r->scene;
  const Camera camera(scene.camera);
  const PixelFilter filter(scene.filter);
  const RenderContext ctx{scene, r->setup->bvh()};
  const WavefrontKernels& kernels = r->setup->kernels();
  const int w = camera.width(), h = camera.height();
  constexpr uint32_t kSpp = 4;
  constexpr int kTile = 32;
  FilmBlock block(0, 0, w, h);
  uint64_t rays = 0;
  for (auto _ : state) {
    block.Clear();
    TileSampleStats stats;
    for (int y = 0; y < h; y += kTile) {
      for (int x = 0; x < w; x += kTile) {
        const int x1 = std::min(w, x + kTile), y1 = std::min(h, y + kTile);
        if (packets) {
          RenderTilePacket8(ctx, kernels, camera, filter, x, y, x1, y1, 0, kSpp, 0, &block, &stats);
        } else {
          RenderTileScalar(ctx, camera, filter, x, y, x1, y1, 0, kSpp, 0, &block, &stats);
        }
      }
    }
    rays += stats.rays;
  }
  state.SetItemsProcessed(state.iterations() * int64_t{w} * h * kSpp);
  SetCounters(state, 0.0, static_cast<double>(scene.triangles.size()), 0.0);
  state.counters["rays_per_second"] =
      benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.SetLabel(packets ? simd::DispatchedTargetName() : "scalar");
}

struct CaseName {
  Case c;
  const char* name;
};

int RegisterAll() {
  benchmark::AddCustomContext("highway_target", simd::DispatchedTargetName());
#ifdef PTLAB_HAVE_EMBREE
  benchmark::AddCustomContext("embree", RTC_VERSION_STRING);
#else
  benchmark::AddCustomContext("embree", "not found at configure time");
#endif
  const CaseName cases[] = {
      {Case::kOracleIntersect1, "OracleIntersect1"},
      {Case::kOracleOccluded1, "OracleOccluded1"},
      {Case::kBvh8Intersect1, "Bvh8Intersect1"},
      {Case::kBvh8Occluded1, "Bvh8Occluded1"},
      {Case::kIntersect8, "Intersect8"},
      {Case::kOccluded8, "Occluded8"},
      {Case::kIntersectStream, "IntersectStream"},
      {Case::kEmbreeIntersect1, "EmbreeIntersect1"},
      {Case::kEmbreeIntersect8, "EmbreeIntersect8"},
      {Case::kEmbreeOccluded1, "EmbreeOccluded1"},
      {Case::kEmbreeOccluded8, "EmbreeOccluded8"},
  };
  using Type = IntegratorDesc::Type;
  for (const auto& [type, name] :
       {std::pair{Type::kDirectMis, "direct_mis"}, std::pair{Type::kPathMis, "path_mis"}}) {
    const Type t = type;
    for (const bool packets : {false, true}) {
      benchmark::RegisterBenchmark(
          ("BM_Render_Table/" + std::string(name) + (packets ? "/packet" : "/scalar")).c_str(),
          [t, packets](benchmark::State& st) { RunRender(st, t, packets); })
          ->Unit(benchmark::kMillisecond);
    }
  }
  for (const char* scene : {"table", "veach", "terrain", "rocks"}) {
    const std::string sc = scene;
    const bool large = sc == "terrain" || sc == "rocks";
#ifdef PTLAB_HAVE_EMBREE
    for (const int threads : {1, 2}) {
      benchmark::RegisterBenchmark(
          ("BM_Pair_Build/" + sc + "/threads:" + std::to_string(threads)).c_str(),
          [sc, threads](benchmark::State& st) { RunBuildPaired(st, sc, threads); })
          ->Unit(benchmark::kMillisecond)
          ->MinTime(large ? 10.0 : 2.0);
    }
#endif
    // One thread: BM_Traverse_Build/<scene>/ours and /embree (benchmarks/report reads these);
    // two: /ours/threads:2 and /embree/threads:2.
    for (const int threads : {1, 2}) {
      const std::string suffix = threads == 1 ? "" : "/threads:" + std::to_string(threads);
      for (const bool embree : {false, true}) {
        benchmark::RegisterBenchmark(
            ("BM_Traverse_Build/" + sc + (embree ? "/embree" : "/ours") + suffix).c_str(),
            [sc, embree, threads](benchmark::State& st) { RunBuild(st, sc, embree, threads); })
            ->Unit(benchmark::kMillisecond);
      }
    }
    for (const char* set : {"coherent", "incoherent", "shadow"}) {
      const std::string st_name = set;
      for (const CaseName& cn : cases) {
        if (cn.c == Case::kIntersectStream && st_name == "coherent") continue;
        const Case c = cn.c;
        benchmark::RegisterBenchmark(
            ("BM_Traverse_" + std::string(cn.name) + "/" + sc + "/" + st_name).c_str(),
            [sc, st_name, c](benchmark::State& st) { RunCase(st, sc, st_name, c, std::nullopt); })
            ->Unit(benchmark::kMillisecond);
      }
      // Leaf merging in the greedy collapse (merge_leaf_size), for Intersect8 and single rays.
      for (const int merge : {0, 4, 8}) {
        for (const Case c : {Case::kIntersect8, Case::kBvh8Intersect1, Case::kOccluded8}) {
          const char* cname = c == Case::kIntersect8  ? "Intersect8"
                              : c == Case::kOccluded8 ? "Occluded8"
                                                      : "Bvh8Intersect1";
          benchmark::RegisterBenchmark(("BM_Tune_Merge/" + sc + "/" + st_name + "/" + cname +
                                        "/merge:" + std::to_string(merge))
                                           .c_str(),
                                       [sc, st_name, c, merge](benchmark::State& st) {
                                         RunCase(st, sc, st_name, c, {}, merge);
                                       })
              ->Unit(benchmark::kMillisecond);
        }
      }
#ifdef PTLAB_HAVE_EMBREE
      for (const bool occluded : {false, true}) {
        benchmark::RegisterBenchmark(
            ("BM_Pair_Embree/" + sc + "/" + st_name + (occluded ? "/Occluded8" : "/Intersect8"))
                .c_str(),
            [sc, st_name, occluded](benchmark::State& st) {
              RunEmbreePaired(st, sc, st_name, occluded);
            })
            ->Unit(benchmark::kMillisecond)
            // Enough pairs for a median, whatever --benchmark_min_time says: a terrain pair
            // takes about 0.3 s, so 1 s gave it four or five pairs, whose median moved by
            // +-0.04 from run to run; 5 s gives it 20 or more (21-26 measured on the Zen 5 VM).
            ->MinTime(large ? 5.0 : 1.0);
      }
#endif
      for (const float cost : {1.0f, 1.5f, 2.0f}) {
        for (const bool occluded : {false, true}) {
          char label[16];
          std::snprintf(label, sizeof label, "%.2f", double(cost));
          benchmark::RegisterBenchmark(
              ("BM_Tune_CollapsePaired/" + sc + "/" + st_name +
               (occluded ? "/Occluded8" : "/Intersect8") + "/leaf_cost:" + label)
                  .c_str(),
              [sc, st_name, occluded, cost](benchmark::State& st) {
                RunCollapsePaired(st, sc, st_name, occluded, cost);
              })
              ->Unit(benchmark::kMillisecond);
        }
      }
      // Tuning sweeps (run with --benchmark_filter=BM_Tune): the hybrid switch threshold
      // and the leaf strategy of Intersect8 and Occluded8.
      for (const Case c : {Case::kIntersect8, Case::kOccluded8}) {
        const std::string cname = c == Case::kIntersect8 ? "Intersect8" : "Occluded8";
        for (uint32_t k = 0; k <= 8; ++k) {
          for (const int variant : {0, 1, 2}) {
            // 0: default leaves and octant fallback; 1: per-lane leaves; 2: no octant fallback.
            // The switch k applies to every packet (shared origins too), and the fallback to
            // BVH8s of any size.
            const simd::Traverse8Options o{.single_ray_lanes = k,
                                           .broadcast_leaves = variant != 1,
                                           .octant_fallback = variant != 2,
                                           .shared_origin_single_ray_lanes = -1,
                                           .octant_fallback_min_triangles = 0};
            benchmark::RegisterBenchmark(
                ("BM_Tune_" + cname + "/" + sc + "/" + st_name + "/switch:" + std::to_string(k) +
                 (variant == 0 ? "/default" : (variant == 1 ? "/per_lane_leaves" : "/no_octant")))
                    .c_str(),
                [sc, st_name, c, o](benchmark::State& st) { RunCase(st, sc, st_name, c, o); })
                ->Unit(benchmark::kMillisecond);
          }
        }
      }
    }
  }
  // The instanced terrain (terrain16): the traversal rows and the paired Embree rows only.
  for (const char* set : {"coherent", "incoherent", "shadow"}) {
    const std::string sc = "terrain16", st_name = set;
    for (const CaseName& cn : cases) {
      if (cn.c == Case::kIntersectStream) continue;
      const Case c = cn.c;
      benchmark::RegisterBenchmark(
          ("BM_Traverse_" + std::string(cn.name) + "/" + sc + "/" + st_name).c_str(),
          [sc, st_name, c](benchmark::State& st) { RunCase(st, sc, st_name, c, std::nullopt); })
          ->Unit(benchmark::kMillisecond);
    }
#ifdef PTLAB_HAVE_EMBREE
    for (const bool occluded : {false, true}) {
      benchmark::RegisterBenchmark(
          ("BM_Pair_Embree/" + sc + "/" + st_name + (occluded ? "/Occluded8" : "/Intersect8"))
              .c_str(),
          [sc, st_name, occluded](benchmark::State& st) {
            RunEmbreePaired(st, sc, st_name, occluded);
          })
          ->Unit(benchmark::kMillisecond)
          ->MinTime(5.0);
    }
#endif
  }
  return 0;
}

const int kRegistered = RegisterAll();

}  // namespace
}  // namespace ptlab
