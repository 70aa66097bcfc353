// Batched shading over SoA arrays (scalar oracle of simd/wavefront/bsdf8.h) and the partition by material.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/core/memory.h"
#include "engine/render/interaction.h"
#include "engine/scene/material_tables.h"

namespace ptlab {

// All directions are unit vectors in the local shading frame (z = normal), wo towards the
// viewer, wi / wl towards the light. Arrays hold n entries; outputs may not alias inputs.

/// Read-only SoA view of n directions.
struct DirectionArrays {
  const float* x = nullptr;
  const float* y = nullptr;
  const float* z = nullptr;
};
/// Writable SoA view of n directions.
struct DirectionOutArrays {
  float* x = nullptr;
  float* y = nullptr;
  float* z = nullptr;
};
/// Writable SoA view of n RGB values.
struct ColorOutArrays {
  float* r = nullptr;
  float* g = nullptr;
  float* b = nullptr;
};

/// What one shading step reads per hit.
struct ShadeInputs {
  DirectionArrays wo;  // towards the viewer
  DirectionArrays wl;  // towards a light sample: f and pdf are evaluated for (wo, wl);
                       // wl.x == nullptr skips the evaluation (f and pdf_l are not written)
  const float* u_lobe = nullptr;  // BsdfSampleDirection's u1 (lobe / reflect-or-refract choice);
                                  // u_lobe == nullptr skips the sample (u_x, u_y are not read,
                                  // wi, weight, pdf and eta not written): evaluation only
  const float* u_x = nullptr;     // BsdfSampleDirection's u2.x
  const float* u_y = nullptr;     // BsdfSampleDirection's u2.y
  /// The shading points of the rows, for textured parameters (engine/texture/texture_site.h):
  /// row i's is its[entry[i]] (TextureSiteOf). textures == nullptr in a scene without textures:
  /// then `its` and `entry` are not read.
  struct Textures {
    const TextureTable* textures = nullptr;
    const SurfaceInteraction* its = nullptr;
    const uint32_t* entry = nullptr;
  } texture;
};

/// The texture site of row i of a shading step (empty without textures).
inline TextureSite RowTextureSite(const ShadeInputs::Textures& t, size_t i) {
  if (t.textures == nullptr) return {};
  const SurfaceInteraction& its = t.its[t.entry[i]];
  return {t.textures, {its.uv, its.p, its.prim}, &its.frame, &its.ng};
}

/// What one shading step writes per hit.
struct ShadeOutputs {
  ColorOutArrays f;        // BsdfEval(wo, wl)
  float* pdf_l = nullptr;  // BsdfPdf(wo, wl)
  DirectionOutArrays wi;   // sampled direction (0 when there is no sample)
  ColorOutArrays weight;   // sample weight f |cos θi| / pdf (0 when there is no sample)
  float* pdf = nullptr;    // sample pdf; 0 means "no sample" (BsdfSampleDirection false)
  float* eta = nullptr;    // relative IOR crossed by the sample (1 unless refracted)
  // matB: 1 where the sample took a Dirac-delta lobe (BsdfSample::delta), else 0; written with
  // the sample when non-null (the wavefront reads it for tags that MixesDeltaLobes).
  float* delta = nullptr;
};

/// One shading step for n hits that all have material tag `tag`; row i uses table row
/// material_index[i]. The scalar oracle of simd::ShadeBatch: per row, BsdfEval, BsdfPdf and
/// BsdfSampleDirection (engine/bsdf/bsdf.h). Whether a sample is a delta lobe follows from
/// the tag (IsDeltaMaterial), except for tags that MixesDeltaLobes: out.delta says it per row.
void ShadeBatch(const MaterialTables& m, MaterialTag tag, const uint32_t* material_index, size_t n,
                const ShadeInputs& in, const ShadeOutputs& out);

/// Hits grouped by material tag with a counting sort. Positions begin[t] .. begin[t + 1] of
/// `slot` and `index` describe the hits with tag t, in their input order: slot = position in
/// the input, index = row in that tag's table. Invalid refs (MaterialRef::None()) belong to
/// no group. Storage is reused across calls.
struct MaterialPartition {
  uint32_t begin[kMaterialTagCount + 1] = {};
  AlignedVector<uint32_t> slot;
  AlignedVector<uint32_t> index;
  size_t Count(MaterialTag t) const {
    return begin[static_cast<int>(t) + 1] - begin[static_cast<int>(t)];
  }
};
void PartitionByMaterial(const MaterialRef* refs, size_t n, MaterialPartition* out);

/// Reusable contiguous per-material copies of the inputs and outputs of ShadeHits.
struct ShadeScratch {
  MaterialPartition partition;
  AlignedVector<float> in[9];    // wo xyz, wl xyz, u_lobe, u_x, u_y
  AlignedVector<float> out[12];  // f rgb, pdf_l, wi xyz, weight rgb, pdf, eta
  AlignedVector<uint32_t> texture_entry;  // in.texture.entry per group row (textures only)
  AlignedVector<float> delta;    // matB: ShadeOutputs::delta
};

/// Heap bytes of the scratch: capacity × element size of every array.
inline size_t ShadeScratchBytes(const ShadeScratch& s) {
  size_t bytes = VectorsBytes(s.partition.slot, s.partition.index, s.texture_entry);
  for (const auto& v : s.in) bytes += VectorBytes(v);
  for (const auto& v : s.out) bytes += VectorBytes(v);
  bytes += VectorBytes(s.delta);
  return bytes;
}

/// The shading stage for n hits with arbitrary materials: partition by tag, copy each group's
/// inputs into contiguous arrays, run `batch` (ShadeBatch or simd::ShadeBatch) once per tag
/// present, scatter the results back (when all n hits have one tag, `batch` runs on the arrays
/// themselves). Tags with no hits cost nothing. Rows with an invalid ref
/// get f = 0, pdf_l = 0, wi = 0, weight = 0, pdf = 0 and eta = 1.
template <class BatchFn>
void ShadeHitsWith(BatchFn&& batch, const MaterialTables& m, const MaterialRef* refs, size_t n,
                   const ShadeInputs& in, const ShadeOutputs& out, ShadeScratch* scratch);

/// ShadeHitsWith the scalar ShadeBatch.
void ShadeHits(const MaterialTables& m, const MaterialRef* refs, size_t n, const ShadeInputs& in,
               const ShadeOutputs& out, ShadeScratch* scratch);

// Scalar twins of the kernel benchmarks/tests in simd/wavefront/bsdf8.h (loops over beckmann.h and
// fresnel.h).

/// d[i], pdf[i] = BeckmannEvalPdf(alpha[i], wo_i, wi_i).
void BeckmannEvalPdfBatch(const float* alpha, DirectionArrays wo, DirectionArrays wi, size_t n,
                          float* d, float* pdf);
/// wi = reflect(wo, SampleBeckmannNormal(alpha, (u_x, u_y))), pdf = BeckmannReflectionPdf;
/// wi = 0 and pdf = 0 when wo or wi is not above the surface.
void SampleBeckmannReflectionBatch(const float* alpha, DirectionArrays wo, const float* u_x,
                                   const float* u_y, size_t n, DirectionOutArrays wi, float* pdf);
/// f[i] = FresnelConductor(cos_i[i], eta[i], k[i]) (one channel).
void ConductorFresnelBatch(const float* cos_i, const float* eta, const float* k, size_t n,
                           float* f);
/// f[i] = FresnelDielectric(cos_i[i], eta[i], &cos_t[i]).
void DielectricFresnelBatch(const float* cos_i, const float* eta, size_t n, float* f, float* cos_t);

// ---------------------------------------------------------------------------------------------

template <class BatchFn>
void ShadeHitsWith(BatchFn&& batch, const MaterialTables& m, const MaterialRef* refs, size_t n,
                   const ShadeInputs& in, const ShadeOutputs& out, ShadeScratch* scratch) {
  const bool eval = in.wl.x != nullptr, sample = in.u_lobe != nullptr;
  MaterialPartition& part = scratch->partition;
  PartitionByMaterial(refs, n, &part);
  // Rows that belong to no group.
  if (part.begin[kMaterialTagCount] != n) {
    for (size_t i = 0; i < n; ++i) {
      if (static_cast<int>(refs[i].tag()) < kMaterialTagCount) continue;
      if (eval) out.f.r[i] = out.f.g[i] = out.f.b[i] = out.pdf_l[i] = 0.0f;
      if (!sample) continue;
      out.wi.x[i] = out.wi.y[i] = out.wi.z[i] = 0.0f;
      out.weight.r[i] = out.weight.g[i] = out.weight.b[i] = out.pdf[i] = 0.0f;
      out.eta[i] = 1.0f;
      if (out.delta != nullptr) out.delta[i] = 0.0f;
    }
  }
  // One tag for every row: the rows are already that tag's contiguous batch, in input order.
  for (int t = 0; t < kMaterialTagCount; ++t) {
    if (n == 0 || part.begin[t + 1] - part.begin[t] != n) continue;
    batch(m, static_cast<MaterialTag>(t), part.index.data(), n, in, out);
    return;
  }
  const float* src_in[9] = {in.wo.x, in.wo.y,   in.wo.z, in.wl.x, in.wl.y,
                            in.wl.z, in.u_lobe, in.u_x,  in.u_y};
  float* dst_out[12] = {out.f.r,  out.f.g,      out.f.b,      out.pdf_l,    out.wi.x, out.wi.y,
                        out.wi.z, out.weight.r, out.weight.g, out.weight.b, out.pdf,  out.eta};
  for (int t = 0; t < kMaterialTagCount; ++t) {
    const size_t begin = part.begin[t], count = part.begin[t + 1] - begin;
    if (count == 0) continue;
    const uint32_t* slot = part.slot.data() + begin;
    float* tin[9];
    for (int c = 0; c < 9; ++c) {
      tin[c] = nullptr;
      if (src_in[c] == nullptr) continue;
      if (scratch->in[c].size() < count) scratch->in[c].resize(count);
      tin[c] = scratch->in[c].data();
      for (size_t j = 0; j < count; ++j) tin[c][j] = src_in[c][slot[j]];
    }
    float* tout[12];
    for (int c = 0; c < 12; ++c) {
      if (scratch->out[c].size() < count) scratch->out[c].resize(count);
      tout[c] = scratch->out[c].data();
    }
    ShadeInputs bin;
    bin.texture = in.texture;
    if (in.texture.textures != nullptr) {
      if (scratch->texture_entry.size() < count) scratch->texture_entry.resize(count);
      for (size_t j = 0; j < count; ++j) scratch->texture_entry[j] = in.texture.entry[slot[j]];
      bin.texture.entry = scratch->texture_entry.data();
    }
    bin.wo = {tin[0], tin[1], tin[2]};
    bin.wl = {tin[3], tin[4], tin[5]};
    bin.u_lobe = tin[6], bin.u_x = tin[7], bin.u_y = tin[8];
    ShadeOutputs bout;
    bout.f = {tout[0], tout[1], tout[2]};
    bout.pdf_l = tout[3];
    bout.wi = {tout[4], tout[5], tout[6]};
    bout.weight = {tout[7], tout[8], tout[9]};
    bout.pdf = tout[10];
    bout.eta = tout[11];
    if (sample && out.delta != nullptr) {
      if (scratch->delta.size() < count) scratch->delta.resize(count);
      bout.delta = scratch->delta.data();
    }
    batch(m, static_cast<MaterialTag>(t), part.index.data() + begin, count, bin, bout);
    for (int c = eval ? 0 : 4; c < (sample ? 12 : 4); ++c)
      for (size_t j = 0; j < count; ++j) dst_out[c][slot[j]] = tout[c][j];
    if (bout.delta != nullptr)
      for (size_t j = 0; j < count; ++j) out.delta[slot[j]] = bout.delta[j];
  }
}

}  // namespace ptlab
