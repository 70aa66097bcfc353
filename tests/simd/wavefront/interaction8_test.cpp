// simd::MakeInteractionBatch (the wavefront's rows: the whole SurfaceInteraction without uv,
// and wo) against its oracle ptlab::MakeInteractionBatch: the hit rows bit-identical on every
// compiled target for 10^6 random hits per scene and the hard cases (barycentrics on edges and
// vertices, degenerate triangles, vertex normals that interpolate to zero, meshes with and
// without uvs, sphere lanes mixed in, partial hit masks), shading normals at the frame's edge
// cases (-z, z = -0, tiny negative z, nearly -z), a clockwise quad (ng = -z) and rays of lengths
// 2^-60..2^60 and axis-aligned; no NaN or Inf in any row written, and the oracle leaves the rows
// of lanes that did not hit untouched. And the hit lists (HitLists: every hit's queue entry,
// those on area lights, the hits per material group) equal to the oracle's and to the rows'
// own count on every target, on the same packets and on adversarial masks (no hit, all hits,
// single lanes, alternating lanes) over every material tag, no material, area and other
// emitter tags and sphere lanes.
#include "simd/targets.h"  // first: the same target policy as simd/
#include "simd/dispatched_target.h"
#include "simd/wavefront/interaction8.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/bvh/sphere_intersect.h"
#include "engine/core/rng.h"
#include "engine/io/mesh_builder.h"
#include "engine/io/scene_file.h"
#include "engine/wavefront/interaction.h"
#include "tests/simd/for_each_target.h"
#include "tests/test_data.h"

