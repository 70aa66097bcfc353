// Wavefront stage: the emitter samples (area lights, environment maps, distant disks) through
// their slots, and their shadow rays queued.
#include <algorithm>

#include "engine/render/integrator_common.h"
#include "engine/wavefront/wave.h"

namespace ptlab {

using integrator::InfiniteEmitterSampleRequest;

// The emitter stage: per material tag, the kernel table's area_light slot over the tag's
// area-light picks, then its area_request slot (shadow ray, contribution: PrepareEmitterSample's
// finish); then, tag by tag in request order, each traced request's row and shadow ray
// (StoreRequest's; reading the columns in their order, not through a slot per row).
void Wavefront::SampleAreaLights() {
  EmitterColumns& a = area_;
  const size_t n = a.size();
  if (n == 0) return;
  // Textured area lights: each sample's radiance is its point's, carried in the le columns.
  const bool textured = !scene_->area_lights.texture.empty();
  if (textured && a.le_r.size() < a.light.size())
    a.le_r.resize(a.light.size()), a.le_g.resize(a.light.size()), a.le_b.resize(a.light.size());
  for (int t = 0; t < kMaterialTagCount; ++t) {
    const size_t b = a.begin[t], count = a.next[t] - b;
    if (count == 0) continue;
    const EmitterColumns::Pointers c = a.At(b);
    float* const le_r = textured ? a.le_r.data() + b : nullptr;
    float* const le_g = textured ? a.le_g.data() + b : nullptr;
    float* const le_b = textured ? a.le_b.data() + b : nullptr;
    const AreaLightBatchInputs in{c.light, c.ref_x, c.ref_y, c.ref_z, c.u_x, c.u_y};
    const AreaLightBatchOutputs out{c.p_x,  c.p_y,  c.p_z,  c.n_x, c.n_y, c.n_z, c.ng_x,
                                    c.ng_y, c.ng_z, c.pdf,  le_r,  le_g,  le_b};
    kernels_->area_light(kernels_->accel, *scene_, scene_->integrator.triangle_sampling, count, in,
                         out);
    const AreaRequestInputs request_in{its_.data(), c.entry, c.ref_x, c.ref_y,  c.ref_z, c.wo_x,
                                       c.wo_y,      c.wo_z,  c.light, c.pick_pmf, c.p_x, c.p_y,
                                       c.p_z,       c.n_x,   c.n_y,   c.n_z,    c.ng_x,  c.ng_y,
                                       c.ng_z,      c.pdf,   le_r,    le_g,     le_b};
    const AreaRequestOutputs request_out{c.traced, c.o_x, c.o_y, c.o_z, c.d_x,
                                         c.d_y,    c.d_z, c.r,   c.g,   c.b};
    kernels_->area_request(*scene_, static_cast<MaterialTag>(t), rules_.mis, count, request_in,
                           request_out);
  }
  // Group by group (rows of no material trace nothing: BsdfEval is 0), each in request order:
  // the traced rows compacted through the shadow_rows slot, then queued a packet at a time.
  ShadowRowColumns& st = shadow_rows_;
  st.Clear(n);
  size_t m = 0;
  for (int t = 0; t < kMaterialTagCount; ++t) {
    const size_t b = a.begin[t], count = a.next[t] - b;
    if (count == 0) continue;
    const EmitterColumns::Pointers c = a.At(b);
    const ShadowRowInputs in{c.traced, c.request, c.o_x, c.o_y, c.o_z, c.d_x,
                             c.d_y,    c.d_z,     c.r,   c.g,   c.b};
    m += kernels_->shadow_rows(count, in, st.Outputs().From(m));
  }
  QueueShadowRows(m);
}

// Rows [0, m) of shadow_rows_ into the shadow queue (owner: the request), a packet's run of
// lanes at a time, and each request's flag and contribution (StoreRequest's).
void Wavefront::QueueShadowRows(size_t m) {
  const ShadowRowColumns& st = shadow_rows_;
  size_t e = shadows_.size();
  shadows_.Resize(e + m);
  const auto copy = [&](RayPacket8& p, size_t j, size_t k, size_t run) {
    std::copy_n(&st.o_x[k], run, &p.org_x[j]), std::copy_n(&st.o_y[k], run, &p.org_y[j]);
    std::copy_n(&st.o_z[k], run, &p.org_z[j]), std::copy_n(&st.d_x[k], run, &p.dir_x[j]);
    std::copy_n(&st.d_y[k], run, &p.dir_y[j]), std::copy_n(&st.d_z[k], run, &p.dir_z[j]);
    std::fill_n(&p.t_min[j], run, 0.0f), std::fill_n(&p.t_max[j], run, 1.0f);
  };
  size_t k = 0;
  // Whole packets (a constant run: eight-float moves), after the partial one the queue ends
  // in and before the last.
  if (e % kLanes != 0) {
    const size_t run = std::min(kLanes - e % kLanes, m);
    copy(shadows_.packets[e / kLanes], e % kLanes, 0, run);
    k += run, e += run;
  }
  for (; k + kLanes <= m; k += kLanes, e += kLanes)
    copy(shadows_.packets[e / kLanes], 0, k, kLanes);
  if (k < m) copy(shadows_.packets[e / kLanes], 0, k, m - k);
  std::copy_n(st.request.data(), m, shadows_.owner.data() + shadows_.size() - m);
  for (k = 0; k < m; ++k) {
    const uint32_t r = st.request[k];
    request_traced_[r] = 1;
    request_contribution_[r] = {st.r[k], st.g[k], st.b[k]};
  }
}

// The emitter stage's infinite lights: the kernel table's environment slot over each map's
// picks and its distant_disk slot over each disk's, then each returned sample's request as
// PrepareEmitterSample finishes it.
void Wavefront::SampleInfiniteLights() {
  // A row without a sample (pdf 0: a black light) keeps its empty request.
  const auto finish = [this](const InfiniteLightColumns& e) {
    for (size_t c = 0; c < e.size(); ++c) {
      if (!(e.pdf[c] > 0)) continue;
      const EnvironmentSample es{
          {e.wi_x[c], e.wi_y[c], e.wi_z[c]}, {e.r[c], e.g[c], e.b[c]}, e.pdf[c]};
      const size_t q = e.entry[c];
      StoreRequest(e.request[c], InfiniteEmitterSampleRequest(*scene_, its_[q], wo_[q], rules_.mis,
                                                              es, e.pick_pmf[c]));
    }
  };
  for (uint32_t map = 0; map < environment_.size(); ++map) {
    InfiniteLightColumns& e = environment_[map];
    if (e.size() == 0) continue;
    kernels_->environment(scene_->environment_maps, map, e.size(), e.Inputs(), e.Outputs());
    finish(e);
  }
  for (uint32_t disk = 0; disk < distant_disk_.size(); ++disk) {
    InfiniteLightColumns& e = distant_disk_[disk];
    if (e.size() == 0) continue;
    kernels_->distant_disk(scene_->distant_disks, disk, e.size(), e.Inputs(), e.Outputs());
    finish(e);
  }
}

}  // namespace ptlab
