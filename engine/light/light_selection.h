// Choosing the emitter of an emitter sample: uniformly, or in proportion to power.
#pragma once

#include <cstdint>

#include "engine/core/check.h"
#include "engine/sampling/guide_table.h"
#include "engine/scene/refs.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// Fills scene->emitter_selection from the emitters, lights and geometry (after
/// FinalizeAreaLights has the lights' areas). Emitters whose power is zero are never picked;
/// when every emitter's power is zero the table is uniform.
void BuildEmitterSelection(Scene* scene);

/// Probability that emitter sampling picks emitter e under the scene's light selection.
inline float EmitterSelectionPmf(const Scene& scene, EmitterRef e) {
  const size_t n = scene.emitters.size();
  if (n == 0) return 0.0f;
  if (scene.integrator.light_selection == LightSelection::kUniform) return 1.0f / float(n);
  const EmitterSelectionTable& t = scene.emitter_selection;
  switch (e.tag()) {
    case EmitterTag::kArea: return t.pmf[t.slot_area[e.index()]];
    case EmitterTag::kEnvironment: return t.pmf[t.slot_environment[e.index()]];
    case EmitterTag::kDistantDisk: return t.pmf[t.slot_disk[e.index()]];
    case EmitterTag::kPoint: return t.pmf[t.slot_point[e.index()]];
    case EmitterTag::kDirectional: return t.pmf[t.slot_directional[e.index()]];
    case EmitterTag::kSpot: return t.pmf[t.slot_spot[e.index()]];
    case EmitterTag::kProjector: return t.pmf[t.slot_projector[e.index()]];
  }
  return 0.0f;
}

/// Picks an emitter with u in [0, 1) (the scene must have one); *pmf = its probability. With
/// `u_remapped`, also u stretched back to [0, 1) over the picked emitter's interval of [0, 1),
/// a number independent of the pick (the Sobol' sampler reuses it for the point on the emitter,
/// so the points that land on each emitter are themselves stratified).
/// Inline: the wavefront picks once per emitter sample, and a call costs it the pmf's round
/// trip through memory and the remapped u's division where nobody asks for it.
inline EmitterRef SelectEmitter(const Scene& scene, float u, float* pmf,
                                float* u_remapped = nullptr) {
  const size_t n = scene.emitters.size();
  PTLAB_DCHECK(n > 0);
  if (scene.integrator.light_selection == LightSelection::kUniform) {
    const size_t k = std::min(n - 1, size_t(u * float(n)));
    *pmf = 1.0f / float(n);
    if (u_remapped) *u_remapped = std::min(u * float(n) - float(k), kOneMinusEpsilon);
    return scene.emitters[k];
  }
  const EmitterSelectionTable& t = scene.emitter_selection;
  PTLAB_CHECK(t.size() == n);  // BuildEmitterSelection ran after the last emitter was added
  const CdfPick pick = PickCdfBin(t.cdf.data(), uint32_t(n), t.guide.data(), u);
  const uint32_t k = pick.bin;
  *pmf = t.pmf[k];
  if (u_remapped) *u_remapped = pick.u_remapped;
  return scene.emitters[k];
}

}  // namespace ptlab
