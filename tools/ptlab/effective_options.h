// The whole effective set of options of `ptlab render`, as (name, value) text pairs: what MPI
// ranks must agree on before they render one image together.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/render/render.h"
#include "engine/scene/scene.h"
#include "tools/ptlab/command_line.h"

namespace ptlab {

/// The options that decide the image after the scene files and the flags are applied: film
/// size, camera (frame, field of view, lens), samples and passes, seed, sampler, integrator,
/// adaptive sampling, kernel path, lookat convention, and the counts of the scene's tables.
/// Not listed: what only changes speed or output (threads, -q, --stats, -o, --tile-times).
std::vector<std::pair<std::string, std::string>> EffectiveRenderOptions(
    const RenderArgs& args, const Scene& scene, uint32_t spp, const AdaptiveSampling& adaptive,
    bool packets);

}  // namespace ptlab
