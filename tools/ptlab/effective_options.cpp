// The effective options of `ptlab render` (see effective_options.h).
#include "tools/ptlab/effective_options.h"

#include <cstdio>

#include "engine/sampling/sampler.h"

namespace ptlab {
namespace {

// Every float to the bit: ranks that differ in the last place render different images.
std::string Exact(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%a", double(v));
  return buf;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> EffectiveRenderOptions(
    const RenderArgs& args, const Scene& scene, uint32_t spp, const AdaptiveSampling& adaptive,
    bool packets) {
  const CameraDesc& c = scene.camera;
  std::string frame;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) frame += (frame.empty() ? "" : " ") + Exact(c.camera_to_world.matrix().m[i][j]);
  return {
      {"film (-r, --width, --height)", std::to_string(c.width) + "x" + std::to_string(c.height)},
      {"camera frame (scene, -c)", frame},
      {"field of view (scene, -c)", Exact(c.fov_deg)},
      {"clip planes (scene, -c)", Exact(c.near_clip) + " " + Exact(c.far_clip)},
      {"lens radius (-b)", Exact(c.aperture_radius)},
      {"focus distance (-d)", Exact(c.focus_distance)},
      {"samples per pixel (-s)", std::to_string(spp)},
      {"seed (--seed)", std::to_string(args.seed)},
      {"sampler (--sampler)", SamplerTypeName(scene.sampler.type)},
      {"integrator", IntegratorTypeName(scene.integrator.type)},
      {"max depth (-m)", std::to_string(scene.integrator.max_depth)},
      {"light samples (-l)", std::to_string(scene.integrator.light_samples)},
      {"adaptive (-a)", std::to_string(adaptive.batch) + " " + Exact(adaptive.tolerance)},
      {"kernels (--scalar)", packets ? "packet" : "scalar"},
      {"lookat (--lookat)", args.lookat},
      {"scene tables", std::to_string(scene.triangles.size()) + " triangles, " +
                           std::to_string(scene.spheres.size()) + " spheres, " +
                           std::to_string(scene.emitters.size()) + " emitters, " +
                           std::to_string(scene.environment_maps.size()) + " environment maps"},
  };
}

}  // namespace ptlab
