// Batched shading over SoA arrays (scalar oracle of simd/wavefront/bsdf8.h) and the partition by material.
#include "engine/wavefront/bsdf.h"

#include "engine/bsdf/beckmann.h"
#include "engine/bsdf/bsdf.h"
#include "engine/bsdf/fresnel.h"

namespace ptlab {

void ShadeBatch(const MaterialTables& m, MaterialTag tag, const uint32_t* material_index, size_t n,
                const ShadeInputs& in, const ShadeOutputs& out) {
  const bool eval = in.wl.x != nullptr;
  for (size_t i = 0; i < n; ++i) {
    const MaterialRef ref = MaterialRef::Make(tag, material_index[i]);
    const Vec3f wo{in.wo.x[i], in.wo.y[i], in.wo.z[i]};
    const TextureSite site = RowTextureSite(in.texture, i);
    if (eval) {
      const Vec3f wl{in.wl.x[i], in.wl.y[i], in.wl.z[i]};
      const Color3f f = BsdfEval(m, ref, wo, wl, site);
      out.f.r[i] = f.r, out.f.g[i] = f.g, out.f.b[i] = f.b;
      out.pdf_l[i] = BsdfPdf(m, ref, wo, wl, site);
    }
    if (in.u_lobe == nullptr) continue;  // evaluation only
    BsdfSample s;
    if (BsdfSampleDirection(m, ref, wo, in.u_lobe[i], {in.u_x[i], in.u_y[i]}, &s, site)) {
      out.wi.x[i] = s.wi.x, out.wi.y[i] = s.wi.y, out.wi.z[i] = s.wi.z;
      out.weight.r[i] = s.weight.r, out.weight.g[i] = s.weight.g, out.weight.b[i] = s.weight.b;
      out.pdf[i] = s.pdf;
      out.eta[i] = s.eta;
      if (out.delta != nullptr) out.delta[i] = s.delta ? 1.0f : 0.0f;
    } else {
      out.wi.x[i] = out.wi.y[i] = out.wi.z[i] = 0.0f;
      out.weight.r[i] = out.weight.g[i] = out.weight.b[i] = 0.0f;
      out.pdf[i] = 0.0f;
      out.eta[i] = 1.0f;
      if (out.delta != nullptr) out.delta[i] = 0.0f;
    }
  }
}

void PartitionByMaterial(const MaterialRef* refs, size_t n, MaterialPartition* out) {
  // The rows in two halves, counted and placed side by side: `++count[t]` and `next[t]++` are
  // load-add-store chains through memory whenever consecutive rows share a tag (the usual
  // case), and two independent halves halve their length. The tag is the ref's top 4 bits;
  // tags from kMaterialTagCount on (MaterialRef::None()) are counted and never placed.
  constexpr int kTagValues = 16;
  const auto tag = [refs](size_t i) { return refs[i].bits >> 28; };
  const size_t half = n / 2;
  uint32_t count_a[kTagValues] = {}, count_b[kTagValues] = {};
  for (size_t i = 0; i < half; ++i) ++count_a[tag(i)], ++count_b[tag(half + i)];
  if (n % 2 != 0) ++count_b[tag(n - 1)];
  uint32_t next_a[kTagValues], next_b[kTagValues];
  out->begin[0] = 0;
  for (int t = 0; t < kMaterialTagCount; ++t) {
    next_a[t] = out->begin[t], next_b[t] = out->begin[t] + count_a[t];
    out->begin[t + 1] = next_b[t] + count_b[t];
  }
  const size_t total = out->begin[kMaterialTagCount];
  out->slot.resize(total);
  out->index.resize(total);
  uint32_t* slot = out->slot.data();
  uint32_t* index = out->index.data();
  for (int t = 0; t < kMaterialTagCount; ++t) {
    if (count_a[t] + count_b[t] != n) continue;
    // One tag for every row: the group is the input itself, no cursor chain.
    for (size_t i = 0; i < n; ++i) slot[i] = uint32_t(i), index[i] = refs[i].index();
    return;
  }
  const auto place = [&](uint32_t* next, size_t i) {
    const uint32_t t = tag(i);
    if (t >= uint32_t(kMaterialTagCount)) return;
    const uint32_t k = next[t]++;
    slot[k] = uint32_t(i), index[k] = refs[i].index();
  };
  for (size_t i = 0; i < half; ++i) place(next_a, i), place(next_b, half + i);
  if (n % 2 != 0) place(next_b, n - 1);
}

void ShadeHits(const MaterialTables& m, const MaterialRef* refs, size_t n, const ShadeInputs& in,
               const ShadeOutputs& out, ShadeScratch* scratch) {
  ShadeHitsWith(
      [](const MaterialTables& mt, MaterialTag tag, const uint32_t* index, size_t count,
         const ShadeInputs& bin,
         const ShadeOutputs& bout) { ptlab::ShadeBatch(mt, tag, index, count, bin, bout); },
      m, refs, n, in, out, scratch);
}

void BeckmannEvalPdfBatch(const float* alpha, DirectionArrays wo, DirectionArrays wi, size_t n,
                          float* d, float* pdf) {
  for (size_t i = 0; i < n; ++i) {
    BeckmannEvalPdf(alpha[i], {wo.x[i], wo.y[i], wo.z[i]}, {wi.x[i], wi.y[i], wi.z[i]}, &d[i],
                    &pdf[i]);
  }
}

void SampleBeckmannReflectionBatch(const float* alpha, DirectionArrays wo, const float* u_x,
                                   const float* u_y, size_t n, DirectionOutArrays wi, float* pdf) {
  for (size_t i = 0; i < n; ++i) {
    const Vec3f o{wo.x[i], wo.y[i], wo.z[i]};
    Vec3f w = ReflectAbout(o, SampleBeckmannNormal(alpha[i], {u_x[i], u_y[i]}));
    float p = 0.0f;
    if (o.z > 0 && w.z > 0) p = BeckmannReflectionPdf(alpha[i], o, w);
    if (!(p > 0)) w = {0, 0, 0}, p = 0.0f;
    wi.x[i] = w.x, wi.y[i] = w.y, wi.z[i] = w.z;
    pdf[i] = p;
  }
}

void ConductorFresnelBatch(const float* cos_i, const float* eta, const float* k, size_t n,
                           float* f) {
  for (size_t i = 0; i < n; ++i) f[i] = FresnelConductor(cos_i[i], eta[i], k[i]);
}

void DielectricFresnelBatch(const float* cos_i, const float* eta, size_t n, float* f,
                            float* cos_t) {
  for (size_t i = 0; i < n; ++i) f[i] = FresnelDielectric(cos_i[i], eta[i], &cos_t[i]);
}

}  // namespace ptlab
