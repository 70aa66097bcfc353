// Tessellation of the procedural shapes: UV sphere, rectangle, cube, disk.
#include "engine/io/shapes.h"

#include <cmath>

#include "engine/core/check.h"

namespace ptlab {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;
constexpr double kPiD = 3.141592653589793238463;

void AddTriangle(MeshData* mesh, uint32_t a, uint32_t b, uint32_t c) {
  mesh->indices.push_back(a), mesh->indices.push_back(b), mesh->indices.push_back(c);
}

}  // namespace

MeshData MakeSphere(const Vec3f& center, float radius) {
  PTLAB_CHECK(radius > 0);
  constexpr int nu = kSphereSegments, nv = kSphereRings;
  MeshData mesh;
  for (int j = 0; j <= nv; ++j) {
    // Exact poles, so that all pole vertices coincide bit for bit.
    const double theta = kPiD * j / nv;
    const double sin_theta = (j == 0 || j == nv) ? 0.0 : std::sin(theta);
    const double cos_theta = j == 0 ? 1.0 : (j == nv ? -1.0 : std::cos(theta));
    for (int i = 0; i <= nu; ++i) {
      // The seam column i == nu reuses the angles of i == 0 so its positions match exactly.
      const double phi = kTwoPi * (i % nu) / nu;
      const Vec3f n{float(sin_theta * std::cos(phi)), float(sin_theta * std::sin(phi)),
                    float(cos_theta)};
      mesh.positions.push_back(center + radius * n);
      mesh.normals.push_back(n);
      mesh.uvs.push_back({float(i) / nu, float(j) / nv});
    }
  }
  const auto vertex = [](int i, int j) { return uint32_t(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      // a→c runs south (+θ), a→b east (+φ); cross(south, east) points outward.
      const uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i, j + 1),
                     d = vertex(i + 1, j + 1);
      if (j != nv - 1) AddTriangle(&mesh, a, c, d);  // degenerate at the south pole
      if (j != 0) AddTriangle(&mesh, a, d, b);       // degenerate at the north pole
    }
  }
  return mesh;
}

MeshData MakeRectangle() {
  MeshData mesh;
  mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  mesh.normals.assign(4, Vec3f{0, 0, 1});
  mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.indices = {0, 1, 2, 2, 3, 0};
  return mesh;
}

MeshData MakeCube() {
  // Per face: normal n and in-plane axes t, b with cross(t, b) = n.
  struct Face {
    Vec3f n, t, b;
  };
  static constexpr Face kFaces[6] = {
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
      {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}},
  };
  MeshData mesh;
  for (const Face& f : kFaces) {
    const uint32_t base = uint32_t(mesh.positions.size());
    mesh.positions.push_back(f.n - f.t - f.b);
    mesh.positions.push_back(f.n + f.t - f.b);
    mesh.positions.push_back(f.n + f.t + f.b);
    mesh.positions.push_back(f.n - f.t + f.b);
    for (int k = 0; k < 4; ++k) mesh.normals.push_back(f.n);
    mesh.uvs.insert(mesh.uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    AddTriangle(&mesh, base, base + 1, base + 2);
    AddTriangle(&mesh, base, base + 2, base + 3);
  }
  return mesh;
}

MeshData MakeDisk() { return MakeDisk(kDiskSegments); }

MeshData MakeDisk(int segments) {
  PTLAB_CHECK(segments >= 3);
  const int n = segments;
  MeshData mesh;
  mesh.positions.push_back({0, 0, 0});
  for (int i = 0; i < n; ++i) {
    const double phi = kTwoPi * i / n;
    mesh.positions.push_back({float(std::cos(phi)), float(std::sin(phi)), 0});
  }
  for (const Vec3f& p : mesh.positions) {
    mesh.normals.push_back({0, 0, 1});
    mesh.uvs.push_back({0.5f * (p.x + 1), 0.5f * (p.y + 1)});
  }
  for (int i = 0; i < n; ++i) AddTriangle(&mesh, 0, uint32_t(1 + i), uint32_t(1 + (i + 1) % n));
  return mesh;
}

}  // namespace ptlab
