// Chi-square subjects of the normalmap / bumpmap wrappers (see perturbed_subjects.h).
#include "tools/chi2/perturbed_subjects.h"

#include <cstdio>
#include <memory>
#include <string>

#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/conductor_presets.h"
#include "engine/core/frame.h"
#include "engine/scene/material_tables.h"
#include "engine/scene/texture_tables.h"
#include "engine/texture/texture_site.h"
#include "tools/chi2/bsdf_subjects.h"

namespace ptlab {
namespace {

// One perturbed row over scene triangle 0, with the site its wrapper reads; the lambdas of a
// subject share it.
struct PerturbedScene {
  MaterialTables m;
  TextureTable textures;
  Frame frame;  // the shading frame, world = local
  Vec3f ng{0, 0, 1};
  MaterialRef row;
  TextureSite Site() const {
    TextureSite s;
    s.textures = &textures;
    s.at.uv = {0.5f, 0.5f}, s.at.prim = 0;
    s.frame = &frame, s.ng = &ng;
    return s;
  }
};

enum class Kind { kNormalDiffuse, kNormalConductor, kBumpDiffuse };

std::shared_ptr<PerturbedScene> MakeScene(Kind kind) {
  auto s = std::make_shared<PerturbedScene>();
  ShadingPerturbations& p = s->m.perturbation;
  p.dp_du_x = {0.8f}, p.dp_du_y = {0.6f}, p.dp_du_z = {0.1f};
  p.dp_dv_x = {-0.6f}, p.dp_dv_y = {0.8f}, p.dp_dv_z = {0.0f};
  if (kind == Kind::kNormalConductor) {
    Color3f eta, k;
    LookupConductorPreset("Al", &eta, &k);
    s->row = s->m.AddRoughConductor(0.25f, 0.1f, kMicrofacetGgx | kMicrofacetSampleVisible, eta,
                                    k, {1, 1, 1});
  } else {
    s->row = s->m.AddDiffuse({0.5f, 0.5f, 0.5f});
  }
  if (kind == Kind::kBumpDiffuse) {
    const uint32_t ramp = s->textures.AddRow(TextureKind::kBitmap, 2, 1, 6);
    for (int c = 0; c < 3; ++c) s->textures.data[s->textures.offset[ramp] + 3 + c] = 1.0f;
    s->textures.wrap[ramp] = uint8_t(TextureWrap::kClamp);
    p.Add(s->row, PerturbationKind::kBumpMap, ramp, 0.4f);
  } else {
    const uint32_t tilt = s->textures.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
    float* d = &s->textures.data[s->textures.offset[tilt]];
    d[0] = d[3] = 0.85f, d[1] = d[4] = 0.35f, d[2] = d[5] = 0.8f;
    p.Add(s->row, PerturbationKind::kNormalMap, tilt, 1.0f);
  }
  return s;
}

Chi2Subject Subject(Kind kind, float theta_deg) {
  const char* stem = kind == Kind::kNormalDiffuse     ? "bsdf/normalmap_diffuse"
                     : kind == Kind::kNormalConductor ? "bsdf/normalmap_ggx_conductor"
                                                      : "bsdf/bumpmap_diffuse";
  char name[96], params[96];
  std::snprintf(name, sizeof(name), "%s_t%g", stem, double(theta_deg));
  std::snprintf(params, sizeof(params), "theta_o=%g phi_o=140", double(theta_deg));
  const std::shared_ptr<const PerturbedScene> s = MakeScene(kind);
  const Vec3f wo = Chi2Direction(theta_deg, 140);
  Chi2Subject subject;
  subject.name = name;
  subject.params = params;
  subject.domain = Chi2Domain::Hemisphere();
  subject.albedo = kChi2UnknownAlbedo;
  subject.uniform_dims = 3;
  // At 20° the tilted conductor's lobe falls mostly beyond the side rule (mass 0.18): four times
  // the samples keep the power to catch a 2 % error of the pdf ≥ 95 % (the lab's target).
  if (kind == Kind::kNormalConductor) subject.sample_scale = 4;
  subject.pdf = [s, wo](const Chi2Point& wi) {
    return double(BsdfPdf(s->m, s->row, wo, wi, s->Site()));
  };
  subject.sample = [s, wo](float u1, const Vec2f& u, Chi2Point* p) {
    BsdfSample bs;
    if (!BsdfSampleDirection(s->m, s->row, wo, u1, u, &bs, s->Site()) || bs.delta) return false;
    *p = bs.wi;
    return true;
  };
  return subject;
}

}  // namespace

void RegisterPerturbedBsdfSubjects(Chi2Registry* r) {
  for (Kind kind : {Kind::kNormalDiffuse, Kind::kNormalConductor, Kind::kBumpDiffuse})
    for (float theta : {20.0f, 70.0f}) r->Add(Subject(kind, theta));
}

}  // namespace ptlab
