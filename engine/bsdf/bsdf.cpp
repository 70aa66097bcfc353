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
#include "engine/bsdf/rough_conductor.h"    // matA
#include "engine/bsdf/rough_dielectric.h"   // matA
#include "engine/bsdf/smooth_conductor.h"   // matA
#include "engine/bsdf/perturbed_frame.h"    // normal
#include "engine/bsdf/principled.h"         // principled
#include "engine/bsdf/principled_thin.h"    // principled
#include "engine/bsdf/mask.h"               // mask

namespace ptlab {
namespace {

ConductorParams ConductorRow(const ConductorTable& t, uint32_t i) {
  return {t.alpha[i], {t.eta_r[i], t.eta_g[i], t.eta_b[i]}, {t.k_r[i], t.k_g[i], t.k_b[i]}};
}

RoughPlasticParams RoughPlasticRow(const RoughPlasticTable& t, uint32_t i) {
  return MakeRoughPlasticParams(t.alpha[i], t.int_ior[i], t.ext_ior[i],
                                {t.kd_r[i], t.kd_g[i], t.kd_b[i]});
}

// matA: the conductor table's Mitsuba form and the rough dielectric.
RoughConductorParams RoughConductorRow(const ConductorTable& t, uint32_t i,
                                       const TextureSite& site) {
  RoughConductorParams p;
  const uint8_t f = t.flags[i];
  // mask: αu, αv may be textured (TexturedFloat).
  p.dist = MakeMicrofacet((f & kMicrofacetGgx) ? MicrofacetType::kGgx : MicrofacetType::kBeckmann,
                          TexturedFloat(t.alpha_texture, i, t.alpha[i], site),
                          TexturedFloat(t.alpha_v_texture, i, t.alpha_v[i], site),
                          (f & kMicrofacetSampleVisible) != 0);
  p.eta = {t.eta_r[i], t.eta_g[i], t.eta_b[i]};
  p.k = {t.k_r[i], t.k_g[i], t.k_b[i]};
  p.specular = {t.specular_r[i], t.specular_g[i], t.specular_b[i]};
  return p;
}

RoughDielectricParams RoughDielectricRow(const RoughDielectricTable& t, uint32_t i,
                                         const TextureSite& site) {
  RoughDielectricParams p;
  const uint8_t f = t.flags[i];
  // αu, αv may be textured (TexturedFloat), as the rough conductor's.
  p.dist = MakeMicrofacet((f & kMicrofacetGgx) ? MicrofacetType::kGgx : MicrofacetType::kBeckmann,
                          TexturedFloat(t.alpha_texture, i, t.alpha_u[i], site),
                          TexturedFloat(t.alpha_v_texture, i, t.alpha_v[i], site),
                          (f & kMicrofacetSampleVisible) != 0);
  p.eta = t.int_ior[i] / t.ext_ior[i];
  p.reflectance = {t.reflectance_r[i], t.reflectance_g[i], t.reflectance_b[i]};
  p.transmittance = {t.transmittance_r[i], t.transmittance_g[i], t.transmittance_b[i]};
  return p;
}

}  // namespace

Color3f BsdfEval(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
                 const TextureSite& site) {
  if (PerturbsFrame(m, ref, site)) return PerturbedBsdfEval(m, ref, wo, wi, site);  // normal
  if (TwoSidedFlips(m, ref, wo)) return BsdfEval(m, ref, FlipZ(wo), FlipZ(wi), site);
  switch (ref.tag()) {
    case MaterialTag::kDiffuse:
      return DiffuseEval(DiffuseAlbedo(m.diffuse, ref.index(), site), wo, wi);
    case MaterialTag::kConductor:
      if (m.conductor.microfacet())
        return RoughConductorEval(RoughConductorRow(m.conductor, ref.index(), site), wo, wi);
      return ConductorEval(ConductorRow(m.conductor, ref.index()), wo, wi);
    case MaterialTag::kRoughDielectric:  // matA
      return RoughDielectricEval(RoughDielectricRow(m.rough_dielectric, ref.index(), site), wo, wi);
    case MaterialTag::kRoughPlastic:
      return RoughPlasticEval(RoughPlasticRow(m.rough_plastic, ref.index()), wo, wi);
    // matB
    case MaterialTag::kPlastic: {
      float pdf;
      return PlasticRowEvalPdf(m.plastic, ref.index(), wo, wi, &pdf);
    }
    case MaterialTag::kBlend:
      return BlendEval(m, ref.index(), wo, wi, site);
    case MaterialTag::kPrincipled:  // principled
      return PrincipledEval(PrincipledAt(m.principled, ref.index(), site), wo, wi);
    case MaterialTag::kPrincipledThin:
      return PrincipledThinEval(PrincipledAt(m.principled_thin, ref.index(), site), wo, wi);
    case MaterialTag::kMask:  // mask
      return MaskEval(m, ref.index(), wo, wi, site);
    case MaterialTag::kThinDielectric:
    case MaterialTag::kMirror:
    case MaterialTag::kDielectric:
      return {};  // delta models
  }
  return {};  // an invalid ref
}

float BsdfPdf(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
              const TextureSite& site) {
  if (PerturbsFrame(m, ref, site)) return PerturbedBsdfPdf(m, ref, wo, wi, site);  // normal
  if (TwoSidedFlips(m, ref, wo)) return BsdfPdf(m, ref, FlipZ(wo), FlipZ(wi), site);
  switch (ref.tag()) {
    case MaterialTag::kDiffuse:
      return DiffusePdf(wo, wi);
    case MaterialTag::kConductor:
      if (m.conductor.microfacet())
        return RoughConductorPdf(RoughConductorRow(m.conductor, ref.index(), site), wo, wi);
      return ConductorPdf(ConductorRow(m.conductor, ref.index()), wo, wi);
    case MaterialTag::kRoughDielectric:  // matA
      return RoughDielectricPdf(RoughDielectricRow(m.rough_dielectric, ref.index(), site), wo, wi);
    case MaterialTag::kRoughPlastic:
      return RoughPlasticPdf(RoughPlasticRow(m.rough_plastic, ref.index()), wo, wi);
    // matB
    case MaterialTag::kPlastic: {
      float pdf;
      PlasticRowEvalPdf(m.plastic, ref.index(), wo, wi, &pdf);
      return pdf;
    }
    case MaterialTag::kBlend:
      return BlendPdf(m, ref.index(), wo, wi, site);
    case MaterialTag::kPrincipled:  // principled: the textured parameters change the pdf
      return PrincipledPdf(PrincipledAt(m.principled, ref.index(), site), wo, wi);
    case MaterialTag::kPrincipledThin:
      return PrincipledThinPdf(PrincipledAt(m.principled_thin, ref.index(), site), wo, wi);
    case MaterialTag::kMask:  // mask
      return MaskPdf(m, ref.index(), wo, wi, site);
    case MaterialTag::kThinDielectric:
    case MaterialTag::kMirror:
    case MaterialTag::kDielectric:
      return 0.0f;  // delta models
  }
  return 0.0f;  // an invalid ref
}

Color3f BsdfEvalPdf(const MaterialTables& m, MaterialRef ref, const Vec3f& wo, const Vec3f& wi,
                    float* pdf, const TextureSite& site) {
  if (PerturbsFrame(m, ref, site)) return PerturbedBsdfEvalPdf(m, ref, wo, wi, pdf, site);  // normal
  if (TwoSidedFlips(m, ref, wo)) return BsdfEvalPdf(m, ref, FlipZ(wo), FlipZ(wi), pdf, site);
  switch (ref.tag()) {
    case MaterialTag::kDiffuse:
      *pdf = DiffusePdf(wo, wi);
      return DiffuseEval(DiffuseAlbedo(m.diffuse, ref.index(), site), wo, wi);
    case MaterialTag::kConductor: {
      if (m.conductor.microfacet()) {
        const RoughConductorParams p = RoughConductorRow(m.conductor, ref.index(), site);
        *pdf = RoughConductorPdf(p, wo, wi);
        return RoughConductorEval(p, wo, wi);
      }
      const ConductorParams p = ConductorRow(m.conductor, ref.index());
      *pdf = ConductorPdf(p, wo, wi);
      return ConductorEval(p, wo, wi);
    }
    case MaterialTag::kRoughPlastic:
      return RoughPlasticEvalPdf(RoughPlasticRow(m.rough_plastic, ref.index()), wo, wi, pdf);
    case MaterialTag::kRoughDielectric: {  // matA
      const RoughDielectricParams p = RoughDielectricRow(m.rough_dielectric, ref.index(), site);
      *pdf = RoughDielectricPdf(p, wo, wi);
      return RoughDielectricEval(p, wo, wi);
    }
    // matB
    case MaterialTag::kPlastic:
      return PlasticRowEvalPdf(m.plastic, ref.index(), wo, wi, pdf);
    case MaterialTag::kBlend:
      return BlendEvalPdf(m, ref.index(), wo, wi, pdf, site);
    case MaterialTag::kPrincipled:  // principled
      return PrincipledEvalPdf(PrincipledAt(m.principled, ref.index(), site), wo, wi, pdf);
    case MaterialTag::kPrincipledThin:
      return PrincipledThinEvalPdf(PrincipledAt(m.principled_thin, ref.index(), site), wo, wi,
                                   pdf);
    case MaterialTag::kMask:  // mask
      return MaskEvalPdf(m, ref.index(), wo, wi, pdf, site);
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
  if (PerturbsFrame(m, ref, site))  // normal
    return PerturbedBsdfSample(m, ref, wo, u1, u2, sample, site);
  if (TwoSidedFlips(m, ref, wo)) {
    if (!BsdfSampleDirection(m, ref, FlipZ(wo), u1, u2, sample, site)) return false;
    sample->wi = FlipZ(sample->wi);
    return true;
  }
  switch (ref.tag()) {
    case MaterialTag::kDiffuse:
      return DiffuseSample(DiffuseAlbedo(m.diffuse, ref.index(), site), wo, u2, sample);
    case MaterialTag::kMirror:
      if (m.mirror.fresnel())  // matA: Mitsuba's smooth conductor
        return SmoothConductorSample(m.mirror.Reflectance(ref.index()), m.mirror.Eta(ref.index()),
                                     m.mirror.K(ref.index()), wo, sample);
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
      if (m.conductor.microfacet())
        return RoughConductorSample(RoughConductorRow(m.conductor, ref.index(), site), wo, u2, sample);
      return ConductorSample(ConductorRow(m.conductor, ref.index()), wo, u2, sample);
    case MaterialTag::kRoughDielectric:  // matA
      return RoughDielectricSample(RoughDielectricRow(m.rough_dielectric, ref.index(), site), wo,
                                   u1, u2, sample);
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
      return BlendSample(m, ref.index(), wo, u1, u2, sample, site);
    case MaterialTag::kPrincipled:  // principled
      return PrincipledSample(PrincipledAt(m.principled, ref.index(), site), wo, u1, u2, sample);
    case MaterialTag::kPrincipledThin:
      return PrincipledThinSample(PrincipledAt(m.principled_thin, ref.index(), site), wo, u1, u2,
                                  sample);
    case MaterialTag::kMask:  // mask
      return MaskSample(m, ref.index(), wo, u1, u2, sample, site);
  }
  return false;
}

}  // namespace ptlab
