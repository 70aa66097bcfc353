// Wavefront stage: BSDF sampling, path continuation and the next rays (the bsdf, continuation
// and spawn slots).
#include "engine/wavefront/wave.h"

namespace ptlab {

// The BSDF stage: the kernel table's bsdf slot over the columns, one call per material tag
// on its group of slots (Sample pushed the rows there; the rows of ShadeHitsWith's batches,
// without its counting sort, gather and scatter); then each sampled path's throughput and
// state, as the scalar integrators do (the continuation slot, one call per tag), and the
// next rays of those that go on as one batch of the spawn slot.
void Wavefront::SampleBsdfs() {
  BsdfColumns& b = bsdf_;
  const size_t n = b.size();
  if (n == 0) return;
  for (int t = 0; t < kMaterialTagCount; ++t) {
    const size_t begin = b.begin[t], count = b.next[t] - begin;
    if (count == 0) continue;
    const BsdfColumns::Pointers c = b.At(begin);
    ShadeInputs in;
    in.wo = {c.wo_x, c.wo_y, c.wo_z};
    in.u_lobe = c.u_lobe, in.u_x = c.u_x;
    in.u_y = c.u_y;
    if (!scene_->textures.empty()) in.texture = {&scene_->textures, its_.data(), c.entry};
    ShadeOutputs out;
    out.wi = {c.wi_x, c.wi_y, c.wi_z};
    out.weight = {c.weight_r, c.weight_g, c.weight_b};
    out.pdf = c.pdf, out.eta = c.eta;
    if (MixesDeltaLobes(static_cast<MaterialTag>(t))) out.delta = c.delta;
    kernels_->bsdf(scene_->materials, static_cast<MaterialTag>(t), c.material_index, count, in,
                   out);
  }
  // Group by group, each in queue order, each sampled path's throughput and state, as the
  // scalar integrators do, through the kernel table's continuation slot, one call per tag; a
  // path that goes on gets the next row of the spawn stage and the next entry of the queue.
  // So the next queue holds the paths of each material tag together (the order changes no
  // result: each path's numbers and state are its own), and the slot reads the columns in
  // their order instead of in queue order through an index. Rows of no material (no group of
  // ShadeHitsWith) sample nothing.
  SpawnColumns& sp = spawn_;
  sp.Clear(n);
  next_rays_.owner.resize(n);
  ContinueBatchOutputs out{sp.entry.data(), sp.wi_x.data(), sp.wi_y.data(), sp.wi_z.data(),
                           next_rays_.owner.data()};
  const ContinueBatchPaths paths{throughput_.data(), eta_.data(), specular_.data(),
                                 prev_pdf_.data(), prev_p_.data()};
  const bool whitted = rules_.roulette == VertexRules::Roulette::kWhitted;
  for (int t = 0; t < kMaterialTagCount; ++t) {
    const size_t begin = b.begin[t], count = b.next[t] - begin;
    if (count == 0) continue;
    const BsdfColumns::Pointers c = b.At(begin);
    const ContinueBatchRules rules{IsDeltaMaterial(static_cast<MaterialTag>(t)), rules_.cut_black};
    ContinueBatchInputs in{
        c.path, c.entry, c.weight_r, c.weight_g, c.weight_b, whitted ? c.roulette_scale : nullptr,
        c.pdf,  c.eta,   c.wi_x,     c.wi_y,     c.wi_z,     its_.data()};
    in.delta = MixesDeltaLobes(static_cast<MaterialTag>(t)) ? c.delta : nullptr;
    kernels_->continuation(rules, count, in, paths, &out);
  }
  const size_t m = out.rows;
  // Their rays (integrator::SpawnOrigin, the sample's world direction) through the kernel
  // table's spawn slot, straight into the queue's packets.
  next_rays_.Resize(m);
  kernels_->spawn(its_.data(), m, sp.Inputs(), next_rays_.packets.data());
}

}  // namespace ptlab