namespace ptlab {
namespace {

constexpr float kUntouched = -12345.0f;  // rows the oracle must not write

// A quad (two triangles) in the z = 1 plane with the given per-vertex normals and uvs (either
// may be empty), appended to the scene; returns its first triangle.
// `clockwise`: wound the other way, so that the geometric normal is -z.
uint32_t AddQuad(Scene* scene, std::vector<Vec3f> normals, std::vector<Vec2f> uvs,
                 bool clockwise = false) {
  MeshData m;
  m.positions = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.normals = std::move(normals), m.uvs = std::move(uvs);
  m.indices = {0, 1, 2, 0, 2, 3};
  if (clockwise) m.indices = {0, 2, 1, 0, 3, 2};
  const uint32_t first = uint32_t(scene->triangles.size());
  AddMesh(scene, m, Transform(), scene->shading.material[0], "quad");
  return first;
}

// The hard geometry: triangle 0 degenerate (V2 on V1), triangle 1 degenerate to a point, and
// where the scene has vertex normals, triangle 2's normals opposite at V0 and V1 (zero at the
// middle of that edge) and triangle 3's all zero, with uvs equal at all three vertices on one
// and ±1e30 on the other where the scene has uvs; quads with normals but no uvs, uvs but no
// normals, neither, and huge uvs appended; two spheres appended.
std::vector<uint32_t> AddHardCases(Scene* scene) {
  TriangleTable& t = scene->triangles;
  t.v2_x[0] = t.v1_x[0], t.v2_y[0] = t.v1_y[0], t.v2_z[0] = t.v1_z[0];
  t.v1_x[1] = t.v2_x[1] = t.v0_x[1], t.v1_y[1] = t.v2_y[1] = t.v0_y[1];
  t.v1_z[1] = t.v2_z[1] = t.v0_z[1];
  TriangleShadingTable& sh = scene->shading;
  VertexTable& v = scene->vertices;
  std::vector<uint32_t> hard = {0, 1};
  for (uint32_t tri = 2; tri < sh.size() && hard.size() < 4; ++tri) {
    if (sh.vertex0[tri] == kNoVertex || v.n_x.empty()) continue;
    // Fresh vertex rows so other triangles keep their normals.
    const uint32_t base = uint32_t(v.n_x.size());
    const bool opposite = hard.size() == 2;
    const float n[3][3] = {{0.0f, 0.0f, opposite ? 1.0f : 0.0f},
                           {0.0f, 0.0f, opposite ? -1.0f : 0.0f},
                           {0.0f, 0.0f, 0.0f}};
    for (const auto& c : n) v.n_x.push_back(c[0]), v.n_y.push_back(c[1]), v.n_z.push_back(c[2]);
    if (!v.u.empty()) {  // VertexTable columns stay aligned
      const float uv[3][2] = {{opposite ? 0.25f : 1e30f, opposite ? 0.75f : -1e30f},
                              {0.25f, opposite ? 0.75f : 1e30f},
                              {opposite ? 0.25f : -1e30f, 0.75f}};
      for (const auto& c : uv) v.u.push_back(c[0]), v.v.push_back(c[1]);
    }
    sh.vertex0[tri] = base, sh.vertex1[tri] = base + 1, sh.vertex2[tri] = base + 2;
    hard.push_back(tri);
  }
  const std::vector<Vec3f> up(4, Vec3f{0, 0, 1});
  const std::vector<Vec2f> uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Vec2f> huge = {{-3e38f, 1e-38f}, {3e38f, -7.5f}, {1e20f, 0}, {0, -1e20f}};
  for (const uint32_t first : {AddQuad(scene, up, {}), AddQuad(scene, {}, uvs),
                               AddQuad(scene, {}, {}), AddQuad(scene, up, huge)}) {
    hard.push_back(first), hard.push_back(first + 1);
  }
  scene->spheres.Append({0.1f, 0.2f, 0.3f}, 0.5f, scene->shading.material[0]);
  scene->spheres.Append({-1.0f, 2.0f, 0.0f}, 1e-3f, scene->shading.material[0]);
  return hard;
}

struct Packets {
  std::vector<RayPacket8> rays;
  std::vector<HitPacket8> hits;
  std::vector<Mask8> mask;
};

// `random` hit lanes on random triangles (1 in 64 on a sphere) with random barycentrics, every
// packet with a random hit mask that keeps most lanes; then the hard triangles at their
// vertices, edges' ends and middles and centroid.
Packets MakePackets(const Scene& scene, const std::vector<uint32_t>& hard, size_t random,
                    Pcg32& rng) {
  Packets p;
  const uint32_t tris = uint32_t(scene.triangles.v0_x.size());
  const uint32_t spheres = uint32_t(scene.spheres.size());
  size_t lane = 0;
  const auto push = [&](uint32_t prim, float b1, float b2) {
    if (lane % kPacketWidth == 0) {
      p.rays.emplace_back(), p.hits.emplace_back();
      // Lanes 0..7 hit except one random lane in four packets.
      const uint32_t r = rng.NextUint();
      p.mask.push_back(r % 4 == 0 ? kAllLanes & ~LaneBit(int(r >> 8) % 8) : kAllLanes);
    }
    const int j = int(lane++ % kPacketWidth);
    const Vec3f o{rng.NextFloat() * 8 - 4, rng.NextFloat() * 8 - 4, rng.NextFloat() * 8 - 4};
    SetLaneRay(&p.rays.back(), j, Ray{o, Vec3f{0.3f, -0.2f, 0.9f}});
    SetLaneHit(&p.hits.back(), j, rng.NextFloat() * 10, b1, b2, prim);
  };
  for (size_t i = 0; i < random; ++i) {
    if (rng.NextUint() % 64 == 0) {
      push(kSphereHitBit | (rng.NextUint() % spheres), 0.0f, 0.0f);
      continue;
    }
    float b1 = rng.NextFloat(), b2 = rng.NextFloat();
    if (b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
    push(rng.NextUint() % tris, b1, b2);
  }
  const float bary[][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0}, {0, 0.5f}, {0.5f, 0.5f},
                           {1.0f / 3, 1.0f / 3}, {0x1.fffffep-1f, 0}, {1e-30f, 1e-30f}};
  for (const uint32_t tri : hard) {
    for (const auto& b : bary) push(tri, b[0], b[1]);
  }
  return p;
}

// Quads whose shading normals are the frame's edge cases: n = -z, n = (1, 0, -0) (z = -0:
// copysign gives -1), n.z = -1e-30 and n = (1e-20, 0, -1) (sign + z = -2), and one wound
// clockwise without normals (ng = n = -z); returns their triangles.
std::vector<uint32_t> AddFrameCases(Scene* scene) {
  std::vector<uint32_t> tris;
  const std::vector<Vec3f> normals[] = {
      std::vector<Vec3f>(4, Vec3f{0, 0, -1}), std::vector<Vec3f>(4, Vec3f{1, 0, -0.0f}),
      std::vector<Vec3f>(4, Vec3f{1, 0, -1e-30f}), std::vector<Vec3f>(4, Vec3f{1e-20f, 0, -1})};
  for (const std::vector<Vec3f>& n : normals) {
    const uint32_t first = AddQuad(scene, n, {});
    tris.push_back(first), tris.push_back(first + 1);
  }
  const uint32_t first = AddQuad(scene, {}, {}, /*clockwise=*/true);
  tris.push_back(first), tris.push_back(first + 1);
  return tris;
}

// Ray directions of every length the rows' float Length handles (|d|² a normal float):
// random directions scaled by 2^-60..2^60, and one lane in eight axis-aligned (±0 components).
void SetDirections(Packets* p, Pcg32& rng) {
  const Vec3f axes[] = {{0, 0, -1}, {-0.0f, 0, 1}, {1, -0.0f, 0}, {0, -1, -0.0f}};
  for (RayPacket8& r : p->rays) {
    for (int j = 0; j < 8; ++j) {
      Vec3f dir;
      if (rng.NextUint() % 8 == 0) {
        dir = axes[rng.NextUint() % 4] * std::ldexp(1.0f, int(rng.NextUint() % 121) - 60);
      } else {
        do {
          dir = {rng.NextFloat() * 2 - 1, rng.NextFloat() * 2 - 1, rng.NextFloat() * 2 - 1};
        } while (Dot(dir, dir) < 1e-4f);
        dir = dir * std::ldexp(1.0f, int(rng.NextUint() % 121) - 60);
      }
      r.dir_x[j] = dir.x, r.dir_y[j] = dir.y, r.dir_z[j] = dir.z;
    }
  }
}

struct Rows {
  explicit Rows(size_t n) {
    SurfaceInteraction fill;
    fill.p = fill.ng = {kUntouched, kUntouched, kUntouched};
    fill.frame.s = fill.frame.t = fill.frame.n = fill.p;
    fill.uv = {kUntouched, kUntouched};
    its.assign(n, fill), wo.assign(n, fill.p);
  }
  std::vector<SurfaceInteraction> its;
  std::vector<Vec3f> wo;
  InteractionRows Out() { return {its.data(), wo.data()}; }
};

constexpr uint32_t kUntouchedEntry = 0xdeadbeefu;  // list entries the oracle must not write

// The hit lists' storage, 8 entries per packet, filled with kUntouchedEntry.
struct Lists {
  explicit Lists(size_t n) : entries(n, kUntouchedEntry), area(n, kUntouchedEntry) {
    lists.group_hits[0] = kUntouchedEntry;  // the kernels must reset the counts
  }
  std::vector<uint32_t> entries, area;
  HitLists lists{entries.data(), area.data()};
};

// The lists as the oracle's rows say they should be: every hit lane's q in order, the q whose
// row's emitter is an area light, the rows by MaterialGroup.
void ExpectListsOfRows(const Packets& p, const std::vector<SurfaceInteraction>& its,
                       const Lists& l) {
  std::vector<uint32_t> hits, area;
  uint32_t groups[kMaterialGroups] = {};
  for (size_t q = 0; q < p.mask.size() * kPacketWidth; ++q) {
    if (!LaneActive(p.mask[q / kPacketWidth], int(q % kPacketWidth))) continue;
    hits.push_back(uint32_t(q));
    if (its[q].emitter.tag() == EmitterTag::kArea) area.push_back(uint32_t(q));
    ++groups[MaterialGroup(its[q].material)];
  }
  ASSERT_EQ(l.lists.hits, hits.size());
  ASSERT_EQ(l.lists.area_hits, area.size());
  EXPECT_TRUE(std::equal(hits.begin(), hits.end(), l.entries.begin()));
  EXPECT_TRUE(std::equal(area.begin(), area.end(), l.area.begin()));
  for (int g = 0; g < kMaterialGroups; ++g) EXPECT_EQ(l.lists.group_hits[g], groups[g]) << g;
  // The oracle writes the lists' entries [0, count) only.
  EXPECT_TRUE(std::all_of(l.entries.begin() + ptrdiff_t(hits.size()), l.entries.end(),
                          [](uint32_t e) { return e == kUntouchedEntry; }));
  EXPECT_TRUE(std::all_of(l.area.begin() + ptrdiff_t(area.size()), l.area.end(),
                          [](uint32_t e) { return e == kUntouchedEntry; }));
}

// The kernel's lists against the oracle's: counts, entries [0, count) and group counts.
void ExpectListsMatch(const Lists& got, const Lists& want) {
  ASSERT_EQ(got.lists.hits, want.lists.hits);
  ASSERT_EQ(got.lists.area_hits, want.lists.area_hits);
  const ptrdiff_t hits = ptrdiff_t(want.lists.hits), area = ptrdiff_t(want.lists.area_hits);
  EXPECT_TRUE(std::equal(want.entries.begin(), want.entries.begin() + hits, got.entries.begin()));
  EXPECT_TRUE(std::equal(want.area.begin(), want.area.begin() + area, got.area.begin()));
  for (int g = 0; g < kMaterialGroups; ++g)
    EXPECT_EQ(got.lists.group_hits[g], want.lists.group_hits[g]) << "group " << g;
}

// The float fields of a row (all but prim, material, emitter) and its wo, all finite.
bool FiniteRow(const SurfaceInteraction& its, const Vec3f& wo) {
  const float f[] = {its.p.x,       its.p.y,       its.p.z,       its.ng.x,      its.ng.y,
                     its.ng.z,      its.frame.s.x, its.frame.s.y, its.frame.s.z, its.frame.t.x,
                     its.frame.t.y, its.frame.t.z, its.frame.n.x, its.frame.n.y, its.frame.n.z,
                     its.uv.x,      its.uv.y,      wo.x,          wo.y,          wo.z};
  for (const float x : f)
    if (!std::isfinite(x)) return false;
  return true;
}

// textured: with a texture in the scene, so that both compute the rows' surface coordinates.
void ExpectRowsMatchOracle(const std::string& path, bool textured = false) {
  PTLAB_REQUIRE_DATA(path);
  StatusOr<Scene> loaded = LoadSceneFile(path);
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  Scene& scene = *loaded;
  if (textured) scene.textures.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
  ASSERT_GT(scene.triangles.v0_x.size(), 8u);
  std::vector<uint32_t> hard = AddHardCases(&scene);
  for (const uint32_t tri : AddFrameCases(&scene)) hard.push_back(tri);
  Pcg32 rng(7, 23);
  Packets p = MakePackets(scene, hard, 1000003, rng);
  SetDirections(&p, rng);
  const size_t packets = p.rays.size(), rows = packets * kPacketWidth;
  Rows want(rows);
  const Rows fill(1);
  Lists want_lists(rows);
  MakeInteractionBatch(scene, p.rays.data(), p.hits.data(), p.mask.data(), packets, want.Out(),
                       &want_lists.lists);
  ExpectListsOfRows(p, want.its, want_lists);
  EXPECT_GT(want_lists.lists.area_hits, 0u);  // both scenes have area lights
  size_t with_uv = 0;
  for (const SurfaceInteraction& its : want.its) with_uv += its.uv.x != 0 || its.uv.y != 0;
  if (textured) {
    EXPECT_GT(with_uv, 1000u);
  }
  const simd::TriangleRows tri_rows = simd::BuildTriangleRows(scene);
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Rows got(rows);
    Lists got_lists(rows);
    simd::MakeInteractionBatch(scene, tri_rows, p.rays.data(), p.hits.data(), p.mask.data(),
                               packets, got.Out(), &got_lists.lists);
    ExpectListsMatch(got_lists, want_lists);
    size_t differ = 0, nonfinite = 0, oracle_wrote = 0, first = rows;
    for (size_t q = 0; q < rows; ++q) {
      const bool hit = LaneActive(p.mask[q / kPacketWidth], int(q % kPacketWidth));
      const SurfaceInteraction& g = got.its[q];
      if (!hit) {
        // The oracle leaves the row; the kernel may write it, with finite floats.
        oracle_wrote += std::memcmp(&want.its[q], &fill.its[0], sizeof(SurfaceInteraction)) != 0;
        nonfinite += !FiniteRow(g, got.wo[q]);
        continue;
      }
      nonfinite += !FiniteRow(g, got.wo[q]);
      if (std::memcmp(&g, &want.its[q], sizeof(SurfaceInteraction)) != 0 ||
          std::memcmp(&got.wo[q], &want.wo[q], sizeof(Vec3f)) != 0) {
        ++differ;
        first = std::min(first, q);
      }
    }
    EXPECT_EQ(differ, 0u) << "first differing row " << first << " of " << rows;
    EXPECT_EQ(nonfinite, 0u);
    EXPECT_EQ(oracle_wrote, 0u);
  });
}

