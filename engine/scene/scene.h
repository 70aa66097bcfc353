// The scene: a handful of component tables plus the render settings read from the scene file.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/transform.h"
#include "engine/scene/emitter_tables.h"
#include "engine/scene/geometry_tables.h"
#include "engine/scene/material_tables.h"

namespace ptlab {

/// Perspective or thin-lens camera (Nori `perspective`, Mitsuba `thinlens` names).
/// Camera space looks along +z with +y up; +x maps to the image's left (Nori's convention).
struct CameraDesc {
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
};

struct SamplerDesc {
  uint32_t sample_count = 1;
};

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
  };
  Type type = Type::kNormals;
  int max_depth = -1;      // CS184 meaning: 0 = emitted only, 1 = direct, ...; -1 = unbounded
  int light_samples = 1;   // emitter samples per hit (CS184's -l)
  bool power_heuristic = false;
};

struct Scene {
  TriangleTable triangles;
  TriangleShadingTable shading;
  VertexTable vertices;
  MeshTable meshes;
  MaterialTables materials;
  AreaLightTable area_lights;
  EnvironmentMapTable environment_maps;
  DistantDiskTable distant_disks;
  PointLightTable point_lights;
  std::vector<EmitterRef> emitters;  // all emitters, for uniform selection

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

/// Fills area_lights' areas and triangle CDFs from the meshes that carry an area emitter.
/// Called by loaders after all shapes are in; idempotent.
void FinalizeAreaLights(Scene* scene);

}  // namespace ptlab
