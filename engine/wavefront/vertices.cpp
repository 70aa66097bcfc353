#include "engine/wavefront/vertices.h"

#include <algorithm>

#include "engine/light/light_selection.h"
#include "engine/render/integrator_common.h"

namespace ptlab {

bool VertexBatchFits(const Scene& scene) {
  const size_t n = scene.emitters.size();
  if (n == 0) return false;
  for (const EmitterRef e : scene.emitters)
    if (e.tag() != EmitterTag::kArea) return false;
  return scene.integrator.light_selection == LightSelection::kUniform || n <= kScanUpperBoundMax;
}

void DecideVertices(const Scene& scene, const VertexBatchRules& rules, size_t n,
                    const VertexBatchInputs& in, const VertexBatchPaths& paths,
                    VertexBatchOutputs* out) {
  const AreaPickColumns& a = out->area;
  const BsdfPickColumns& b = out->bsdf;
  const int depth = rules.depth;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t q = in.entries[k];
    const uint32_t i = in.owner[q];
    const SurfaceInteraction& its = in.its[q];
    const Vec3f& wo = in.wo[q];
    PathSampler& sampler = paths.sampler[i];
    if (rules.emitter_sample) {
      const uint32_t request = rules.first_request + uint32_t(k);
      out->request_traced[request] = 0;
      const float pick = sampler.Get1D(DecisionDimension(depth, Decision::kLightPick));
      const Vec2f u = sampler.Get2D(DecisionDimension(depth, Decision::kLightPoint));
      float pick_pmf = 0.0f;
      const EmitterRef emitter = SelectEmitter(scene, pick, &pick_pmf);
      if (pick_pmf > 0) {
        const size_t c = out->area_rows++;
        a.request[c] = request, a.entry[c] = q, a.light[c] = emitter.index();
        a.pick_pmf[c] = pick_pmf;
        a.ref_x[c] = its.p.x, a.ref_y[c] = its.p.y, a.ref_z[c] = its.p.z;
        a.wo_x[c] = wo.x, a.wo_y[c] = wo.y, a.wo_z[c] = wo.z;
        a.u_x[c] = u.x, a.u_y[c] = u.y;
      }
      if (!IsFinite(paths.throughput[i])) out->nonfinite[out->nonfinite_rows++] = request;
      out->nee_paths[request] = i;
      paths.nee_throughput[i] = paths.throughput[i];
    }
    if (rules.roulette) {
      const float q_continue = integrator::NoriContinuation(paths.throughput[i], in.eta[i]);
      if (!(sampler.Get1D(DecisionDimension(depth, Decision::kRoulette)) < q_continue)) continue;
      paths.throughput[i] *= 1.0f / q_continue;
    }
    float u_lobe;
    Vec2f u_dir;
    integrator::DrawBsdfNumbers(sampler, depth, &u_lobe, &u_dir);
    const size_t c = out->bsdf_rows++;
    b.path[c] = i, b.entry[c] = q, b.material_index[c] = its.material.index();
    b.roulette_scale[c] = 1.0f;
    b.wo_x[c] = wo.x, b.wo_y[c] = wo.y, b.wo_z[c] = wo.z;
    b.u_lobe[c] = u_lobe, b.u_x[c] = u_dir.x, b.u_y[c] = u_dir.y;
  }
}

}  // namespace ptlab
