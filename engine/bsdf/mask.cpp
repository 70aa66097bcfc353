// Mitsuba `mask`: a nested material seen with probability `opacity`, else passed through.
#include "engine/bsdf/mask.h"

#include "engine/bsdf/bsdf.h"

namespace ptlab {

Color3f MaskEval(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
                 const TextureSite& site) {
  const float opacity = MaskOpacity(m.mask, row, site);
  return BsdfEval(m, m.mask.Nested(row), wo, wi, site) * opacity;
}

float MaskPdf(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
              const TextureSite& site) {
  return BsdfPdf(m, m.mask.Nested(row), wo, wi, site) * MaskOpacity(m.mask, row, site);
}

Color3f MaskEvalPdf(const MaterialTables& m, uint32_t row, const Vec3f& wo, const Vec3f& wi,
                    float* pdf, const TextureSite& site) {
  const float opacity = MaskOpacity(m.mask, row, site);
  float p = 0.0f;
  const Color3f f = BsdfEvalPdf(m, m.mask.Nested(row), wo, wi, &p, site);
  *pdf = p * opacity;
  return f * opacity;
}

bool MaskSample(const MaterialTables& m, uint32_t row, const Vec3f& wo, float u_lobe,
                const Vec2f& u, BsdfSample* s, const TextureSite& site) {
  const float opacity = MaskOpacity(m.mask, row, site);
  float u_nested = 0.0f;
  if (MaskPicksNested(opacity, u_lobe, &u_nested)) {
    if (!BsdfSampleDirection(m, m.mask.Nested(row), wo, u_nested, u, s, site)) return false;
    s->pdf *= opacity;
    return s->pdf > 0;
  }
  s->wi = -wo;
  s->weight = {1, 1, 1};
  s->pdf = 1.0f - opacity;
  s->delta = true;
  s->eta = 1.0f;
  return true;
}

}  // namespace ptlab
