// Wavefront stage: the vertex decisions of the paths that go on (emitter picks, roulette, BSDF
// numbers) into the emitter and BSDF stages' columns.
#include <algorithm>
#include <utility>

#include "engine/render/integrator_common.h"
#include "engine/wavefront/wave.h"

namespace ptlab {

using integrator::PrepareEmitterSampleFrom;

// Emitter samples (shadow rays queued), Russian roulette and BSDF sampling, in the scalar
// integrators' order of random numbers; continuing paths form the next, compact ray queue.
// The decisions are the kernel table's vertices slot, group by group, into the emitter and BSDF
// stages' columns (SampleGroup); SampleBsdfs then runs the bsdf slot over them and continues
// the paths.
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
  other_picks_.Clear(emitter_rows);
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

// Sample's rows [k, end) of goes_on_, all of material group g (delta: its tag's lobes are all
// Dirac deltas), through the kernel table's vertices slot: the integrator's rules for this
// group, the Sobol' numbers of the rows (drawn by DrawVertexNumbers) or none (the independent
// sampler's are drawn by the slot), and the area-light and BSDF rows appended to their
// columns' group g; the other emitters' picks are routed to their stages (RouteOtherPicks).
void Wavefront::SampleGroup(int depth, bool delta, int g, size_t k, size_t end) {
  VertexBatchRules rules;
  rules.depth = depth;
  rules.emitter_sample = rules_.nee && (!delta || rules_.nee_on_delta);
  rules.light_samples = rules_.light_samples;
  rules.ends_path =
      !rules_.bsdf_sampling || (rules.emitter_sample && rules_.nee_ends_path && !delta);
  // Nori's roulette from depth 3 (as integrator.cpp's path loop), Whitted's at every vertex.
  const bool nori_too_early = rules_.roulette == VertexRules::Roulette::kNori && depth < 3;
  rules.roulette = nori_too_early ? VertexRules::Roulette::kNone : rules_.roulette;
  rules.sobol = sobol_;
  rules.first_request = uint32_t(n_requests_);
  const size_t n = end - k;
  const size_t n_light = size_t(rules.light_samples);
  if (rules.emitter_sample) {
    n_requests_ += n * n_light;
    nee_paths_.resize(n_requests_ / n_light);
  }
  EmitterColumns& a = area_;
  BsdfColumns& b = bsdf_;
  VertexBatchOutputs out;
  const EmitterColumns::Pointers ac = a.At(a.next[g]);
  const BsdfColumns::Pointers bc = b.At(b.next[g]);
  const OtherPickColumns::Pointers oc = other_picks_.At(0);
  out.area = {ac.request, ac.entry, ac.light, ac.pick_pmf, ac.ref_x, ac.ref_y,
              ac.ref_z,   ac.wo_x,  ac.wo_y,  ac.wo_z,     ac.u_x,   ac.u_y};
  out.other = {oc.request, oc.entry, oc.emitter, oc.pick_pmf, oc.u_x, oc.u_y};
  out.bsdf = {bc.path, bc.entry, bc.material_index, bc.roulette_scale,
              bc.wo_x, bc.wo_y,  bc.wo_z,           bc.u_lobe,
              bc.u_x,  bc.u_y};
  out.request_traced = request_traced_.data();
  out.nee_paths = nee_paths_.data();
  const size_t nonfinite_at = nonfinite_nee_.size();
  nonfinite_nee_.resize(nonfinite_at + n);
  out.nonfinite = nonfinite_nee_.data() + nonfinite_at;
  VertexBatchInputs in{goes_on_.data() + k, rays_.owner.data(), its_.data(), wo_.data(),
                       eta_.data()};
  if (sobol_) {
    // DrawVertexNumbers' rows are goes_on_'s: row k of this group is row k there.
    const size_t m = continuing_.size();
    if (!light_point_.empty()) in.light_point = light_point_.data() + k, in.light_stride = m;
    if (!roulette_.empty()) in.roulette = roulette_.data() + k;
    if (!bsdf_lobe_.empty()) in.bsdf_lobe = bsdf_lobe_.data() + k;
    if (!bsdf_direction_.empty()) in.bsdf_direction = bsdf_direction_.data() + k;
  }
  const VertexBatchPaths paths{sampler_.data(), throughput_.data(), nee_throughput_.data()};
  kernels_->vertices(*scene_, rules, n, in, paths, &out);
  nonfinite_nee_.resize(nonfinite_at + out.nonfinite_rows);
  a.rows += out.area_rows, a.next[g] += uint32_t(out.area_rows);
  b.rows += out.bsdf_rows, b.next[g] += uint32_t(out.bsdf_rows);
  RouteOtherPicks(out.other_rows);
}

// Rows [0, n) of other_picks_, in request order: environment-map and distant-disk picks to
// their emitter stages' columns, delta lights prepared here (one position or direction each,
// nothing to batch; kernels.h).
void Wavefront::RouteOtherPicks(size_t n) {
  const OtherPickColumns& o = other_picks_;
  for (size_t c = 0; c < n; ++c) {
    const EmitterRef emitter{o.emitter[c]};
    const uint32_t request = o.request[c], q = o.entry[c];
    const Vec2f u{o.u_x[c], o.u_y[c]};
    switch (emitter.tag()) {
      case EmitterTag::kEnvironment:
        environment_[emitter.index()].Push(request, q, o.pick_pmf[c], u);
        break;
      case EmitterTag::kDistantDisk:
        distant_disk_[emitter.index()].Push(request, q, o.pick_pmf[c], u);
        break;
      case EmitterTag::kPoint:
      case EmitterTag::kDirectional:
      case EmitterTag::kSpot:
      case EmitterTag::kProjector:
        StoreRequest(request, PrepareEmitterSampleFrom(*scene_, its_[q], wo_[q], rules_.mis, emitter,
                                                       o.pick_pmf[c], u));
        break;
      case EmitterTag::kArea:  // the vertices slot writes these to the area columns
        break;
    }
  }
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
