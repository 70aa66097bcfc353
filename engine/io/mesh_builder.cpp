// AddMesh: appends an object-space MeshData to the scene's geometry tables in world space.
#include "engine/io/mesh_builder.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/core/check.h"

namespace ptlab {
namespace {

// Makes `column` cover `rows` rows (zero-filling) if it must hold data from now on.
template <typename Column>
void ZeroFillTo(Column* column, size_t rows) {
  if (column->size() < rows) column->resize(rows, 0.0f);
}

}  // namespace

uint32_t AddMesh(Scene* scene, const MeshData& mesh, const Transform& to_world,
                 MaterialRef material, std::string name) {
  const size_t vertex_count = mesh.positions.size();
  const bool has_normals = !mesh.normals.empty();
  const bool has_uvs = !mesh.uvs.empty();
  PTLAB_CHECK(mesh.indices.size() % 3 == 0);
  PTLAB_CHECK(!has_normals || mesh.normals.size() == vertex_count);
  PTLAB_CHECK(!has_uvs || mesh.uvs.size() == vertex_count);
  for (const uint32_t index : mesh.indices) PTLAB_CHECK(index < vertex_count);

  MeshTable& meshes = scene->meshes;
  const uint32_t mesh_row = uint32_t(meshes.size());
  const uint32_t first_triangle = uint32_t(scene->triangles.size());

  // Vertex rows: every non-empty VertexTable column has the same length.
  VertexTable& vt = scene->vertices;
  const size_t vertex_rows = std::max(vt.n_x.size(), vt.u.size());
  uint32_t vertex_base = kNoVertex;
  if (has_normals || has_uvs) {
    vertex_base = uint32_t(vertex_rows);
    PTLAB_CHECK(vertex_rows + vertex_count < kNoVertex);
    if (has_normals) {
      ZeroFillTo(&vt.n_x, vertex_rows), ZeroFillTo(&vt.n_y, vertex_rows),
          ZeroFillTo(&vt.n_z, vertex_rows);
      for (const Vec3f& n : mesh.normals) {
        // Scaling by the largest component before and after the transform keeps tiny or huge
        // (but valid) normals from underflowing or overflowing in Length.
        Vec3f w = to_world.ApplyNormal(n / MaxComponent(Abs(n)));
        const float largest = MaxComponent(Abs(w));
        PTLAB_CHECK(largest > 0 && std::isfinite(largest));
        w = Normalize(w / largest);
        vt.n_x.push_back(w.x), vt.n_y.push_back(w.y), vt.n_z.push_back(w.z);
      }
    } else if (!vt.n_x.empty()) {
      const size_t end = vertex_rows + vertex_count;
      ZeroFillTo(&vt.n_x, end), ZeroFillTo(&vt.n_y, end), ZeroFillTo(&vt.n_z, end);
    }
    if (has_uvs) {
      ZeroFillTo(&vt.u, vertex_rows), ZeroFillTo(&vt.v, vertex_rows);
      for (const Vec2f& uv : mesh.uvs) vt.u.push_back(uv.x), vt.v.push_back(uv.y);
    } else if (!vt.u.empty()) {
      const size_t end = vertex_rows + vertex_count;
      ZeroFillTo(&vt.u, end), ZeroFillTo(&vt.v, end);
    }
  }

  std::vector<Vec3f> world(vertex_count);
  for (size_t i = 0; i < vertex_count; ++i) world[i] = to_world.ApplyPoint(mesh.positions[i]);

  TriangleShadingTable& shading = scene->shading;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1],
                   c = mesh.indices[3 * t + 2];
    scene->triangles.Append(world[a], world[b], world[c]);
    shading.mesh.push_back(mesh_row);
    shading.material.push_back(material);
    const bool indexed = vertex_base != kNoVertex;
    shading.vertex0.push_back(indexed ? vertex_base + a : kNoVertex);
    shading.vertex1.push_back(indexed ? vertex_base + b : kNoVertex);
    shading.vertex2.push_back(indexed ? vertex_base + c : kNoVertex);
  }

  meshes.first_triangle.push_back(first_triangle);
  meshes.triangle_count.push_back(uint32_t(mesh.triangle_count()));
  meshes.material.push_back(material);
  meshes.emitter.push_back(EmitterRef::None());
  meshes.has_normals.push_back(has_normals ? 1 : 0);
  meshes.has_uvs.push_back(has_uvs ? 1 : 0);
  meshes.name.push_back(std::move(name));
  return mesh_row;
}

void AttachAreaLight(Scene* scene, uint32_t mesh, const Color3f& radiance) {
  AreaLightTable& lights = scene->area_lights;
  const EmitterRef ref = EmitterRef::Make(EmitterTag::kArea, uint32_t(lights.size()));
  lights.radiance.push_back(radiance);
  lights.mesh.push_back(mesh);
  scene->meshes.emitter[mesh] = ref;
  scene->emitters.push_back(ref);
}

}  // namespace ptlab
