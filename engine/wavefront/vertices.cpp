#include "engine/wavefront/vertices.h"

#include "engine/light/light_selection.h"
#include "engine/render/integrator_common.h"

namespace ptlab {

void DecideVertices(const Scene& scene, const VertexBatchRules& rules, size_t n,
                    const VertexBatchInputs& in, const VertexBatchPaths& paths,
                    VertexBatchOutputs* out) {
  using Roulette = VertexBatchRules::Roulette;
  const AreaPickColumns& a = out->area;
  const OtherPickColumns& o = out->other;
  const BsdfPickColumns& b = out->bsdf;
  const int depth = rules.depth;
  const uint32_t n_light = uint32_t(rules.light_samples);
  const bool emitters = !scene.emitters.empty();
  for (size_t k = 0; k < n; ++k) {
    const uint32_t q = in.entries[k];
    const uint32_t i = in.owner[q];
    const SurfaceInteraction& its = in.its[q];
    const Vec3f& wo = in.wo[q];
    PathSampler& sampler = paths.sampler[i];
    if (rules.emitter_sample) {
      const uint32_t first = rules.first_request + uint32_t(k) * n_light;
      for (uint32_t s = 0; s < n_light; ++s) {
        const uint32_t request = first + s;
        out->request_traced[request] = 0;
        if (!emitters) continue;
        float pick_pmf = 0.0f;
        EmitterRef emitter;
        Vec2f u;
        if (rules.sobol) {
          u = in.light_point[size_t(s) * in.light_stride + k];
          emitter = SelectEmitter(scene, u.x, &pick_pmf, &u.x);
        } else {
          const float pick = sampler.Get1D(DecisionDimension(depth, Decision::kLightPick), s,
                                           n_light);
          u = sampler.Get2D(DecisionDimension(depth, Decision::kLightPoint), s, n_light);
          emitter = SelectEmitter(scene, pick, &pick_pmf);
        }
        if (!(pick_pmf > 0)) continue;
        if (emitter.tag() == EmitterTag::kArea) {
          const size_t c = out->area_rows++;
          a.request[c] = request, a.entry[c] = q, a.light[c] = emitter.index();
          a.pick_pmf[c] = pick_pmf;
          a.ref_x[c] = its.p.x, a.ref_y[c] = its.p.y, a.ref_z[c] = its.p.z;
          a.wo_x[c] = wo.x, a.wo_y[c] = wo.y, a.wo_z[c] = wo.z;
          a.u_x[c] = u.x, a.u_y[c] = u.y;
        } else {
          const size_t c = out->other_rows++;
          o.request[c] = request, o.entry[c] = q, o.emitter[c] = emitter.bits;
          o.pick_pmf[c] = pick_pmf, o.u_x[c] = u.x, o.u_y[c] = u.y;
        }
      }
      if (n_light == 1 && !IsFinite(paths.throughput[i]))
        out->nonfinite[out->nonfinite_rows++] = first;
      out->nee_paths[rules.first_request / n_light + k] = i;
      paths.nee_throughput[i] = paths.throughput[i];
    }
    if (rules.ends_path) continue;
    const auto roulette = [&] {
      return rules.sobol ? in.roulette[k]
                         : sampler.Get1D(DecisionDimension(depth, Decision::kRoulette));
    };
    float roulette_scale = 1.0f;
    if (rules.roulette == Roulette::kNori) {
      const float q_continue = integrator::NoriContinuation(paths.throughput[i], in.eta[i]);
      if (!(roulette() < q_continue)) continue;
      paths.throughput[i] *= 1.0f / q_continue;
    } else if (rules.roulette == Roulette::kWhitted) {
      if (depth >= integrator::kWhittedMaxDepth || roulette() >= integrator::kWhittedContinuation)
        continue;
      roulette_scale = 1.0f / integrator::kWhittedContinuation;
    }
    // The lobe number, then the direction (SampleBsdf's order).
    float u_lobe;
    Vec2f u_dir;
    if (rules.sobol) {
      u_lobe = in.bsdf_lobe[k], u_dir = in.bsdf_direction[k];
    } else {
      integrator::DrawBsdfNumbers(sampler, depth, &u_lobe, &u_dir);
    }
    const size_t c = out->bsdf_rows++;
    b.path[c] = i, b.entry[c] = q, b.material_index[c] = its.material.index();
    b.roulette_scale[c] = roulette_scale;
    b.wo_x[c] = wo.x, b.wo_y[c] = wo.y, b.wo_z[c] = wo.z;
    b.u_lobe[c] = u_lobe, b.u_x[c] = u_dir.x, b.u_y[c] = u_dir.y;
  }
}

}  // namespace ptlab
