// Wavefront stage: a bounce's hits and escaped rays (the interaction slot, emission at
// area-light hits, environment light of escaped rays).
#include <algorithm>
#include <bit>

#include "engine/render/integrator_common.h"
#include "engine/wavefront/wave.h"

namespace ptlab {

using integrator::Escaped;
using integrator::MisWeight;

// Emission at hits, environment light for escaped rays; lists the entries that go on to the
// sampling stage (goes_on_; its_ / wo_ hold their shading points). The interaction slot
// writes the shading points for the whole wave, frames and wo included, and lists the hits
// (all, and those on area lights) with their material groups' counts, so that this stage
// visits only the hits that emit and the escaped rays.
void Wavefront::Shade(int depth) {
  const size_t packets = rays_.packets.size();
  // Eight rows per packet: the SIMD slot may write every row of a packet with a hit and the
  // lists' room past their counts. Only grown: a resize up would construct each new row, and
  // the queue shrinks and grows back every wave.
  GrowColumns(packets * kLanes, &its_, &wo_, &goes_on_, &area_hits_);
  const bool batch_escaped = EscapedRaysBatch();
  escaped_.Clear();
  HitLists lists{goes_on_.data(), area_hits_.data()};
  kernels_->interaction(kernels_->accel, *scene_, rays_.packets.data(), hits_.data(),
                        hit_mask_.data(), packets, {its_.data(), wo_.data()}, &lists);
  if (rules_.normals) {
    // The first hit's |n|, nothing else: no path goes on.
    for (uint32_t h = 0; h < lists.hits; ++h) {
      const uint32_t q = goes_on_[h];
      const Vec3f a = Abs(its_[q].frame.n);
      L_[rays_.owner[q]] = {a.x, a.y, a.z};
    }
    n_goes_on_ = 0;
    std::fill(std::begin(goes_on_tags_), std::end(goes_on_tags_), 0u);
    return;
  }
  // Without infinite lights an escaped ray brings no light: Escaped's zero times a finite
  // throughput adds ±0, which leaves L as it is (it starts at +0 and never becomes -0), so only
  // the paths whose throughput is not finite (0 times Inf or NaN is NaN) take the loop below.
  const bool infinite = scene_->environment_maps.size() + scene_->distant_disks.size() != 0;
  // hide_emitters: the camera rays' emitted light is not counted (neither loop runs).
  const bool hidden = depth == 0 && scene_->integrator.hide_emitters;
  for (size_t k = 0; k < packets && !hidden; ++k) {
    for (Mask8 todo = rays_.Active(k) & ~hit_mask_[k]; todo != 0; todo &= todo - 1) {
      // Escaped: environment light, counted unless emitter sampling already did (after a
      // non-specular bounce), MIS-weighted when mis is on.
      const size_t q = k * kLanes + size_t(std::countr_zero(todo));
      const uint32_t i = rays_.owner[q];
      if (!infinite && IsFinite(throughput_[i])) continue;
      const Vec3f d = rays_.Direction(q);
      const Vec3f w = d / Length(d);
      const bool plain = !rules_.nee || specular_[i];
      if (!plain && !rules_.mis) continue;
      if (batch_escaped) {
        escaped_.Push(uint32_t(q), w, !plain);
      } else {
        L_[i] += throughput_[i] * Escaped(*scene_, w, !plain, plain ? 0.0f : prev_pdf_[i]);
      }
    }
  }
  // Only area lights emit at a surface (Emitted's test; EmitterRef::None's tag is not kArea).
  if (lists.area_hits != 0 && !hidden) {
    kernels_->emission(
        *scene_, {.nee = rules_.nee, .mis = rules_.mis}, lists.area_hits,
        {area_hits_.data(), rays_.packets.data(), rays_.owner.data(), its_.data()},
        {throughput_.data(), specular_.data(), prev_pdf_.data(), prev_p_.data(), L_.data()});
  }
  // Past the last vertex that is shaded no hit goes on; otherwise every hit does.
  const bool goes_on = rules_.max_depth < 0 || depth < rules_.max_depth;
  n_goes_on_ = goes_on ? lists.hits : 0;
  for (int g = 0; g < kMaterialGroups; ++g) goes_on_tags_[g] = goes_on ? lists.group_hits[g] : 0;
  if (batch_escaped) ShadeEscaped();
}

// Whether the escaped rays take the environment_eval batch: when every infinite emitter is
// an environment map, listed among the emitters in table order (so that summing the maps
// per row in that order is integrator::Escaped's sum, with and without MIS). Distant disks
// keep the per-row integrator::Escaped.
bool Wavefront::EscapedRaysBatch() const {
  if (scene_->environment_maps.size() == 0 || scene_->distant_disks.size() != 0) return false;
  uint32_t next = 0;
  for (const EmitterRef e : scene_->emitters)
    if (IsInfiniteLight(e) && (e.tag() != EmitterTag::kEnvironment || e.index() != next++))
      return false;
  return next == scene_->environment_maps.size();
}

// The escaped rays' environment light as one batch per map: radiance (and, for MIS, the
// emitter-sampling pdf) through the kernel table's environment_eval slot, summed per row over
// the maps in integrator::Escaped's order and operations.
void Wavefront::ShadeEscaped() {
  EscapedColumns& e = escaped_;
  const size_t m = e.q.size();
  if (m == 0) return;
  const bool any_mis = std::find(e.mis.begin(), e.mis.end(), uint8_t(1)) != e.mis.end();
  e.light.assign(m, Color3f{});
  e.r.resize(m), e.g.resize(m), e.b.resize(m), e.pdf.resize(m);
  for (const EmitterRef emitter : scene_->emitters) {
    if (!IsInfiniteLight(emitter)) continue;
    kernels_->environment_eval(
        scene_->environment_maps, emitter.index(), m, {e.w_x.data(), e.w_y.data(), e.w_z.data()},
        {e.r.data(), e.g.data(), e.b.data(), any_mis ? e.pdf.data() : nullptr});
    const float pmf = EmitterSelectionPmf(*scene_, emitter);
    for (size_t row = 0; row < m; ++row) {
      const Color3f Le{e.r[row], e.g[row], e.b[row]};
      if (!e.mis[row]) {
        e.light[row] += Le;
      } else if (!IsBlack(Le)) {
        const uint32_t i = rays_.owner[e.q[row]];
        e.light[row] +=
            Le * MisWeight(prev_pdf_[i], e.pdf[row] * pmf, scene_->integrator.power_heuristic);
      }
    }
  }
  for (size_t row = 0; row < m; ++row) {
    const uint32_t i = rays_.owner[e.q[row]];
    L_[i] += throughput_[i] * e.light[row];
  }
}

}  // namespace ptlab
