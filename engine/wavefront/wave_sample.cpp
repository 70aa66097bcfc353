// Wavefront stage: the vertex decisions of the paths that go on (emitter picks, roulette, BSDF
// numbers) into the emitter and BSDF stages' columns.
#include <algorithm>
#include <utility>

#include "engine/render/integrator_common.h"
#include "engine/wavefront/wave.h"

namespace ptlab {

using integrator::DrawBsdfNumbers;
using integrator::kWhittedContinuation;
using integrator::kWhittedMaxDepth;
using integrator::NoriContinuation;
using integrator::PrepareEmitterSampleFrom;

// Emitter samples (shadow rays queued), Russian roulette and BSDF sampling, in the scalar
// integrators' order of random numbers; continuing paths form the next, compact ray queue.
// The BSDF numbers are drawn here, per path in that order, into the BSDF stage's columns
// (group by group: through the vertices slot where it serves, else row by row);
// SampleBsdfs then runs the kernel table's bsdf slot over them and continues the paths.
void Wavefront::Sample(int depth) {
  const int n_light = rules_.light_samples;
  next_rays_.Clear(), shadows_.Clear();
  nee_paths_.clear(), nonfinite_nee_.clear();
  bsdf_.Clear(rays_.size(), goes_on_tags_);
  const size_t emitter_rows = rules_.nee ? rays_.size() * size_t(n_light) : 0;
  // Requests are SoA columns written in place (a row's flag, its ray and contribution only
  // when it traces): no request struct per row. The columns only grow.
  n_requests_ = 0;
  GrowColumns(emitter_rows, &request_traced_, &request_contribution_);
  uint32_t area_rows[kMaterialGroups] = {};
  if (rules_.nee)
    for (int t = 0; t < kMaterialGroups; ++t) area_rows[t] = goes_on_tags_[t] * uint32_t(n_light);
  area_.Clear(emitter_rows, area_rows);
  for (InfiniteLightColumns& e : environment_) e.Clear(emitter_rows);
  for (InfiniteLightColumns& e : distant_disk_) e.Clear(emitter_rows);
  GroupEntries();
  if (sobol_) DrawVertexNumbers(depth);
  // Group by group (the BSDF and emitter columns' groups): a group's rows share their tag, so
  // whether the vertex takes emitter samples is known per group, and its rows go to the
  // columns' slots one after the other.
  size_t k = 0;
  for (int g = 0; g < kMaterialGroups; ++g) {
    const size_t end = k + goes_on_tags_[g];
    if (k == end) continue;
    const bool delta = g < kMaterialTagCount && IsDeltaMaterial(static_cast<MaterialTag>(g));
    SampleGroup(depth, delta, g, k, end);
    k = end;
  }
  SampleAreaLights();
  SampleInfiniteLights();
  SampleBsdfs();
}

// goes_on_[0, n_goes_on_) in stable order by material group (a counting sort, whose counts
// are goes_on_tags_); as it is when one group holds every entry.
void Wavefront::GroupEntries() {
  uint32_t at[kMaterialGroups];
  uint32_t sum = 0, groups = 0;
  for (int g = 0; g < kMaterialGroups; ++g) {
    at[g] = sum, sum += goes_on_tags_[g];
    groups += goes_on_tags_[g] != 0 ? 1u : 0u;
  }
  if (groups < 2) return;
  GrowColumns(goes_on_.size(), &grouped_);
  for (size_t k = 0; k < n_goes_on_; ++k) {
    const uint32_t q = goes_on_[k];
    grouped_[at[MaterialGroup(its_[q].material)]++] = q;
  }
  std::swap(goes_on_, grouped_);
}

// SampleGroup through the kernel table's vertices slot (vertex_batch_: the independent
// sampler, one emitter sample per vertex, only area lights, no Whitted rules).
void Wavefront::SampleGroupBatch(int depth, bool delta, int g, size_t k, size_t end) {
  VertexBatchRules rules;
  rules.depth = depth;
  rules.emitter_sample = rules_.nee && (!delta || rules_.nee_on_delta);
  rules.roulette = rules_.roulette == VertexRules::Roulette::kNori && depth >= 3;
  rules.first_request = uint32_t(n_requests_);
  const size_t n = end - k;
  if (rules.emitter_sample) {
    n_requests_ += n;
    nee_paths_.resize(n_requests_);
  }
  EmitterColumns& a = area_;
  BsdfColumns& b = bsdf_;
  const uint32_t area_at = a.next[g], bsdf_at = b.next[g];
  VertexBatchOutputs out;
  const EmitterColumns::Pointers ac = a.At(area_at);
  const BsdfColumns::Pointers bc = b.At(bsdf_at);
  out.area = {ac.request, ac.entry, ac.light, ac.pick_pmf, ac.ref_x, ac.ref_y,
              ac.ref_z,   ac.wo_x,  ac.wo_y,  ac.wo_z,     ac.u_x,   ac.u_y};
  out.bsdf = {bc.path, bc.entry, bc.material_index, bc.roulette_scale,
              bc.wo_x, bc.wo_y,  bc.wo_z,           bc.u_lobe,
              bc.u_x,  bc.u_y};
  out.request_traced = request_traced_.data();
  out.nee_paths = nee_paths_.data();
  const size_t nonfinite_at = nonfinite_nee_.size();
  nonfinite_nee_.resize(nonfinite_at + n);
  out.nonfinite = nonfinite_nee_.data() + nonfinite_at;
  const VertexBatchInputs in{goes_on_.data() + k, rays_.owner.data(), its_.data(), wo_.data(),
                             eta_.data()};
  const VertexBatchPaths paths{sampler_.data(), throughput_.data(), nee_throughput_.data()};
  kernels_->vertices(*scene_, rules, n, in, paths, &out);
  nonfinite_nee_.resize(nonfinite_at + out.nonfinite_rows);
  a.rows += out.area_rows, a.next[g] += uint32_t(out.area_rows);
  b.rows += out.bsdf_rows, b.next[g] += uint32_t(out.bsdf_rows);
}

// Sample's rows [k, end) of goes_on_, all of material group g (delta: its tag's lobes are all
// Dirac deltas).
void Wavefront::SampleGroup(int depth, bool delta, int g, size_t k, size_t end) {
  if (vertex_batch_) {
    SampleGroupBatch(depth, delta, g, k, end);
    return;
  }
  const int n_light = rules_.light_samples;
  const bool emitters = !scene_->emitters.empty();
  const size_t m = continuing_.size();  // with sobol: entry c of the drawn numbers
  uint32_t area_at = area_.next[g], bsdf_at = bsdf_.next[g];
  for (; k < end; ++k) {
    const uint32_t q = goes_on_[k];
    const uint32_t i = rays_.owner[q];
    const SurfaceInteraction& its = its_[q];
    const Vec3f& wo = wo_[q];
    PathSampler& sampler = sampler_[i];
    if (rules_.nee && (!delta || rules_.nee_on_delta)) {
      for (int s = 0; s < n_light; ++s) {
        const uint32_t request = uint32_t(n_requests_++);
        request_traced_[request] = 0;
        if (!emitters) continue;
        // PrepareEmitterSample's numbers and pick (DrawEmitterNumbers, PickEmitter), as
        // plain floats; area-light, environment-map and distant-disk picks go to the emitter
        // stage's batches, the delta lights are prepared here.
        float pick_pmf = 0.0f;
        EmitterRef emitter;
        Vec2f u;
        if (sobol_) {
          u = light_point_[size_t(s) * m + k];
          emitter = SelectEmitter(*scene_, u.x, &pick_pmf, &u.x);
        } else {
          const float pick = sampler.Get1D(DecisionDimension(depth, Decision::kLightPick),
                                           uint32_t(s), uint32_t(n_light));
          u = sampler.Get2D(DecisionDimension(depth, Decision::kLightPoint), uint32_t(s),
                            uint32_t(n_light));
          emitter = SelectEmitter(*scene_, pick, &pick_pmf);
        }
        if (!(pick_pmf > 0)) continue;
        switch (emitter.tag()) {
          case EmitterTag::kArea:
            area_.Put(area_at++, request, uint32_t(q), emitter.index(), pick_pmf, its.p, wo, u);
            break;
          case EmitterTag::kEnvironment:
            environment_[emitter.index()].Push(request, uint32_t(q), pick_pmf, u);
            break;
          case EmitterTag::kDistantDisk:
            distant_disk_[emitter.index()].Push(request, uint32_t(q), pick_pmf, u);
            break;
          // Delta lights: one position or direction each, nothing to batch.
          case EmitterTag::kPoint:
          case EmitterTag::kDirectional:
          case EmitterTag::kSpot:
          case EmitterTag::kProjector:
            StoreRequest(request, PrepareEmitterSampleFrom(*scene_, its, wo, rules_.mis, emitter,
                                                           pick_pmf, u));
            break;
        }
      }
      // With one sample per vertex, the request of nee path p is row p.
      if (n_light == 1 && !IsFinite(throughput_[i])) nonfinite_nee_.push_back(n_requests_ - 1);
      nee_paths_.push_back(i);
      nee_throughput_[i] = throughput_[i];
      if (rules_.nee_ends_path && !delta) continue;
    }
    if (!rules_.bsdf_sampling) continue;
    const auto roulette = [&] {
      return sobol_ ? roulette_[k] : sampler.Get1D(DecisionDimension(depth, Decision::kRoulette));
    };
    float roulette_scale = 1.0f;
    if (rules_.roulette == VertexRules::Roulette::kNori && depth >= 3) {
      const float q_continue = NoriContinuation(throughput_[i], eta_[i]);
      if (!(roulette() < q_continue)) continue;
      throughput_[i] *= 1.0f / q_continue;
    } else if (rules_.roulette == VertexRules::Roulette::kWhitted) {
      if (depth >= kWhittedMaxDepth || roulette() >= kWhittedContinuation) continue;
      roulette_scale = 1.0f / kWhittedContinuation;
    }
    // The lobe number, then the direction (SampleBsdf's order).
    float u_lobe;
    Vec2f u_dir;
    if (sobol_) {
      u_lobe = bsdf_lobe_[k], u_dir = bsdf_direction_[k];
    } else {
      DrawBsdfNumbers(sampler, depth, &u_lobe, &u_dir);
    }
    bsdf_.Put(bsdf_at++, i, uint32_t(q), its.material, wo, u_lobe, u_dir, roulette_scale);
  }
  area_.rows += area_at - area_.next[g], area_.next[g] = area_at;
  bsdf_.rows += bsdf_at - bsdf_.next[g], bsdf_.next[g] = bsdf_at;
}

// Sobol' numbers of every decision of vertex `depth` for the paths that go on (continuing_,
// in queue order), one batch draw per dimension (and emitter sub-sample).
void Wavefront::DrawVertexNumbers(int depth) {
  continuing_.clear();
  for (size_t k = 0; k < n_goes_on_; ++k) continuing_.push_back(rays_.owner[goes_on_[k]]);
  const size_t m = continuing_.size();
  const uint32_t n_light = uint32_t(rules_.light_samples);
  if (rules_.nee && !scene_->emitters.empty()) {
    // No pick numbers: the pick is folded into the point's x (EmitterNumbers).
    light_point_.resize(m * n_light);
    for (uint32_t s = 0; s < n_light; ++s) {
      FillSobolRows(continuing_, s, n_light);
      DrawSobol2D(DecisionDimension(depth, Decision::kLightPoint), light_point_.data() + s * m);
    }
  }
  if (!rules_.bsdf_sampling) return;
  // With one emitter sample per vertex, its rows (sub 0 of 1) are the BSDF decisions' rows.
  const bool emitter_rows_fit = rules_.nee && !scene_->emitters.empty() && n_light == 1;
  if (!emitter_rows_fit) FillSobolRows(continuing_, 0, 1);
  roulette_.resize(m), bsdf_lobe_.resize(m), bsdf_direction_.resize(m);
  // Roulette numbers only where Sample reads them (Nori's from depth 3, Whitted's always).
  const bool roulette = rules_.roulette == VertexRules::Roulette::kWhitted ||
                        (rules_.roulette == VertexRules::Roulette::kNori && depth >= 3);
  if (roulette) DrawSobol1D(DecisionDimension(depth, Decision::kRoulette), roulette_.data());
  DrawSobol1D(DecisionDimension(depth, Decision::kBsdfLobe), bsdf_lobe_.data());
  DrawSobol2D(DecisionDimension(depth, Decision::kBsdfDirection), bsdf_direction_.data());
}

// The rows of the next draws: the given paths' pixel seeds and sample indices (sub-sample
// sub of sub_count); each DrawSobol then draws one dimension for all of them with the kernel
// table's batch kernel.
void Wavefront::FillSobolRows(const std::vector<uint32_t>& paths, uint32_t sub,
                              uint32_t sub_count) {
  const size_t m = paths.size();
  draw_seed_.resize(m), draw_index_.resize(m), draw_x_.resize(m), draw_y_.resize(m);
  for (size_t k = 0; k < m; ++k) {
    const PathSampler& p = sampler_[paths[k]];
    draw_seed_[k] = p.pixel_seed32();
    draw_index_[k] = p.index() * sub_count + sub;
  }
}

void Wavefront::DrawSobol1D(uint32_t dim, float* out) {
  kernels_->sobol1d(draw_seed_.data(), draw_index_.data(), dim, draw_seed_.size(), out);
}

void Wavefront::DrawSobol2D(uint32_t dim, Vec2f* out) {
  const size_t m = draw_seed_.size();
  kernels_->sobol2d(draw_seed_.data(), draw_index_.data(), dim, m, draw_x_.data(), draw_y_.data());
  for (size_t k = 0; k < m; ++k) out[k] = {draw_x_[k], draw_y_[k]};
}

}  // namespace ptlab
