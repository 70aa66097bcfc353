// Chi-square subjects of geometric samplers: Beckmann normals, area lights, the thin lens.
#include "tools/chi2/geometry_subjects.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "engine/bsdf/beckmann.h"
#include "engine/light/area_light.h"
#include "engine/render/camera.h"
#include "engine/sampling/warp.h"
#include "engine/scene/scene.h"
#include "tools/chi2/lobe_disk.h"

namespace ptlab {
namespace {

// "0.05" -> "0p05": the name becomes a valid GoogleTest parameter name.
std::string AlphaTag(float alpha) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "a%g", double(alpha));
  std::string s = buf;
  for (char& c : s)
    if (c == '.') c = 'p';
  return s;
}

std::string AlphaParams(float alpha) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "alpha=%g", double(alpha));
  return buf;
}

Chi2Subject BeckmannNormalSubject(std::string name, float alpha) {
  Chi2Subject s = DirectionWarpSubject(
      std::move(name), Chi2Domain::Hemisphere(),
      [alpha](const Vec2f& u) { return SampleBeckmannNormal(alpha, u); },
      [alpha](const Vec3f& h) { return BeckmannPdfH(alpha, h); });
  s.pdf = FlushLobeTail(std::move(s.pdf), BeckmannPdfH(alpha, {0, 0, 1}));
  s.params = AlphaParams(alpha);
  return s;
}

double Cross(const Vec2f& a, const Vec2f& b, const Vec2f& p) {
  return (double(b.x) - a.x) * (double(p.y) - a.y) - (double(b.y) - a.y) * (double(p.x) - a.x);
}

// One area light: the quad of the header as a two-triangle mesh, emitting on +z.
std::shared_ptr<Scene> QuadLightScene() {
  auto scene = std::make_shared<Scene>();
  const auto at = [](const Vec2f& p) { return Vec3f{p.x, p.y, kChi2QuadZ}; };
  scene->triangles.Append(at(kChi2QuadA), at(kChi2QuadB), at(kChi2QuadC));
  scene->triangles.Append(at(kChi2QuadA), at(kChi2QuadC), at(kChi2QuadD));
  const MaterialRef material = scene->materials.AddDiffuse({0.5f, 0.5f, 0.5f});
  for (int i = 0; i < 2; ++i) {
    scene->shading.mesh.push_back(0);
    scene->shading.material.push_back(material);
    scene->shading.vertex0.push_back(kNoVertex);
    scene->shading.vertex1.push_back(kNoVertex);
    scene->shading.vertex2.push_back(kNoVertex);
  }
  const EmitterRef emitter = EmitterRef::Make(EmitterTag::kArea, 0);
  MeshTable& meshes = scene->meshes;
  meshes.first_triangle.push_back(0);
  meshes.triangle_count.push_back(2);
  meshes.material.push_back(material);
  meshes.emitter.push_back(emitter);
  meshes.has_normals.push_back(0);
  meshes.has_uvs.push_back(0);
  meshes.name.push_back("chi2 quad");
  scene->area_lights.radiance.push_back({1.0f, 1.0f, 1.0f});
  scene->area_lights.mesh.push_back(0);
  scene->emitters.push_back(emitter);
  FinalizeAreaLights(scene.get());
  return scene;
}

Chi2Subject AreaLightSubject(std::string name, std::shared_ptr<const Scene> scene,
                             Chi2Expect expect) {
  Chi2Subject s;
  s.name = std::move(name);
  s.params = "quad split into triangles of area 0.2938 and 0.11395, plane z = 0.25";
  s.domain = Chi2Domain::UnitSquare();
  // Sampled by area from a point one unit in front of the light's emitting side.
  const Vec3f front = Vec3f{0.0f, 0.0f, 0.25f} + ShadingNormalAt(*scene, 0, 0.3f, 0.3f);
  s.sample = [scene, front](float, const Vec2f& u2, Chi2Point* p) {
    const AreaLightSample ls = SampleAreaLight(*scene, 0, front, TriangleSampling::kArea, u2);
    *p = {ls.p.x, ls.p.y, 0.0f};
    // The light must claim a density for every point it samples (seen from the front).
    return ls.pdf > 0;
  };
  // 1/area inside the quad (convex, so inside = left of all four edges), from the corners in
  // double: independent of the area FinalizeAreaLights computed.
  const double area =
      0.5 * (Cross(kChi2QuadA, kChi2QuadB, kChi2QuadC) + Cross(kChi2QuadA, kChi2QuadC, kChi2QuadD));
  s.pdf = [area](const Chi2Point& p) {
    const Vec2f q{p.x, p.y};
    const bool inside =
        Cross(kChi2QuadA, kChi2QuadB, q) >= 0 && Cross(kChi2QuadB, kChi2QuadC, q) >= 0 &&
        Cross(kChi2QuadC, kChi2QuadD, q) >= 0 && Cross(kChi2QuadD, kChi2QuadA, q) >= 0;
    return inside ? 1.0 / area : 0.0;
  };
  s.expect = expect;
  return s;
}

}  // namespace

