// Chi-square subjects of emitter sampling.
#include "tools/chi2/emitter_subjects.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/io/mesh_builder.h"
#include "engine/io/mitsuba_meshes.h"
#include "engine/light/area_light.h"
#include "engine/light/light_selection.h"
#include "engine/sampling/spherical_triangle.h"
#include "engine/scene/scene.h"
#include "simd/dispatched_target.h"
#include "simd/wavefront/area_light8.h"

namespace ptlab {
namespace {

struct D3 {
  double x, y, z;
};
D3 Sub(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double Dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 Cross(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
D3 Unit(const D3& a) {
  const double l = std::sqrt(Dot(a, a));
  return {a.x / l, a.y / l, a.z / l};
}
D3 ToD3(const Vec3f& v) { return {v.x, v.y, v.z}; }

using Triangle = std::array<Vec3f, 3>;

// Solid angle of the triangle seen from the origin by Girard's theorem: the sum of the
// spherical triangle's corner angles minus π.
double GirardSolidAngle(const Triangle& t) {
  const D3 a = Unit(ToD3(t[0])), b = Unit(ToD3(t[1])), c = Unit(ToD3(t[2]));
  const auto corner = [](const D3& p, const D3& q, const D3& r) {
    // Angle at p between the great circles towards q and r.
    const D3 tq = Unit(Sub(q, {Dot(p, q) * p.x, Dot(p, q) * p.y, Dot(p, q) * p.z}));
    const D3 tr = Unit(Sub(r, {Dot(p, r) * p.x, Dot(p, r) * p.y, Dot(p, r) * p.z}));
    return std::acos(std::clamp(Dot(tq, tr), -1.0, 1.0));
  };
  return corner(a, b, c) + corner(b, c, a) + corner(c, a, b) - 3.14159265358979323846;
}

// Distance along unit w from the origin to triangle t, or -1 when the ray misses it.
double HitDistance(const Triangle& t, const D3& w) {
  const D3 v0 = ToD3(t[0]), e1 = Sub(ToD3(t[1]), v0), e2 = Sub(ToD3(t[2]), v0);
  const D3 p = Cross(w, e2);
  const double det = Dot(e1, p);
  if (det == 0) return -1;
  const D3 s = Sub({0, 0, 0}, v0);
  const double b1 = Dot(s, p) / det;
  const D3 q = Cross(s, e1);
  const double b2 = Dot(w, q) / det;
  const double dist = Dot(e2, q) / det;
  return (b1 >= 0 && b2 >= 0 && b1 + b2 <= 1 && dist > 0) ? dist : -1;
}

Vec3f Direction(const Vec3f& p) {
  const float l = Length(p);
  return p / l;
}

Chi2Subject SphericalTriangleSubject(std::string name, const Triangle& t, std::string params) {
  Chi2Subject s;
  s.name = std::move(name);
  s.params = std::move(params);
  s.domain = Chi2Domain::Sphere();
  s.sample = [t](float, const Vec2f& u, Chi2Point* p) {
    SphericalTriangleSample st;
    if (!SampleSphericalTriangle(t[0], t[1], t[2], Vec3f{}, u, &st)) return false;
    *p = Direction(st.p);
    return true;
  };
  const double omega = GirardSolidAngle(t);
  s.pdf = [t, omega](const Chi2Point& p) {
    const D3 w = Unit({p.x, p.y, p.z});
    return HitDistance(t, w) > 0 ? 1.0 / omega : 0.0;
  };
  return s;
}

struct QuadLight {
  Vec3f corner, edge_u, edge_v;  // emits on the side of edge_u × edge_v
  Color3f radiance;
};

// Appends an emitting mesh of `triangles` with `material` (each triangle emits on the side of
// (v1 - v0) × (v2 - v0)); a non-zero `normal` is every vertex's shading normal (the mesh then
// has vertex normals). Call FinalizeAreaLights once every light is in.
void AddMeshLight(Scene* scene, MaterialRef material, const std::vector<Triangle>& triangles,
                  const Color3f& radiance, const Vec3f& normal) {
  const uint32_t light = uint32_t(scene->area_lights.size());
  const uint32_t mesh = uint32_t(scene->meshes.first_triangle.size());
  const bool has_normals = normal.x != 0 || normal.y != 0 || normal.z != 0;
  const EmitterRef emitter = EmitterRef::Make(EmitterTag::kArea, light);
  MeshTable& meshes = scene->meshes;
  meshes.first_triangle.push_back(uint32_t(scene->triangles.size()));
  meshes.triangle_count.push_back(uint32_t(triangles.size()));
  VertexTable& v = scene->vertices;
  for (const Triangle& t : triangles) {
    scene->triangles.Append(t[0], t[1], t[2]);
    scene->shading.mesh.push_back(mesh);
    scene->shading.material.push_back(material);
    for (AlignedVector<uint32_t>* column :
         {&scene->shading.vertex0, &scene->shading.vertex1, &scene->shading.vertex2}) {
      column->push_back(has_normals ? uint32_t(v.n_x.size()) : kNoVertex);
      if (has_normals)
        v.n_x.push_back(normal.x), v.n_y.push_back(normal.y), v.n_z.push_back(normal.z);
    }
  }
  meshes.material.push_back(material);
  meshes.emitter.push_back(emitter);
  meshes.has_normals.push_back(has_normals ? 1 : 0);
  meshes.has_uvs.push_back(0);
  meshes.name.push_back("chi2 light " + std::to_string(light));
  scene->area_lights.radiance.push_back(radiance);
  scene->area_lights.mesh.push_back(mesh);
  scene->emitters.push_back(emitter);
}

// Quad lights around the origin (each two triangles, no vertex normals); the origin is on
// their emitting sides.
std::shared_ptr<Scene> QuadLightsScene(const std::vector<QuadLight>& quads) {
  auto scene = std::make_shared<Scene>();
  const MaterialRef material = scene->materials.AddDiffuse({0.5f, 0.5f, 0.5f});
  for (const QuadLight& q : quads) {
    const Vec3f a = q.corner, b = q.corner + q.edge_u, c = b + q.edge_v, d = q.corner + q.edge_v;
    AddMeshLight(scene.get(), material, {Triangle{a, b, c}, Triangle{a, c, d}}, q.radiance,
                 Vec3f{});
  }
  FinalizeAreaLights(scene.get());
  return scene;
}

// Solid-angle density at the origin of the direction p (any length) when each light is picked
// with probability pmf(light) and sampled by `mode`: Σ over the triangles the ray hits.
template <typename Pmf>
double LightsPdfFromOrigin(const Scene& scene, TriangleSampling mode, const Chi2Point& p, Pmf pmf) {
  const D3 w = Unit({p.x, p.y, p.z});
  double pdf = 0;
  for (uint32_t tri = 0; tri < scene.triangles.size(); ++tri) {
    const Triangle t{scene.triangles.V0(tri), scene.triangles.V1(tri), scene.triangles.V2(tri)};
    const double dist = HitDistance(t, w);
    if (!(dist > 0)) continue;
    const uint32_t light = scene.meshes.emitter[scene.shading.mesh[tri]].index();
    const Vec3f at{float(w.x * dist), float(w.y * dist), float(w.z * dist)};
    const Vec3f n = Normalize(Cross(t[1] - t[0], t[2] - t[0]));
    pdf += double(pmf(light)) * double(AreaLightPdf(scene, light, tri, at, n, Vec3f{}, mode));
  }
  return pdf;
}

// Directions from the origin towards the scene's lights, picked by the scene's light selection
// (u1, rescaled, also picks the triangle) and sampled by its triangle sampling.
Chi2Subject EmitterSelectionSubject(std::string name, std::shared_ptr<const Scene> scene,
                                    bool claim_uniform_pmf, Chi2Expect expect) {
  Chi2Subject s;
  s.name = std::move(name);
  s.domain = Chi2Domain::Sphere();
  s.uniform_dims = 3;  // u1 picks the light, u2 the point (and the light's triangle)
  s.params = std::string("lights=") +
             (scene->integrator.light_selection == LightSelection::kPower ? "power" : "uniform") +
             " triangles=" +
             (scene->integrator.triangle_sampling == TriangleSampling::kSolidAngle ? "solidAngle"
                                                                                    : "area");
  s.sample = [scene](float u1, const Vec2f& u2, Chi2Point* p) {
    float pmf = 0;
    const EmitterRef e = SelectEmitter(*scene, u1, &pmf);
    if (!(pmf > 0)) return false;
    const AreaLightSample ls =
        SampleAreaLight(*scene, e.index(), Vec3f{}, scene->integrator.triangle_sampling, u2);
    if (!(ls.pdf > 0)) return false;
    *p = Direction(ls.p);
    return true;
  };
  s.pdf = [scene, claim_uniform_pmf](const Chi2Point& p) {
    return LightsPdfFromOrigin(*scene, scene->integrator.triangle_sampling, p,
                               [&scene, claim_uniform_pmf](uint32_t light) {
                                 return claim_uniform_pmf
                                            ? 1.0f / float(scene->emitters.size())
                                            : EmitterSelectionPmf(*scene, scene->emitters[light]);
                               });
  };
  s.expect = expect;
  return s;
}

// A star-shaped polygon in the plane z = 0.7 above the origin, facing it (normal -z): a fan of
// twelve 30° triangles of uneven radii around (0.15, -0.1, 0.7), so the triangle pick meets
// CDF steps of different widths. Every triangle subtends 0.03 to 0.2 sr from the origin: the
// solid-angle mode samples each by solid angle.
std::vector<Triangle> FanLight() {
  constexpr float kRadius[12] = {0.9f, 0.5f, 0.7f, 0.35f, 0.8f, 0.6f,
                                 1.0f, 0.45f, 0.75f, 0.55f, 0.65f, 0.4f};
  const Vec3f centre{0.15f, -0.1f, 0.7f};
  const auto rim = [&](int k) {
    const float a = float(k % 12) * (2.0f * 3.14159265f / 12.0f);
    return centre + Vec3f{kRadius[k % 12] * std::cos(a), kRadius[k % 12] * std::sin(a), 0.0f};
  };
  std::vector<Triangle> fan;
  for (int k = 0; k < 12; ++k) fan.push_back({centre, rim(k + 1), rim(k)});  // (e1 × e2).z < 0
  return fan;
}

// Rows of one call of the batch.
constexpr int kBatchRows = 1024;

// simd::SampleAreaLightBatch from the origin, `mode`: u1 picks one of the scene's lights
// uniformly (rows of a batch mix lights; one light: u1 unused), u2 goes to the batch. The pdf
// is AreaLightPdf under `claimed_mode` (the scalar oracle's density when it is `mode`).
Chi2Subject SimdAreaLightSubject(std::string name, std::shared_ptr<const Scene> scene,
                                 TriangleSampling mode, TriangleSampling claimed_mode,
                                 Chi2Expect expect) {
  const uint32_t lights = uint32_t(scene->area_lights.size());
  Chi2Subject s;
  s.name = std::move(name);
  s.domain = Chi2Domain::Sphere();
  s.uniform_dims = lights > 1 ? 3 : 2;
  s.params = std::to_string(lights) + " light(s), uniform pick, triangles=" +
             (mode == TriangleSampling::kSolidAngle ? "solidAngle" : "area") +
             " target=" + simd::DispatchedTargetName();
  auto rows = std::make_shared<const simd::TriangleRows>(simd::BuildTriangleRows(*scene));
  s.sample_batch = [scene, rows, mode, lights](const float* u1, const Vec2f* u2, int n,
                                               Chi2Point* p, uint8_t* ok) {
    uint32_t light[kBatchRows];
    float zero[kBatchRows] = {}, u_x[kBatchRows], u_y[kBatchRows];
    float p_x[kBatchRows], p_y[kBatchRows], p_z[kBatchRows], n_x[kBatchRows], n_y[kBatchRows],
        n_z[kBatchRows], ng_x[kBatchRows], ng_y[kBatchRows], ng_z[kBatchRows], pdf[kBatchRows];
    for (int begin = 0; begin < n; begin += kBatchRows) {
      const int count = std::min(kBatchRows, n - begin);
      for (int i = 0; i < count; ++i) {
        light[i] = std::min(uint32_t(u1[begin + i] * float(lights)), lights - 1);
        u_x[i] = u2[begin + i].x, u_y[i] = u2[begin + i].y;
      }
      AreaLightBatchInputs in;
      in.light = light, in.ref_x = zero, in.ref_y = zero, in.ref_z = zero;
      in.u_x = u_x, in.u_y = u_y;
      const AreaLightBatchOutputs out{p_x, p_y, p_z, n_x, n_y, n_z, ng_x, ng_y, ng_z, pdf};
      simd::SampleAreaLightBatch(*scene, *rows, mode, size_t(count), in, out);
      for (int i = 0; i < count; ++i) {
        ok[begin + i] = pdf[i] > 0 ? 1 : 0;
        p[begin + i] = Direction({p_x[i], p_y[i], p_z[i]});
      }
    }
  };
  s.pdf = [scene, claimed_mode, lights](const Chi2Point& p) {
    return LightsPdfFromOrigin(*scene, claimed_mode, p,
                               [lights](uint32_t) { return 1.0f / float(lights); });
  };
  s.expect = expect;
  return s;
}

}  // namespace

void RegisterEmitterSubjects(Chi2Registry* r) {
  r->Add(SphericalTriangleSubject("emitter/spherical_triangle_near",
                                  {Vec3f{-0.6f, -0.5f, 1.0f}, Vec3f{0.7f, -0.4f, 1.1f},
                                   Vec3f{0.1f, 0.8f, 0.9f}},
                                  "triangle ahead at distance ~1"));
  r->Add(SphericalTriangleSubject("emitter/spherical_triangle_oblique",
                                  {Vec3f{0.5f, 0.0f, 0.2f}, Vec3f{2.0f, 0.3f, 0.1f},
                                   Vec3f{1.0f, 1.5f, 0.6f}},
                                  "tilted triangle seen at grazing angles"));
  r->Add(SphericalTriangleSubject("emitter/spherical_triangle_wide",
                                  {Vec3f{-2.0f, -1.5f, 0.5f}, Vec3f{2.0f, -1.5f, 0.5f},
                                   Vec3f{0.0f, 2.5f, 0.5f}},
                                  "large triangle close to the origin"));

  // Quads facing the origin: powers ∝ radiance × area = 1 × 0.36, 4 × 0.5, 0.5 × 1.2, 30 × 0.04.
  const std::vector<QuadLight> quads = {
      {{-0.3f, -0.3f, 1.5f}, {0.0f, 0.6f, 0.0f}, {0.6f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}},
      {{1.2f, -0.5f, -0.5f}, {0.0f, 0.0f, 1.0f}, {0.0f, 0.5f, 0.0f}, {4.0f, 3.0f, 5.0f}},
      {{-0.6f, -1.0f, -0.5f}, {0.0f, 0.0f, 1.0f}, {1.2f, 0.0f, 0.0f}, {0.5f, 0.4f, 0.6f}},
      // Small and far (0.0025 sr): sampled by area even with triangles=solidAngle, so the
      // distribution mixes both rules and the pdf must follow the same switch.
      {{-0.1f, -0.1f, -4.0f}, {0.2f, 0.0f, 0.0f}, {0.0f, 0.2f, 0.0f}, {30.0f, 30.0f, 30.0f}},
  };
  auto power = QuadLightsScene(quads);
  power->integrator.light_selection = LightSelection::kPower;
  power->integrator.triangle_sampling = TriangleSampling::kSolidAngle;
  r->Add(EmitterSelectionSubject("emitter/power_selection_four_quads", power, false,
                                 Chi2Expect::kPass));
  auto uniform = std::make_shared<Scene>(*power);
  uniform->integrator.light_selection = LightSelection::kUniform;
  uniform->integrator.triangle_sampling = TriangleSampling::kArea;
  r->Add(EmitterSelectionSubject("emitter/uniform_selection_area_sampling", uniform, false,
                                 Chi2Expect::kPass));
  r->Add(EmitterSelectionSubject("broken/power_selection_claims_uniform_pmf", power, true,
                                 Chi2Expect::kFail));

  // The SIMD area-light batch: the fan (vertex normals) in both modes, and the quads with a
  // light per row (no vertex normals). Broken: area samples claimed to be solid-angle ones
  // (both integrate to 1 over the fan's solid angle; only the histogram can tell).
  auto fan = std::make_shared<Scene>();
  AddMeshLight(fan.get(), fan->materials.AddDiffuse({0.5f, 0.5f, 0.5f}), FanLight(),
               {1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, -1.0f});
  FinalizeAreaLights(fan.get());
  constexpr TriangleSampling kArea = TriangleSampling::kArea;
  constexpr TriangleSampling kSolidAngle = TriangleSampling::kSolidAngle;
  r->Add(SimdAreaLightSubject("simd/area_light_fan_area", fan, kArea, kArea, Chi2Expect::kPass));
  r->Add(SimdAreaLightSubject("simd/area_light_fan_solid_angle", fan, kSolidAngle, kSolidAngle,
                              Chi2Expect::kPass));
  r->Add(SimdAreaLightSubject("simd/area_light_four_quads_area", power, kArea, kArea,
                              Chi2Expect::kPass));
  r->Add(SimdAreaLightSubject("broken/simd_area_light_fan_claims_solid_angle_pdf", fan, kArea,
                              kSolidAngle, Chi2Expect::kFail));

  // Mitsuba's cylinder and disk as emitters (engine/io/mitsuba_meshes.h, far coarser than the
  // loader's 1024 segments to keep the pdf's loop over triangles short). Emitters are one-sided,
  // so both face the origin: the origin is on the axis inside the cylinder (radius 0.9, z from
  // -0.8 to 0.8), its normals flipped inward, and an elliptic disk above it faces down; uniform
  // pick, area sampling, scalar and SIMD.
  auto shapes = std::make_shared<Scene>();
  const MaterialRef grey = shapes->materials.AddDiffuse({0.5f, 0.5f, 0.5f});
  MeshData tube = MakeMitsubaCylinder(8);
  for (size_t t = 0; t + 2 < tube.indices.size(); t += 3)
    std::swap(tube.indices[t + 1], tube.indices[t + 2]);
  for (Vec3f& n : tube.normals) n = -n;
  const uint32_t cylinder =
      AddMesh(shapes.get(), tube,
              Transform::Translate({0.0f, 0.0f, -0.8f}) * Transform::Scale({0.9f, 0.9f, 1.6f}),
              grey, "cylinder");
  AttachAreaLight(shapes.get(), cylinder, {1.0f, 1.0f, 1.0f});
  const uint32_t disk = AddMesh(shapes.get(), MakeMitsubaDisk(6),
                                Transform::Translate({0.1f, 0.05f, 0.6f}) *
                                    Transform::Rotate({1.0f, 0.2f, 0.0f}, 165.0f) *
                                    Transform::Scale({0.5f, 0.3f, 1.0f}),
                                grey, "disk");
  AttachAreaLight(shapes.get(), disk, {2.0f, 2.0f, 2.0f});
  FinalizeAreaLights(shapes.get());
  shapes->integrator.light_selection = LightSelection::kUniform;
  shapes->integrator.triangle_sampling = kArea;
  r->Add(EmitterSelectionSubject("emitter/mitsuba_cylinder_and_disk_area", shapes, false,
                                 Chi2Expect::kPass));
  r->Add(SimdAreaLightSubject("simd/area_light_mitsuba_cylinder_and_disk_area", shapes, kArea,
                              kArea, Chi2Expect::kPass));
}

}  // namespace ptlab
