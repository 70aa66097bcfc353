// Wavefront stage: traversal (closest hits of the ray queue) and shadow traversal (each
// unoccluded emitter sample added to its path).
#include <bit>

#include "engine/wavefront/wave.h"

namespace ptlab {

// Closest hits of every queued ray, one kernel call per packet.
void Wavefront::Traverse() {
  const size_t packets = rays_.packets.size();
  hits_.resize(packets), hit_mask_.resize(packets);
  for (size_t k = 0; k < packets; ++k) {
    const Mask8 active = rays_.Active(k);
    hit_mask_[k] =
        kernels_->intersect8(kernels_->accel, rays_.packets[k], active, &hits_[k]) & active;
  }
  // Every queued ray is in an active lane (the queue is compact): no popcount per packet,
  // which the baseline target makes a library call.
  stats_->rays += rays_.size();
  stats_->packets += packets;
}

// The shadow rays, one kernel call per packet. With one emitter sample per vertex, each
// unoccluded sample's light is added to its path here (AddEmitterSamples' sum for that path,
// its operations in its order), while the packet's owners are at hand: no per-request flag
// and no second pass over the paths.
void Wavefront::TraceShadows() {
  const bool add_here = rules_.light_samples == 1;
  if (!add_here) occluded_.assign(n_requests_, 0);
  for (size_t k = 0; k < shadows_.packets.size(); ++k) {
    const Mask8 active = shadows_.Active(k);
    const Mask8 occ = kernels_->occluded8(kernels_->accel, shadows_.packets[k], active) & active;
    const uint32_t* owner = shadows_.owner.data() + k * kLanes;
    if (!add_here) {
      for (Mask8 m = occ; m != 0; m &= m - 1) occluded_[owner[std::countr_zero(m)]] = 1;
      continue;
    }
    for (Mask8 m = active & ~occ; m != 0; m &= m - 1) {
      const uint32_t r = owner[std::countr_zero(m)];
      AddEmitterSample(nee_paths_[r], request_contribution_[r]);
    }
    // An occluded sample's zero goes through AddNonFiniteEmitterSamples like an untraced one.
    for (Mask8 m = occ; m != 0; m &= m - 1) request_traced_[owner[std::countr_zero(m)]] = 0;
  }
  if (add_here) AddNonFiniteEmitterSamples();
  stats_->rays += shadows_.size();  // as in Traverse: every queued ray is an active lane
  stats_->packets += shadows_.packets.size();
}

// One emitter sample's light (sum `direct`, of n_light = 1 samples) weighted by the path's
// throughput at the vertex: AddEmitterSamples' last line.
void Wavefront::AddEmitterSample(uint32_t i, const Color3f& contribution) {
  Color3f direct;
  direct += contribution;
  L_[i] += nee_throughput_[i] * direct * 1.0f;
}

// With one emitter sample per vertex: the zero light of the untraced or occluded samples of
// paths whose throughput is not finite. Their zero is skipped everywhere else, which changes
// no bit for a finite throughput (L starts at +0 and never becomes -0); here it makes the
// NaN that Inf or NaN times zero gives, as AddEmitterSamples does.
void Wavefront::AddNonFiniteEmitterSamples() {
  for (const uint32_t r : nonfinite_nee_) {
    if (!request_traced_[r]) AddEmitterSample(nee_paths_[r], Color3f{});
  }
}

// Each path's emitter samples, summed in sample order, weighted by its throughput at the
// vertex (the scalar integrators add them before shading the next vertex; so does this).
// With one sample per vertex TraceShadows has added them already.
void Wavefront::AddEmitterSamples() {
  const int n_light = rules_.light_samples;
  if (n_light == 1) return;
  const float inv_n = 1.0f / float(n_light);
  for (size_t p = 0; p < nee_paths_.size(); ++p) {
    const uint32_t i = nee_paths_[p];
    Color3f direct;
    for (int s = 0; s < n_light; ++s) {
      const size_t r = p * size_t(n_light) + size_t(s);
      // EmitterSampleResult: adding its zero for an untraced or occluded sample changes no
      // bit (direct starts at +0 and never becomes -0), so those rows are skipped.
      if (request_traced_[r] && !occluded_[r]) direct += request_contribution_[r];
    }
    L_[i] += nee_throughput_[i] * direct * inv_n;
  }
}

}  // namespace ptlab
