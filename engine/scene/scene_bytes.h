// Heap bytes of the scene's component tables (capacity × element size of every column).
#pragma once

#include <cstddef>

#include "engine/scene/geometry_tables.h"
#include "engine/scene/scene.h"
#include "engine/scene/sphere_table.h"

namespace ptlab {

/// Heap bytes of the scene's tables, by what reads them: traversal (`triangles`, `spheres`),
/// shading after a hit (`shading`: TriangleShadingTable; `vertices`: VertexTable; `materials`),
/// emitters (`emitters`: every emitter table, the emitter list and its selection table) and
/// `meshes` (MeshTable, names included). The render settings and file names are not counted.
struct SceneBytes {
  size_t triangles = 0, spheres = 0, shading = 0, vertices = 0, materials = 0, emitters = 0,
         meshes = 0;
  size_t total() const {
    return triangles + spheres + shading + vertices + materials + emitters + meshes;
  }
};

SceneBytes SceneTableBytes(const Scene& scene);

/// Heap bytes of one table's columns.
size_t TableBytes(const TriangleTable& t);
size_t TableBytes(const SphereTable& t);
/// Sdfgrids: counted with the spheres (traversal reads both).
size_t TableBytes(const SdfGridTable& t);

}  // namespace ptlab
