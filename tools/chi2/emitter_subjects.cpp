// Chi-square subjects of emitter sampling.
#include "tools/chi2/emitter_subjects.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/light/area_light.h"
#include "engine/light/light_selection.h"
#include "engine/sampling/spherical_triangle.h"
#include "engine/scene/scene.h"

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

// Quad lights around the origin (each two triangles, no vertex normals); the origin is on
// their emitting sides.
std::shared_ptr<Scene> QuadLightsScene(const std::vector<QuadLight>& quads) {
  auto scene = std::make_shared<Scene>();
  const MaterialRef material = scene->materials.AddDiffuse({0.5f, 0.5f, 0.5f});
  for (const QuadLight& q : quads) {
    const uint32_t light = uint32_t(scene->area_lights.size());
    const uint32_t first = uint32_t(scene->triangles.size());
    const Vec3f a = q.corner, b = q.corner + q.edge_u, c = b + q.edge_v, d = q.corner + q.edge_v;
    scene->triangles.Append(a, b, c);
    scene->triangles.Append(a, c, d);
    const EmitterRef emitter = EmitterRef::Make(EmitterTag::kArea, light);
    for (int i = 0; i < 2; ++i) {
      scene->shading.material.push_back(material);
      scene->shading.vertex0.push_back(kNoVertex);
      scene->shading.vertex1.push_back(kNoVertex);
      scene->shading.vertex2.push_back(kNoVertex);
    }
    MeshTable& meshes = scene->meshes;
    meshes.first_triangle.push_back(first);
    meshes.triangle_count.push_back(2);
    meshes.material.push_back(material);
    meshes.emitter.push_back(emitter);
    meshes.has_normals.push_back(0);
    meshes.has_uvs.push_back(0);
    meshes.name.push_back("chi2 light " + std::to_string(light));
    scene->area_lights.radiance.push_back(q.radiance);
    scene->area_lights.mesh.push_back(light);
    scene->emitters.push_back(emitter);
  }
  FinalizeAreaLights(scene.get());
  return scene;
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
    const D3 w = Unit({p.x, p.y, p.z});
    double pdf = 0;
    for (uint32_t tri = 0; tri < scene->triangles.size(); ++tri) {
      const Triangle t{scene->triangles.V0(tri), scene->triangles.V1(tri), scene->triangles.V2(tri)};
      const double dist = HitDistance(t, w);
      if (!(dist > 0)) continue;
      const uint32_t light = tri / 2;
      const Vec3f at{float(w.x * dist), float(w.y * dist), float(w.z * dist)};
      const Vec3f n = Normalize(Cross(t[1] - t[0], t[2] - t[0]));
      const float pmf = claim_uniform_pmf
                            ? 1.0f / float(scene->emitters.size())
                            : EmitterSelectionPmf(*scene, scene->emitters[light]);
      pdf += double(pmf) * double(AreaLightPdf(*scene, light, tri, at, n, Vec3f{},
                                               scene->integrator.triangle_sampling));
    }
    return pdf;
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
}

}  // namespace ptlab
