// The scene: a handful of component tables plus the render settings read from the scene file.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/transform.h"
#include "engine/sampling/sampler.h"
#include "engine/scene/emitter_tables.h"
#include "engine/scene/geometry_tables.h"
#include "engine/scene/instance_table.h"
#include "engine/scene/material_tables.h"
#include "engine/scene/sdf_grid_table.h"
#include "engine/scene/sphere_table.h"
#include "engine/scene/texture_tables.h"

namespace ptlab {

/// Perspective or thin-lens camera (Nori `perspective`, Mitsuba `thinlens` names).
/// Camera space looks along +z with +y up; +x maps to the image's left (Nori's convention).
struct CameraDesc {
  /// Perspective (pinhole or thin lens, fov_deg) or orthographic (Mitsuba's `orthographic`:
  /// rays along camera +z from the film rectangle x in [-1, 1], y in [-1/aspect, 1/aspect] on
  /// the plane z = near_clip, mapped by camera_to_world, whose scale sets the view's extent).
  enum class Projection : uint8_t { kPerspective, kOrthographic };
  Projection projection = Projection::kPerspective;
  Transform camera_to_world;
  float fov_deg = 30.0f;  // horizontal field of view
  int width = 1280, height = 720;
  float near_clip = 1e-4f, far_clip = 1e4f;
  float aperture_radius = 0.0f;  // 0 = pinhole
  float focus_distance = 1.0f;
  /// Which field of view a new film size keeps (ResizeFilm, engine/render/camera.h): the
  /// horizontal one (Nori) or the vertical one (CS184's pathtracer -r).
  bool keep_vertical_fov = false;
};

/// Pixel reconstruction filter; Nori's default is Gaussian, radius 2 px, stddev 0.5 px.
struct FilterDesc {
  enum class Type : uint8_t { kBox, kTent, kGaussian };
  Type type = Type::kGaussian;
  float radius = 2.0f;
  float stddev = 0.5f;
  /// 0: the film interpolates the filter from a fine table (PixelFilter). n > 0: the filter is
  /// a staircase of n steps over [0, radius], each step the value at its inner end: how Mitsuba
  /// 3's scalar variants, which render its reference images, splat (its
  /// ReconstructionFilter::eval_discretized, MI_FILTER_RESOLUTION = 31). Mitsuba scenes set 31.
  uint16_t steps = 0;
};

/// The scene's sampler (Nori `<sampler type=... >`); scenes that name none get kDefaultSampler.
struct SamplerDesc {
  static constexpr SamplerType kDefaultSampler = SamplerType::kSobol;
  SamplerType type = kDefaultSampler;
  uint32_t sample_count = 1;
};

/// How emitter sampling picks the emitter: uniformly (Nori's rule), or in proportion to the
/// emitters' power (EmitterSelectionTable).
enum class LightSelection : uint8_t { kUniform, kPower };
/// How emitter sampling draws a point on a triangle of an area light: uniform by area, or
/// uniform in the solid angle the triangle subtends (Arvo 1995), falling back to area
/// sampling where that is not accurate in float (tiny or nearly hemispherical triangles).
enum class TriangleSampling : uint8_t { kArea, kSolidAngle };

struct IntegratorDesc {
  enum class Type : uint8_t {
    kNormals,
    kDirectEms,
    kDirectMats,
    kDirectMis,
    kWhitted,
    kPathMats,
    kPathEms,
    kPathMis,
    kBdpt,     // bidirectional path tracing (engine/render/bdpt.h)
    kPtracer,  // particle tracer: light tracing plus emitters seen directly
  };
  Type type = Type::kNormals;
  int max_depth = -1;      // CS184 meaning: 0 = emitted only, 1 = direct, ...; -1 = unbounded
  int light_samples = 1;   // emitter samples per hit (CS184's -l)
  bool power_heuristic = false;  // bdpt/ptracer: the power heuristic unless `balance`
  LightSelection light_selection = LightSelection::kPower;
  TriangleSampling triangle_sampling = TriangleSampling::kArea;
  /// Mitsuba's hide_emitters (path and direct integrators): the camera ray's own emitted light
  /// (an emitter it hits, or the environment it escapes to) is not counted.
  bool hide_emitters = false;
};

struct Scene {
  TriangleTable triangles;
  TriangleShadingTable shading;
  VertexTable vertices;
  MeshTable meshes;
  SphereTable spheres;  // analytic spheres, beside the triangles (BuildBvh takes both)
  SdfGridTable sdf_grids;  // signed-distance grids, beside the triangles as the spheres
  InstanceTable instances;  // shape groups (rows of triangles) placed by instances
  MaterialTables materials;
  TextureTable textures;  // empty unless a material parameter is textured (engine/texture/)
  AreaLightTable area_lights;
  EnvironmentMapTable environment_maps;
  DistantDiskTable distant_disks;
  PointLightTable point_lights;
  DirectionalLightTable directional_lights;
  SpotLightTable spot_lights;
  ProjectorTable projectors;
  std::vector<EmitterRef> emitters;  // all emitters, in selection order
  EmitterSelectionTable emitter_selection;

  CameraDesc camera;
  FilterDesc filter;
  SamplerDesc sampler;
  IntegratorDesc integrator;
  std::string source_path;  // the scene file, for headers and messages
  /// Every file the loader read (scene, meshes, images), so that processes rendering one scene
  /// can check they all read the same bytes.
  std::vector<std::string> input_files;
  /// What a loader accepted although the file is not quite right (printed by `ptlab render`).
  std::vector<std::string> load_warnings;
};

/// The XML name of an integrator type ("path_mis", ...).
const char* IntegratorTypeName(IntegratorDesc::Type type);
/// The integrator type of an XML name; false for an unknown name.
bool IntegratorTypeFromName(std::string_view name, IntegratorDesc::Type* type);

/// Fills area_lights' areas and triangle CDFs from the meshes that carry an area emitter, and
/// the emitter selection table of all emitters. Called by loaders after all shapes and
/// emitters are in (and again by whoever adds emitters later); idempotent.
void FinalizeAreaLights(Scene* scene);

}  // namespace ptlab
