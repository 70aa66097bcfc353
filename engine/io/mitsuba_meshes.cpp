// Mitsuba 3's disk and cylinder as triangle meshes with Mitsuba's uvs.
#include "engine/io/mitsuba_meshes.h"

#include <cmath>

#include "engine/core/check.h"

namespace ptlab {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;

void AddTriangle(MeshData* mesh, uint32_t a, uint32_t b, uint32_t c) {
  mesh->indices.push_back(a), mesh->indices.push_back(b), mesh->indices.push_back(c);
}

// The rim point at φ = 2πi/n, computed as MakeDisk does (so that positions match bit for bit).
Vec3f RimPoint(int i, int n) {
  const double phi = kTwoPi * i / n;
  return {float(std::cos(phi)), float(std::sin(phi)), 0};
}

}  // namespace

MeshData MakeMitsubaDisk(int segments) {
  PTLAB_CHECK(segments >= 3);
  const int n = segments;
  MeshData mesh;
  // Rim vertices 0..n (n repeats 0 with v = 1), then one centre vertex per triangle.
  for (int i = 0; i <= n; ++i) {
    mesh.positions.push_back(RimPoint(i % n, n));
    mesh.uvs.push_back({1.0f, float(double(i) / n)});
  }
  for (int i = 0; i < n; ++i) {
    mesh.positions.push_back({0, 0, 0});
    mesh.uvs.push_back({0.0f, float((i + 0.5) / n)});
  }
  mesh.normals.assign(mesh.positions.size(), Vec3f{0, 0, 1});
  for (int i = 0; i < n; ++i) AddTriangle(&mesh, uint32_t(n + 1 + i), uint32_t(i), uint32_t(i + 1));
  return mesh;
}

MeshData MakeMitsubaCylinder(int segments) {
  PTLAB_CHECK(segments >= 3);
  const int n = segments;
  MeshData mesh;
  // Vertex 2i at z = 0, 2i + 1 at z = 1, for i = 0..n (n repeats 0's positions with u = 1).
  for (int i = 0; i <= n; ++i) {
    const Vec3f rim = RimPoint(i % n, n);
    const float u = float(double(i) / n);
    mesh.positions.push_back(rim);
    mesh.positions.push_back({rim.x, rim.y, 1.0f});
    mesh.normals.push_back(rim);
    mesh.normals.push_back(rim);
    mesh.uvs.push_back({u, 0.0f});
    mesh.uvs.push_back({u, 1.0f});
  }
  for (int i = 0; i < n; ++i) {
    const uint32_t b0 = uint32_t(2 * i), t0 = b0 + 1, b1 = b0 + 2, t1 = b0 + 3;
    AddTriangle(&mesh, b0, b1, t1);
    AddTriangle(&mesh, b0, t1, t0);
  }
  return mesh;
}

MeshData MakeMitsubaCube() {
  struct Face {
    Vec3f n, o, u, v;
  };
  static constexpr Face kFaces[6] = {
      {{0, -1, 0}, {-1, -1, -1}, {0, 0, 1}, {1, 0, 0}},
      {{0, 1, 0}, {1, 1, 1}, {-1, 0, 0}, {0, 0, -1}},
      {{1, 0, 0}, {1, -1, 1}, {0, 1, 0}, {0, 0, -1}},
      {{0, 0, 1}, {-1, -1, 1}, {0, 1, 0}, {1, 0, 0}},
      {{-1, 0, 0}, {-1, -1, -1}, {0, 1, 0}, {0, 0, 1}},
      {{0, 0, -1}, {-1, 1, -1}, {0, -1, 0}, {1, 0, 0}},
  };
  MeshData mesh;
  for (const Face& f : kFaces) {
    const uint32_t base = uint32_t(mesh.positions.size());
    const Vec2f uvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const Vec2f& uv : uvs) {
      mesh.positions.push_back(f.o + f.u * (2 * uv.x) + f.v * (2 * uv.y));
      mesh.normals.push_back(f.n);
      mesh.uvs.push_back(uv);
    }
    // Wound so that the geometric normal is the face's (outward).
    const Vec3f p0 = mesh.positions[base], p1 = mesh.positions[base + 1],
                p2 = mesh.positions[base + 2];
    if (Dot(Cross(p1 - p0, p2 - p0), f.n) > 0) {
      AddTriangle(&mesh, base, base + 1, base + 2);
      AddTriangle(&mesh, base, base + 2, base + 3);
    } else {
      AddTriangle(&mesh, base, base + 2, base + 1);
      AddTriangle(&mesh, base, base + 3, base + 2);
    }
  }
  return mesh;
}

}  // namespace ptlab
