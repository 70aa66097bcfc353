// Chi-square subjects of emission sampling (see emission_subjects.h).
#include "tools/chi2/emission_subjects.h"

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/frame.h"
#include "engine/image/image.h"
#include "engine/light/distant_disk.h"
#include "engine/light/emission.h"
#include "engine/light/environment_map.h"
#include "engine/scene/scene.h"

namespace ptlab {
namespace {

// Appends an area light of `triangles` (no vertex normals) to *scene.
void AddLight(Scene* scene, const std::vector<std::array<Vec3f, 3>>& triangles) {
  const MaterialRef m = scene->materials.AddDiffuse({0.5f, 0.5f, 0.5f});
  const uint32_t light = uint32_t(scene->area_lights.size());
  const uint32_t mesh = uint32_t(scene->meshes.first_triangle.size());
  const EmitterRef e = EmitterRef::Make(EmitterTag::kArea, light);
  scene->meshes.first_triangle.push_back(uint32_t(scene->triangles.size()));
  scene->meshes.triangle_count.push_back(uint32_t(triangles.size()));
  for (const auto& t : triangles) {
    scene->triangles.Append(t[0], t[1], t[2]);
    scene->shading.mesh.push_back(mesh);
    scene->shading.material.push_back(m);
    scene->shading.vertex0.push_back(kNoVertex);
    scene->shading.vertex1.push_back(kNoVertex);
    scene->shading.vertex2.push_back(kNoVertex);
  }
  scene->meshes.material.push_back(m);
  scene->meshes.emitter.push_back(e);
  scene->meshes.has_normals.push_back(0);
  scene->meshes.has_uvs.push_back(0);
  scene->meshes.name.push_back("chi2 emission light");
  scene->area_lights.radiance.push_back({1, 1, 1});
  scene->area_lights.mesh.push_back(mesh);
  scene->emitters.push_back(e);
}

// A fan of twelve uneven triangles around (0.1, -0.05) in the plane z = 0, normal +z.
std::vector<std::array<Vec3f, 3>> Fan() {
  constexpr float kRadius[12] = {0.9f, 0.5f, 0.7f, 0.35f, 0.8f, 0.6f,
                                 1.0f, 0.45f, 0.75f, 0.55f, 0.65f, 0.4f};
  const Vec3f c{0.1f, -0.05f, 0.0f};
  const auto rim = [&](int k) {
    const float a = float(k % 12) * (2.0f * kPi / 12.0f);
    return c + Vec3f{kRadius[k % 12] * std::cos(a), kRadius[k % 12] * std::sin(a), 0.0f};
  };
  std::vector<std::array<Vec3f, 3>> fan;
  for (int k = 0; k < 12; ++k) fan.push_back({c, rim(k), rim(k + 1)});
  return fan;
}

bool InTriangle2D(const std::array<Vec3f, 3>& t, float x, float y) {
  const auto edge = [](const Vec3f& a, const Vec3f& b, float px, float py) {
    return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
  };
  const float e0 = edge(t[0], t[1], x, y), e1 = edge(t[1], t[2], x, y), e2 = edge(t[2], t[0], x, y);
  return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}

// A scene of every emitter kind: a tilted quad light, the fan, a point light, a spot, a
// distant disk and an environment map, around the fan's geometry.
std::shared_ptr<const Scene> EmittersScene() {
  auto s = std::make_shared<Scene>();
  const Vec3f a{-0.5f, -0.4f, 0.2f}, b{0.6f, -0.3f, 0.5f}, c{0.5f, 0.6f, 0.1f}, d{-0.6f, 0.5f, -0.2f};
  AddLight(s.get(), {{a, b, c}, {a, c, d}});  // emitter 0: the quad (planar up to rounding)
  AddLight(s.get(), Fan());                   // emitter 1: the fan
  s->point_lights.position.push_back({0.1f, 0.2f, 0.3f});
  s->point_lights.power.push_back({1, 1, 1});
  s->emitters.push_back(EmitterRef::Make(EmitterTag::kPoint, 0));
  s->spot_lights.position.push_back({0, 0, 1});
  s->spot_lights.axis.push_back(Normalize(Vec3f{0.3f, -0.2f, -1.0f}));
  s->spot_lights.intensity.push_back({1, 1, 1});
  s->spot_lights.cos_half_angle.push_back(std::cos(0.7f));
  s->spot_lights.exponent.push_back(1.0f);
  // No linear ramp (COLLADA's spots): cos^exponent up to the cone's edge.
  s->spot_lights.cos_beam.push_back(s->spot_lights.cos_half_angle.back());
  s->spot_lights.cutoff.push_back(std::acos(s->spot_lights.cos_half_angle.back()));
  s->spot_lights.inv_transition.push_back(0.0f);
  s->emitters.push_back(EmitterRef::Make(EmitterTag::kSpot, 0));
  (void)AddDistantDisk({1, 1, 1}, 40.0f, Frame(Normalize(Vec3f{0.2f, 1.0f, 0.4f})), "disk",
                       &s->distant_disks);
  s->emitters.push_back(EmitterRef::Make(EmitterTag::kDistantDisk, 0));
  Image map(16, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x)
      map.Set(x, y, Color3f{0.2f + float((x * 7 + y * 3) % 11), 0.5f + float(y), 1.0f});
  (void)AddEnvironmentMap(map, EnvironmentMapDesc{}, "chi2 map", &s->environment_maps);
  s->emitters.push_back(EmitterRef::Make(EmitterTag::kEnvironment, 0));
  FinalizeAreaLights(s.get());
  return s;
}

// The emitted direction of emitter k (u1 and a fixed number pick the point; u2 the direction).
Chi2Subject DirectionSubject(std::string name, std::shared_ptr<const Scene> scene, size_t k,
                             bool claim_uniform_hemisphere, Chi2Expect expect) {
  const SceneSphere sphere = BoundingSphereOf(*scene);
  Chi2Subject s;
  s.name = std::move(name);
  s.domain = Chi2Domain::Sphere();
  s.uniform_dims = 3;
  s.params = "emitter " + std::to_string(k) + " of the emission scene";
  const EmitterRef e = scene->emitters[k];
  s.sample = [scene, sphere, e](float u1, const Vec2f& u2, Chi2Point* p) {
    EmissionSample es;
    // The subject is the direction's density: a direction drawn with a density but carrying
    // no light (a spot's direction that rounds onto its cone's edge, where the intensity is 0:
    // 1 in 10^6 here) counts as drawn. SampleEmission returns false for it, and bdpt drops it.
    const bool lit = SampleEmission(*scene, sphere, e, {u1, 0.37f}, u2, &es);
    if (!lit && !(es.pdf_dir > 0)) return false;
    *p = es.w;
    return true;
  };
  // The quad is planar: its normal is the same at every point.
  const TriangleTable& t = scene->triangles;
  const Vec3f n = t.size() > 0 ? Normalize(Cross(t.V1(0) - t.V0(0), t.V2(0) - t.V0(0))) : Vec3f{};
  s.pdf = [scene, sphere, e, n, claim_uniform_hemisphere](const Chi2Point& p) {
    const Vec3f w = Normalize(Vec3f{float(p.x), float(p.y), float(p.z)});
    if (claim_uniform_hemisphere) return Dot(n, w) > 0 ? 1.0 / (2.0 * kPi) : 0.0;
    float pdf_pos, pdf_dir;
    EmissionPdf(*scene, sphere, e, n, w, &pdf_pos, &pdf_dir);
    return double(pdf_dir);
  };
  s.expect = expect;
  return s;
}

}  // namespace

void RegisterEmissionSubjects(Chi2Registry* r) {
  const auto scene = EmittersScene();
  const SceneSphere sphere = BoundingSphereOf(*scene);
  r->Add(DirectionSubject("emission/area_direction", scene, 0, false, Chi2Expect::kPass));
  r->Add(DirectionSubject("emission/point_direction", scene, 2, false, Chi2Expect::kPass));
  r->Add(DirectionSubject("emission/distant_disk_direction", scene, 4, false, Chi2Expect::kPass));
  r->Add(DirectionSubject("emission/spot_direction", scene, 3, false, Chi2Expect::kPass));
  r->Add(DirectionSubject("broken/emission_area_claims_uniform_direction", scene, 0, true,
                          Chi2Expect::kFail));

  // The fan's points, in the plane z = 0 (box domain around it).
  {
    Chi2Subject s;
    s.name = "emission/area_position";
    s.params = "twelve uneven triangles, pdf 1/area";
    s.domain = Chi2Domain::Box(-1.0, -1.1, 1.2, 1.0);
    const EmitterRef e = scene->emitters[1];
    s.sample = [scene, sphere, e](float, const Vec2f& u2, Chi2Point* p) {
      EmissionSample es;
      if (!SampleEmission(*scene, sphere, e, u2, {0.5f, 0.5f}, &es)) return false;
      *p = {es.p.x, es.p.y, 0.0f};
      return true;
    };
    const std::vector<std::array<Vec3f, 3>> fan = Fan();
    const double inv_area = 1.0 / double(scene->area_lights.area[1]);
    s.pdf = [fan, inv_area](const Chi2Point& p) {
      for (const auto& t : fan)
        if (InTriangle2D(t, float(p.x), float(p.y))) return inv_area;
      return 0.0;
    };
    r->Add(std::move(s));
  }
  // The environment map's emitted directions in the map's own (u, v): on the sphere its
  // density has the lat-long map's 1/sin θ poles, which the cell integration cannot resolve
  // (it found a mass of 6); over (u, v) it is piecewise constant. Density: EmissionPdf of the
  // emitted direction w = -(the direction towards the map at (u, v)) times dω/(du dv) = 2π² sin θ.
  {
    Chi2Subject s;
    s.name = "emission/environment_direction";
    s.params = "16 x 8 map, (u, v) of -w, pdf × 2π² sin θ";
    s.domain = Chi2Domain::UnitSquare();
    s.uniform_dims = 3;
    const EmitterRef e = scene->emitters[5];
    const Frame to_world = scene->environment_maps.to_world[e.index()];
    s.sample = [scene, sphere, e, to_world](float u1, const Vec2f& u2, Chi2Point* p) {
      EmissionSample es;
      if (!SampleEmission(*scene, sphere, e, {u1, 0.37f}, u2, &es)) return false;
      const Vec2f uv = EnvironmentDirectionToUv(to_world.ToLocal(-es.w));
      *p = {uv.x, uv.y, 0.0f};
      return true;
    };
    s.pdf = [scene, sphere, e, to_world](const Chi2Point& p) {
      const Vec3f d = EnvironmentUvToDirection({float(p.x), float(p.y)});
      const double sin_theta = std::sqrt(double(d.x) * d.x + double(d.z) * d.z) / Length(d);
      float pdf_pos, pdf_dir;
      EmissionPdf(*scene, sphere, e, Vec3f{}, -to_world.ToWorld(d), &pdf_pos, &pdf_dir);
      return double(pdf_dir) * 2.0 * kPi * kPi * sin_theta;
    };
    r->Add(std::move(s));
  }
  // The environment map's origins on the scene disk, in the disk's unit coordinates.
  {
    Chi2Subject s;
    s.name = "emission/infinite_origin_disk";
    s.params = "pdf_pos × r² on the unit disk";
    s.domain = Chi2Domain::Disk();
    s.uniform_dims = 3;
    const EmitterRef e = scene->emitters[5];
    s.sample = [scene, sphere, e](float u1, const Vec2f& u2, Chi2Point* p) {
      EmissionSample es;
      // The direction from fixed numbers (u1 varies it a little), the origin from u2.
      if (!SampleEmission(*scene, sphere, e, u2, {0.3f + 0.1f * u1, 0.6f}, &es)) return false;
      const Frame frame(-es.w);
      const Vec3f q = (es.p - sphere.center) * (1.0f / sphere.radius) - frame.n;
      *p = {Dot(q, frame.s), Dot(q, frame.t), 0.0f};
      return true;
    };
    const double pdf = 1.0 / kPi;  // pdf_pos × r² = 1/π on the unit disk
    s.pdf = [pdf](const Chi2Point& p) { return p.x * p.x + p.y * p.y <= 1.0 ? pdf : 0.0; };
    r->Add(std::move(s));
  }
}

}  // namespace ptlab
