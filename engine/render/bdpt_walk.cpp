// The subpath walks of bidirectional path tracing (bdpt_walk.h): the loop of a random walk cut
// at its traversal, so that the caller traces the rays of many walks together.
#include "engine/render/bdpt_walk.h"

#include <algorithm>
#include <cmath>

#include "engine/bsdf/bsdf.h"
#include "engine/bvh/ray_offset.h"
#include "engine/light/light_selection.h"
#include "engine/render/integrator_common.h"

namespace ptlab::bdpt {

using namespace integrator;

void StartCameraWalk(const BidirectionalSetup& setup, const Ray& ray, int max_vertices,
                     Subpath* camera, Walk* walk) {
  Vertex& c0 = At(camera, 0);
  c0 = Vertex{};
  c0.kind = VertexKind::kCamera;
  c0.p = ray.o;
  c0.beta = {1, 1, 1};
  const Vec3f d = ray.d / Length(ray.d);
  *walk = Walk{};
  walk->ray = ray;
  walk->beta = {1, 1, 1};
  walk->pdf_dir = setup.camera.DirectionPdf(ray.o, d);
  walk->n = 1;
  walk->max_vertices = max_vertices;
  walk->active = walk->n < max_vertices;
}

void StartLightWalk(const Scene& scene, const BidirectionalSetup& setup, int max_vertices,
                    PathSampler& sampler, Subpath* light, Walk* walk) {
  *walk = Walk{};
  walk->light_subpath = true;
  walk->max_vertices = max_vertices;
  if (max_vertices <= 0 || scene.emitters.empty()) return;
  const int depth = kLightSubpathDepth;
  EmitterNumbers numbers = DrawEmitterNumbers(sampler, depth, 0, 1);
  const Vec2f u_dir = sampler.Get2D(DecisionDimension(depth, Decision::kBsdfDirection));
  float pmf = 0.0f;
  const EmitterRef e = PickEmitter(scene, &numbers, &pmf);
  EmissionSample es;
  if (!(pmf > 0) || !SampleEmission(scene, setup.sphere, e, numbers.point, u_dir, &es)) return;
  if (!(es.pdf_pos > 0) || !(es.pdf_dir > 0)) return;
  Vertex& x0 = At(light, 0);
  x0 = Vertex{};
  x0.kind = VertexKind::kLight;
  x0.emitter = e;
  x0.infinite = es.infinite;
  walk->n = 1;
  Color3f beta;
  if (es.infinite) {
    x0.w = -es.w;
    x0.pdf_fwd = e.tag() == EmitterTag::kDirectional ? pmf : pmf * es.pdf_dir;
    // The cosine at the first hit cancels against the disk's projection (PdfLight).
    beta = es.radiance * (1.0f / (pmf * es.pdf_pos * es.pdf_dir));
  } else {
    x0.p = es.p, x0.n = es.n, x0.ng = es.ng;
    x0.on_surface = e.tag() == EmitterTag::kArea;
    x0.pdf_fwd = pmf * es.pdf_pos;
    x0.beta = Color3f{1, 1, 1} * (1.0f / x0.pdf_fwd);
    const float cos = x0.on_surface ? std::abs(Dot(es.ng, es.w)) : 1.0f;
    beta = es.radiance * (cos / (x0.pdf_fwd * es.pdf_dir));
  }
  if (!IsFinite(beta) || IsBlack(beta)) return;
  walk->ray.o =
      x0.on_surface ? OffsetRayOrigin(es.p, Dot(es.ng, es.w) >= 0 ? es.ng : -es.ng) : es.p;
  walk->ray.d = es.w;
  walk->ray.t_min = 0.0f;
  walk->ray.t_max = kInfinity;
  walk->beta = beta;
  // From infinity the first vertex's density is the disk's (area) times the cosine there,
  // set when it is found (StepWalk); the walk converts solid-angle densities.
  walk->infinite_origin = es.infinite;
  walk->pdf_dir = es.infinite ? 0.0f : es.pdf_dir;
  walk->active = walk->n < max_vertices;
}

void StepWalk(const Scene& scene, const BidirectionalSetup& setup, const Hit* hit,
              PathSampler& sampler, Subpath* path, Walk* walk) {
  Walk& w = *walk;
  w.active = false;
  const Ray& ray = w.ray;
  if (hit == nullptr) {
    // A camera subpath that escapes ends at infinity, where s = 0 finds the environment.
    const bool infinite_lights = scene.environment_maps.size() + scene.distant_disks.size() > 0;
    if (!w.light_subpath && infinite_lights) {
      Vertex& e = At(path, w.n);
      e = Vertex{};
      e.kind = VertexKind::kLight;
      e.infinite = true;
      e.w = ray.d / Length(ray.d);
      e.beta = w.beta;
      e.pdf_fwd = w.pdf_dir;
      ++w.n;
    }
    return;
  }
  At(path, w.n);  // grow first: the references below stay valid
  Vertex& prev = (*path)[size_t(w.n - 1)];
  Vertex& x = (*path)[size_t(w.n)];
  x = Vertex{};
  x.kind = VertexKind::kSurface;
  x.its = MakeInteraction(scene, ray, *hit);
  x.p = x.its.p, x.ng = x.its.ng, x.n = x.its.frame.n;
  x.on_surface = true;
  x.emitter = x.its.emitter;
  x.wo = -ray.d / Length(ray.d);
  x.beta = w.beta;
  x.pdf_fwd = ConvertDensity(w.pdf_dir, prev, x);
  x.delta = IsDeltaMaterial(x.its.material.tag());
  x.to_prev = x.its.frame.ToLocal(DirectionTo(x, prev));
  if (w.infinite_origin && w.n == 1) x.pdf_fwd = PdfLight(scene, setup, prev, x);
  ++w.n;
  if (w.n >= w.max_vertices) return;
  const int depth = w.light_subpath ? kLightSubpathDepth + 1 + w.bounce : w.bounce;
  if (w.bounce >= 3) {
    const float q = std::min(MaxComponent(w.ratio) * w.eta * w.eta, 0.99f);
    if (!(sampler.Get1D(DecisionDimension(depth, Decision::kRoulette)) < q)) return;
    w.beta = w.beta * (1.0f / q);
    w.ratio = w.ratio * (1.0f / q);
  }
  const Vec3f wo = x.its.frame.ToLocal(x.wo);
  BsdfSample bs;
  if (!SampleBsdf(scene, x.its, wo, sampler, depth, &bs)) return;
  const Vec3f wi = x.its.frame.ToWorld(bs.wi);
  Color3f weight = bs.weight;
  if (w.light_subpath) {
    weight = weight * ShadingNormalCorrection(x.its, x.wo, wi);
    // A dielectric that scales radiance by (η_o/η_i)² on refraction: importance is not
    // scaled (Veach 5.2), so the light subpath takes the scale back out.
    if (bs.delta && bs.eta != 1.0f && x.its.material.tag() == MaterialTag::kDielectric &&
        (scene.materials.dielectric.Flags(x.its.material.index()) & kDielectricScaleRadiance))
      weight = weight * (bs.eta * bs.eta);
  }
  w.beta = w.beta * weight;
  w.ratio = w.ratio * weight;
  w.eta *= w.light_subpath ? 1.0f : bs.eta;
  if (IsBlack(w.beta) || !IsFinite(w.beta)) return;
  float pdf_rev = 0.0f;
  if (bs.delta) {
    w.pdf_dir = 0.0f;
  } else {
    w.pdf_dir = bs.pdf;
    pdf_rev = BsdfPdf(scene.materials, x.its.material, bs.wi, wo, TextureSiteOf(scene, x.its));
  }
  prev.pdf_rev = ConvertDensity(pdf_rev, x, prev);
  w.ray = Ray{SpawnOrigin(x.its, wi), wi, 0.0f, kInfinity};
  ++w.bounce;
  w.active = true;  // n < max_vertices: checked above
}

}  // namespace ptlab::bdpt
