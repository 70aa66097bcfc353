// Choosing the emitter of an emitter sample: uniformly, or in proportion to power.
#pragma once

#include <cstdint>

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
  }
  return 0.0f;
}

/// Picks an emitter with u in [0, 1) (the scene must have one); *pmf = its probability. With
/// `u_remapped`, also u stretched back to [0, 1) over the picked emitter's interval of [0, 1),
/// a number independent of the pick (the Sobol' sampler reuses it for the point on the emitter,
/// so the points that land on each emitter are themselves stratified).
EmitterRef SelectEmitter(const Scene& scene, float u, float* pmf, float* u_remapped = nullptr);

}  // namespace ptlab
