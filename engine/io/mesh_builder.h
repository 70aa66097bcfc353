// MeshData (an indexed triangle mesh in object space) and AddMesh, which appends it to a Scene.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/transform.h"
#include "engine/core/vec.h"
#include "engine/io/mesh_attribute.h"
#include "engine/scene/refs.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// An indexed triangle mesh in object space, as produced by LoadObj and the procedural shapes.
/// Vertex i is (positions[i], normals[i] if any, uvs[i] if any): `normals` and `uvs` are either
/// empty or exactly as long as `positions`. `indices` holds 3 entries per triangle.
struct MeshData {
  std::vector<Vec3f> positions, normals;
  std::vector<Vec2f> uvs;
  std::vector<uint32_t> indices;
  /// Other per-vertex / per-triangle columns of the file (PLY), for mesh_attribute textures.
  std::vector<MeshAttribute> attributes;

  size_t triangle_count() const { return indices.size() / 3; }
};

/// Appends `mesh`, transformed to world space by `to_world`, as one new MeshTable row and
/// returns that row. Positions go through ApplyPoint, normals through ApplyNormal and are
/// renormalised. Rows are appended to TriangleTable and TriangleShadingTable (one per triangle,
/// all with `material`) and, when the mesh has normals or uvs, to VertexTable; otherwise the
/// triangles' vertex rows are kNoVertex. The new mesh does not emit (EmitterRef::None()).
///
/// VertexTable columns stay aligned: a column is either empty (no mesh in the scene has that
/// attribute) or as long as the others; rows of meshes lacking an attribute are zero-filled
/// in that column and MeshTable::has_normals / has_uvs say which rows are meaningful.
///
/// Winding is kept as in `mesh`, even when `to_world` mirrors (FlipsHandedness()), as Nori
/// does. The geometric normal of a stored triangle is therefore
/// normalize(cross(v1 - v0, v2 - v0)) of its world-space vertices; under a mirroring transform
/// it points to the opposite side of the transformed shading normals (a mesh whose object-space
/// winding agreed with its normals then disagrees in world space).
///
/// Preconditions (PTLAB_CHECK): indices.size() % 3 == 0, every index < positions.size(),
/// normals/uvs empty or positions.size() long, every normal transforms to a non-zero finite
/// vector.
uint32_t AddMesh(Scene* scene, const MeshData& mesh, const Transform& to_world,
                 MaterialRef material, std::string name);

/// Makes mesh row `mesh` of `scene` an area light of `radiance`: a new AreaLightTable row, the
/// mesh's emitter reference, and the emitter appended to Scene::emitters. FinalizeAreaLights
/// fills its areas and CDFs once every shape is in.
void AttachAreaLight(Scene* scene, uint32_t mesh, const Color3f& radiance);

}  // namespace ptlab