// The lists on adversarial hit masks: no hit, all hits, each lane alone, alternating lanes and
// halves, and random masks, over triangles whose materials cycle through every tag and no
// material and whose meshes' emitters cycle through an area light, another tag and none, and
// spheres of every material group (a sphere never emits).
void ExpectListsMatchOracleOnMasks(const std::string& path) {
  PTLAB_REQUIRE_DATA(path);
  StatusOr<Scene> loaded = LoadSceneFile(path);
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  Scene& scene = *loaded;
  const std::vector<uint32_t> hard = AddHardCases(&scene);
  std::vector<MaterialRef> materials = {MaterialRef::None()};
  for (int t = 0; t < kMaterialTagCount; ++t)
    materials.push_back(MaterialRef::Make(MaterialTag(t), uint32_t(t)));
  for (size_t tri = 0; tri < scene.shading.size(); ++tri)
    scene.shading.material[tri] = materials[tri % materials.size()];
  const EmitterRef emitters[] = {EmitterRef::Make(EmitterTag::kArea, 0), EmitterRef::None(),
                                 EmitterRef::Make(EmitterTag::kEnvironment, 0),
                                 EmitterRef::Make(EmitterTag::kArea, 0x0fffffffu)};
  for (size_t m = 0; m < scene.meshes.emitter.size(); ++m)
    scene.meshes.emitter[m] = emitters[m % std::size(emitters)];
  for (const MaterialRef m : materials) scene.spheres.Append({0, 0, 0}, 1.0f, m);
  Pcg32 rng(11, 5);
  Packets p = MakePackets(scene, hard, 40000, rng);
  SetDirections(&p, rng);
  std::vector<Mask8> masks = {0, kAllLanes, 0x55, 0xaa, 0x0f, 0xf0, 0x81, 0x7e};
  for (int j = 0; j < 8; ++j) masks.push_back(LaneBit(j)), masks.push_back(kAllLanes & ~LaneBit(j));
  for (size_t k = 0; k < p.mask.size(); ++k)
    p.mask[k] = k < masks.size() * 4 ? masks[k % masks.size()] : Mask8(rng.NextUint() & 0xff);
  // One packet of nothing but spheres, one without any hit at the end.
  for (int j = 0; j < 8; ++j) p.hits[1].prim[j] = kSphereHitBit | uint32_t(j % materials.size());
  p.mask.back() = 0;
  const size_t packets = p.rays.size(), rows = packets * kPacketWidth;
  Rows want(rows);
  Lists want_lists(rows);
  MakeInteractionBatch(scene, p.rays.data(), p.hits.data(), p.mask.data(), packets, want.Out(),
                       &want_lists.lists);
  ExpectListsOfRows(p, want.its, want_lists);
  for (int g = 0; g < kMaterialGroups; ++g) EXPECT_GT(want_lists.lists.group_hits[g], 0u) << g;
  EXPECT_GT(want_lists.lists.area_hits, 0u);
  const simd::TriangleRows tri_rows = simd::BuildTriangleRows(scene);
  test::ForEachTarget(simd::DispatchedTargetName, [&](const char*) {
    Rows got(rows);
    Lists got_lists(rows);
    simd::MakeInteractionBatch(scene, tri_rows, p.rays.data(), p.hits.data(), p.mask.data(),
                               packets, got.Out(), &got_lists.lists);
    ExpectListsMatch(got_lists, want_lists);
    // Every prefix of packets (down to none) and single packets: the counts restart per call.
    for (const size_t n : {size_t(0), size_t(1), size_t(2), size_t(33)}) {
      Lists w(rows), g(rows);
      Rows scratch(rows);
      MakeInteractionBatch(scene, p.rays.data(), p.hits.data(), p.mask.data(), n, scratch.Out(),
                           &w.lists);
      simd::MakeInteractionBatch(scene, tri_rows, p.rays.data(), p.hits.data(), p.mask.data(), n,
                                 scratch.Out(), &g.lists);
      SCOPED_TRACE(n);
      ExpectListsMatch(g, w);
    }
  });
}

const std::string kSharedData = test_data::Dir();

// The wavefront's rows (no vertex normals in cbox but on the frame-case quads).
TEST(Interaction8, RowsMatchOracleOnCbox) {
  ExpectRowsMatchOracle(std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml");
}

TEST(Interaction8, RowsMatchOracleOnTable) {
  ExpectRowsMatchOracle(kSharedData + "nori/epfl/scenes/pa5/table/table_mis.xml");
}

// In a scene with textures the rows carry their surface coordinates (SurfaceUvAt, SphereUv).
TEST(Interaction8, RowsWithUvMatchOracleInTexturedScenes) {
  ExpectRowsMatchOracle(std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml", true);
  ExpectRowsMatchOracle(kSharedData + "nori/epfl/scenes/pa5/table/table_mis.xml", true);
}

TEST(Interaction8, ListsMatchOracleOnAdversarialMasksCbox) {
  ExpectListsMatchOracleOnMasks(std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml");
}

TEST(Interaction8, ListsMatchOracleOnAdversarialMasksTable) {
  ExpectListsMatchOracleOnMasks(kSharedData + "nori/epfl/scenes/pa5/table/table_mis.xml");
}

}  // namespace
}  // namespace ptlab
