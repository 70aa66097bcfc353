// The subpath vertex of bidirectional path tracing and the densities, scattering and MIS weights
// over it (bdpt_mis.cpp): shared by the subpath walks (bdpt_walk.cpp), the connections
// (bdpt_connect.cpp) and the batch driver (bdpt.cpp). Internal to engine/render/bdpt*.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/light/delta_light.h"
#include "engine/render/bdpt.h"
#include "engine/render/interaction.h"

namespace ptlab::bdpt {

enum class VertexKind : uint8_t { kCamera, kLight, kSurface };

// One subpath vertex. pdf_fwd: density with which its own subpath produced it; pdf_rev: with
// which the other subpath would have (both per unit area, or per solid angle for a vertex at
// infinity, whose `w` is then the unit direction towards the emitter).
struct Vertex {
  VertexKind kind = VertexKind::kSurface;
  Vec3f p, ng, n;  // position, geometric and shading normals (zero for points and the camera)
  Vec3f wo;        // surface: unit direction towards the previous vertex of its subpath
  Vec3f w;         // vertex at infinity: unit direction towards the emitter
  Vec3f to_prev;   // surface: DirectionTo(this, previous vertex) in its shading frame
  SurfaceInteraction its;
  EmitterRef emitter;  // light vertex: its emitter; surface: the area light it lies on, if any
  Color3f beta;
  float pdf_fwd = 0, pdf_rev = 0;
  bool delta = false;     // surface with a delta BSDF
  bool infinite = false;  // light vertex at infinity
  bool on_surface = false;

  bool DeltaLight() const { return kind == VertexKind::kLight && IsDeltaLight(emitter); }
  // Whether a connection may end here.
  bool Connectible() const {
    if (kind == VertexKind::kSurface) return !delta;
    if (kind == VertexKind::kLight) return emitter.tag() != EmitterTag::kDirectional;
    return true;
  }
};

// A subpath's vertices, grown on demand (every vertex is assigned before it is read), so a
// batch's memory follows the lengths of its paths, not maxDepth.
using Subpath = std::vector<Vertex>;

// Vertex i of `path`, growing it when needed. References into the path are invalidated.
inline Vertex& At(Subpath* path, int i) {
  if (path->size() <= size_t(i)) path->resize(std::max<size_t>(size_t(i) + 1, 2 * path->size()));
  return (*path)[size_t(i)];
}

// Area density at `to` of a direction sampled at `from` with solid-angle density pdf; a vertex
// at infinity keeps the solid-angle density.
float ConvertDensity(float pdf, const Vertex& from, const Vertex& to);
// Unit direction from `from` to `to` (either may be at infinity).
Vec3f DirectionTo(const Vertex& from, const Vertex& to);
// Density (area at `next`) with which light vertex v emits towards `next`.
float PdfLight(const Scene& scene, const BidirectionalSetup& setup, const Vertex& v,
               const Vertex& next);
// Veach's adjoint-BSDF factor for a light subpath turning at a surface with shading normals.
float ShadingNormalCorrection(const SurfaceInteraction& its, const Vec3f& w_in, const Vec3f& w_out);
// What surface vertex v sends towards unit direction w, the cosine at v included (camera
// subpath: the BSDF; light subpath: the adjoint BSDF with the shading-normal factor).
Color3f ScatterTo(const Scene& scene, const Vertex& v, const Vec3f& w, bool light_subpath);
// The MIS weight of strategy (s, t) (Veach eq. 10.9 as ratios of densities along the path),
// light[0..s) and camera[0..t) with the connection's sampled vertex already in place.
float MisWeightOf(const Scene& scene, const BidirectionalSetup& setup, Subpath& light, int s,
                  Subpath& camera, int t);

}  // namespace ptlab::bdpt