void RegisterGeometrySubjects(Chi2Registry* r) {
  // The Beckmann half-vector warp. On the hemisphere grid (51 rows in cosθ) a lobe is resolved
  // once 1 − cosθ at θ = atan α spans a few rows: α >= 0.3. Below, the zoomed disk.
  for (float alpha : {0.3f, 1.0f, 2.0f})
    r->Add(BeckmannNormalSubject("warp/beckmann_normal_" + AlphaTag(alpha), alpha));
  for (float alpha : {1e-4f, 1e-3f, 0.05f, 0.3f}) {
    r->Add(OnLobeDisk(BeckmannNormalSubject("warp/beckmann_normal_zoom_" + AlphaTag(alpha), alpha),
                      LobeDisk({0, 0, 1}, alpha)));
  }

  const std::shared_ptr<Scene> quad = QuadLightScene();
  r->Add(AreaLightSubject("area_light/quad", quad, Chi2Expect::kPass));

  CameraDesc desc;
  desc.width = 64, desc.height = 48;
  desc.aperture_radius = 0.3f;
  desc.focus_distance = 2.5f;
  const float radius = desc.aperture_radius;
  const Camera camera(desc);
  Chi2Subject lens = PlanarWarpSubject(
      "camera/thin_lens_aperture", Chi2Domain::Disk(),
      [camera, radius](const Vec2f& u) {
        // An off-centre film position: the lens point must not depend on it.
        const Ray ray = camera.GenerateRay(41.3f, 9.7f, u);
        return Vec2f{ray.o.x / radius, ray.o.y / radius};
      },
      UniformDiskPdf);
  lens.params = "aperture radius 0.3, focus 2.5, identity camera_to_world; origin / radius";
  r->Add(std::move(lens));

  constexpr Chi2Expect kFail = Chi2Expect::kFail;
  Chi2Subject no_sin = DirectionWarpSubject(
      "broken/beckmann_normal_pdf_no_sin_jacobian", Chi2Domain::Hemisphere(),
      [](const Vec2f& u) { return SampleBeckmannNormal(0.5f, u); },
      [](const Vec3f& h) {
        const float sin_t = std::sqrt(std::max(0.0f, h.x * h.x + h.y * h.y));
        return BeckmannPdfH(0.5f, h) * sin_t;
      },
      kFail);
  no_sin.params = AlphaParams(0.5f);
  r->Add(std::move(no_sin));
  // The true (flushed) pdf of α = 0.3, with a sampler that takes Walter's tanθ for θ.
  Chi2Subject theta_from_tan = BeckmannNormalSubject("broken/beckmann_normal_theta_from_tan", 0.3f);
  theta_from_tan.sample = [](float, const Vec2f& u, Chi2Point* p) {
    const float theta = 0.3f * std::sqrt(-std::log1p(-ClampSample(u.x)));
    const float phi = 2.0f * kPi * u.y;
    *p = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
    return true;
  };
  theta_from_tan.expect = kFail;
  r->Add(OnLobeDisk(std::move(theta_from_tan), LobeDisk({0, 0, 1}, 0.3)));

  auto uniform_choice = std::make_shared<Scene>(*quad);
  uniform_choice->area_lights.triangle_cdf[0] = 0.5f;
  r->Add(AreaLightSubject("broken/area_light_uniform_triangle_choice", uniform_choice, kFail));
}

}  // namespace ptlab
