// Writes the benchmarks' fractal terrain as an OBJ and a Nori XML scene that `ptlab render` reads.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "benchmarks/fractal_terrain.h"
#include "engine/image/image_io.h"
#include "engine/io/text_parsing.h"

namespace ptlab {
namespace {

constexpr int kMinGridSize = 2, kMaxGridSize = 4096;

// The terrain's vertices and faces (shared vertices, 1-based indices), in the order of
// MakeFractalTerrain, with every coordinate printed so that it reads back to the same float.
std::string TerrainObj(int n) {
  const std::vector<Vec3f> v = FractalTerrainVertices(n);
  const size_t triangles = 2 * size_t(n - 1) * size_t(n - 1);
  std::string out = "# ptlab fractal terrain (benchmarks/fractal_terrain.h), " + std::to_string(n) +
                    " x " + std::to_string(n) + " vertices, " + std::to_string(triangles) +
                    " triangles\n";
  out.reserve(v.size() * 40 + triangles * 30);
  char line[96];
  for (const Vec3f& p : v) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    out += line;
  }
  for (size_t t = 0; t < triangles; ++t) {
    const std::array<uint32_t, 3> c = FractalTerrainTriangle(n, t);
    std::snprintf(line, sizeof line, "f %u %u %u\n", c[0] + 1, c[1] + 1, c[2] + 1);
    out += line;
  }
  return out;
}

// The benchmarks' view of the terrain, lit by a sun (a 5° disk 40° from the zenith) and a sky.
std::string TerrainXml(const std::string& obj_name) {
  const TerrainView& v = kTerrainView;
  char camera[512];
  std::snprintf(camera, sizeof camera,
                "\t<camera type=\"perspective\">\n"
                "\t\t<transform name=\"toWorld\">\n"
                "\t\t\t<lookat origin=\"%.9g, %.9g, %.9g\" target=\"%.9g, %.9g, %.9g\" "
                "up=\"%.9g, %.9g, %.9g\"/>\n"
                "\t\t</transform>\n"
                "\t\t<float name=\"fov\" value=\"%.9g\"/>\n"
                "\t\t<integer name=\"width\" value=\"%d\"/>\n"
                "\t\t<integer name=\"height\" value=\"%d\"/>\n"
                "\t</camera>\n",
                v.eye.x, v.eye.y, v.eye.z, v.target.x, v.target.y, v.target.z, v.up.x, v.up.y,
                v.up.z, v.fov_deg, v.width, v.height);
  return "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
         "<!-- The fractal terrain of benchmarks/fractal_terrain.h (benchmarks/write_terrain). "
         "-->\n"
         "<scene>\n"
         "\t<integrator type=\"path_mis\"/>\n"
         "\t<sampler type=\"independent\">\n"
         "\t\t<integer name=\"sampleCount\" value=\"16\"/>\n"
         "\t</sampler>\n" +
         std::string(camera) +
         "\t<mesh type=\"obj\">\n"
         "\t\t<string name=\"filename\" value=\"" +
         obj_name +
         "\"/>\n"
         "\t\t<bsdf type=\"diffuse\">\n"
         "\t\t\t<color name=\"albedo\" value=\"0.55, 0.5, 0.42\"/>\n"
         "\t\t</bsdf>\n"
         "\t</mesh>\n"
         "\t<emitter type=\"distantdisk\">\n"
         "\t\t<color name=\"radiance\" value=\"80, 76, 68\"/>\n"
         "\t\t<float name=\"thetaA\" value=\"5\"/>\n"
         "\t\t<transform name=\"toWorld\">\n"
         "\t\t\t<rotate axis=\"1, 0, 0\" angle=\"40\"/>\n"
         "\t\t</transform>\n"
         "\t</emitter>\n"
         "\t<emitter type=\"constant\">\n"
         "\t\t<color name=\"radiance\" value=\"0.25, 0.32, 0.45\"/>\n"
         "\t</emitter>\n"
         "</scene>\n";
}

int Run(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr,
                 "usage: write_terrain OUT_DIR [GRID]\n"
                 "  writes OUT_DIR/terrain.obj (GRID x GRID vertices, default %d: 1,048,352 "
                 "triangles)\n  and OUT_DIR/terrain.xml (a Nori scene of it for ptlab render)\n",
                 kTerrainGridSize);
    return 2;
  }
  const std::filesystem::path dir(argv[1]);
  if (!std::filesystem::is_directory(dir)) {
    std::fprintf(stderr, "error: output directory '%s' does not exist\n", argv[1]);
    return 2;
  }
  int n = kTerrainGridSize;
  if (argc == 3 && (!ParseInt(argv[2], &n) || n < kMinGridSize || n > kMaxGridSize)) {
    std::fprintf(stderr, "error: GRID '%s' is not an integer in [%d, %d]\n", argv[2], kMinGridSize,
                 kMaxGridSize);
    return 2;
  }
  const std::string obj = (dir / "terrain.obj").string(), xml = (dir / "terrain.xml").string();
  Status st = WriteFileAtomically(obj, TerrainObj(n));
  if (st.ok()) st = WriteFileAtomically(xml, TerrainXml("terrain.obj"));
  if (!st.ok()) {
    std::fprintf(stderr, "error: %s\n", st.message().c_str());
    return 1;
  }
  std::printf("wrote %s (%zu triangles) and %s\n", obj.c_str(), 2 * size_t(n - 1) * size_t(n - 1),
              xml.c_str());
  return 0;
}

}  // namespace
}  // namespace ptlab

int main(int argc, char** argv) { return ptlab::Run(argc, argv); }
