// BSDF dispatch over the closed set of material models: one switch on the MaterialRef tag.
#include "engine/bsdf/bsdf.h"

#include "engine/bsdf/conductor.h"
#include "engine/bsdf/dielectric.h"
#include "engine/bsdf/diffuse.h"
#include "engine/bsdf/mirror.h"
#include "engine/bsdf/rough_plastic.h"
// matB
#include "engine/bsdf/blend.h"
#include "engine/bsdf/plastic.h"
#include "engine/bsdf/plastic_rough.h"
#include "engine/bsdf/thin_dielectric.h"
#include "engine/bsdf/two_sided.h"

namespace ptlab {
namespace {

ConductorParams ConductorRow(const ConductorTable& t, uint32_t i) {
  return {t.alpha[i], {t.eta_r[i], t.eta_g[i], t.eta_b[i]}, {t.k_r[i], t.k_g[i], t.k_b[i]}};
}

RoughPlasticParams RoughPlasticRow(const RoughPlasticTable& t, uint32_t i) {
  return MakeRoughPlasticParams(t.alpha[i], t.int_ior[i], t.ext_ior[i],
                                {t.kd_r[i], t.kd_g[i], t.kd_b[i]});
}

}  // namespace

Color3f BsdfEval(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
                 const TextureSite& site) {
  if (TwoSidedFlips(m, ref, wo)) return BsdfEval(m, ref, FlipZ(wo), FlipZ(wi), site);
  switch (ref.tag()) {
    case MaterialTag::kDiffuse:
      return DiffuseEval(DiffuseAlbedo(m.diffuse, ref.index(), site), wo, wi);
    case MaterialTag::kConductor:
      return ConductorEval(ConductorRow(m.conductor, ref.index()), wo, wi);
    case MaterialTag::kRoughPlastic:
      return RoughPlasticEval(RoughPlasticRow(m.rough_plastic, ref.index()), wo, wi);
    // matB
    case MaterialTag::kPlastic: {
      float pdf;
      return PlasticRowEvalPdf(m.plastic, ref.index(), wo, wi, &pdf);
    }
    case MaterialTag::kBlend:
      return BlendEval(m, ref.index(), wo, wi);
    case MaterialTag::kThinDielectric:
    case MaterialTag::kMirror:
    case MaterialTag::kDielectric:
      return {};  // delta models
  }
  return {};  // an invalid ref
}

float BsdfPdf(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
              const TextureSite& site) {
  if (TwoSidedFlips(m, ref, wo)) return BsdfPdf(m, ref, FlipZ(wo), FlipZ(wi), site);
  (void)site;  // no textured parameter changes a pdf yet
  switch (ref.tag()) {
    case MaterialTag::kDiffuse:
      return DiffusePdf(wo, wi);
    case MaterialTag::kConductor:
      return ConductorPdf(ConductorRow(m.conductor, ref.index()), wo, wi);
    case MaterialTag::kRoughPlastic:
      return RoughPlasticPdf(RoughPlasticRow(m.rough_plastic, ref.index()), wo, wi);
    // matB
    case MaterialTag::kPlastic: {
      float pdf;
      PlasticRowEvalPdf(m.plastic, ref.index(), wo, wi, &pdf);
      return pdf;
    }
    case MaterialTag::kBlend:
      return BlendPdf(m, ref.index(), wo, wi);
    case MaterialTag::kThinDielectric:
    case MaterialTag::kMirror:
    case MaterialTag::kDielectric:
      return 0.0f;  // delta models
  }
  return 0.0f;  // an invalid ref
}

Color3f BsdfEvalPdf(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
                    float* pdf, const TextureSite& site) {
  if (TwoSidedFlips(m, ref, wo)) return BsdfEvalPdf(m, ref, FlipZ(wo), FlipZ(wi), pdf, site);
  switch (ref.tag()) {
    case MaterialTag::kDiffuse:
      *pdf = DiffusePdf(wo, wi);
      return DiffuseEval(DiffuseAlbedo(m.diffuse, ref.index(), site), wo, wi);
    case MaterialTag::kConductor: {
      const ConductorParams p = ConductorRow(m.conductor, ref.index());
      *pdf = ConductorPdf(p, wo, wi);
      return ConductorEval(p, wo, wi);
    }
    case MaterialTag::kRoughPlastic:
      return RoughPlasticEvalPdf(RoughPlasticRow(m.rough_plastic, ref.index()), wo, wi, pdf);
    // matB
    case MaterialTag::kPlastic:
      return PlasticRowEvalPdf(m.plastic, ref.index(), wo, wi, pdf);
    case MaterialTag::kBlend:
      return BlendEvalPdf(m, ref.index(), wo, wi, pdf);
    case MaterialTag::kThinDielectric:
    case MaterialTag::kMirror:
    case MaterialTag::kDielectric:
      break;  // delta models
  }
  *pdf = 0.0f;  // a delta model or an invalid ref
  return {};
}

bool BsdfSampleDirection(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, float u1,
                         const Vec2f& u2, BsdfSample* sample, const TextureSite& site) {
  if (TwoSidedFlips(m, ref, wo)) {
    if (!BsdfSampleDirection(m, ref, FlipZ(wo), u1, u2, sample, site)) return false;
    sample->wi = FlipZ(sample->wi);
    return true;
  }
  switch (ref.tag()) {
    case MaterialTag::kDiffuse:
      return DiffuseSample(DiffuseAlbedo(m.diffuse, ref.index(), site), wo, u2, sample);
    case MaterialTag::kMirror:
      return MirrorSample(m.mirror.Reflectance(ref.index()), wo, sample);
    case MaterialTag::kDielectric: {
      const uint32_t i = ref.index();
      const float eta = m.dielectric.int_ior[i] / m.dielectric.ext_ior[i];
      if (!DielectricSample(eta, wo, u1, sample, m.dielectric.Flags(i))) return false;
      if (m.dielectric.tinted())
        // Reflection keeps the side of wo (wi.z wo.z >= 0); refraction changes it (< 0).
        sample->weight *= sample->wi.z * wo.z >= 0 ? m.dielectric.Reflectance(i)
                                                 : m.dielectric.Transmittance(i);
      return true;
    }
    case MaterialTag::kConductor:
      return ConductorSample(ConductorRow(m.conductor, ref.index()), wo, u2, sample);
    case MaterialTag::kRoughPlastic:
      return RoughPlasticSample(RoughPlasticRow(m.rough_plastic, ref.index()), wo, u1, u2, sample);
    // matB
    case MaterialTag::kPlastic:
      return PlasticRowSample(m.plastic, ref.index(), wo, u1, u2, sample);
    case MaterialTag::kThinDielectric: {
      const ThinDielectricTable& t = m.thin_dielectric;
      const uint32_t i = ref.index();
      return ThinDielectricSample(t.eta[i], t.Reflectance(i), t.Transmittance(i), wo, u1, sample);
    }
    case MaterialTag::kBlend:
      return BlendSample(m, ref.index(), wo, u1, u2, sample);
  }
  return false;
}

}  // namespace ptlab
