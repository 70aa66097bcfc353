// COLLADA loader (CS184 scenes): every element kind on small files of our own, malformed files
// with file:line messages, and the nine CS184 scenes of ../shared/data.
#include "engine/io/collada_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/io/scene_file.h"
#include "engine/io/shapes.h"
#include "engine/light/distant_disk.h"
#include "engine/render/camera.h"
#include "tests/test_data.h"

namespace ptlab {
namespace {

const std::string kHeader =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n";

// A camera looking down -z from (0, 0, 5) (yfov 60, aspect 2).
const std::string kCamera =
    "<library_cameras><camera id=\"cam\"><optics><technique_common><perspective>\n"
    "<xfov>60</xfov><aspect_ratio>2</aspect_ratio><znear>0.1</znear><zfar>100</zfar>\n"
    "</perspective></technique_common></optics></camera></library_cameras>\n";

// One triangle (0,0,0) (1,0,0) (0,1,0), material symbol "m".
const std::string kTriangle =
    "<geometry id=\"tri\"><mesh>\n"
    "<source id=\"tri-p\"><float_array id=\"tri-pa\" count=\"9\">0 0 0 1 0 0 0 1 0</float_array>\n"
    "<technique_common><accessor source=\"#tri-pa\" count=\"3\" stride=\"3\">"
    "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
    "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
    "<vertices id=\"tri-v\"><input semantic=\"POSITION\" source=\"#tri-p\"/></vertices>\n"
    "<triangles material=\"m\" count=\"1\"><input semantic=\"VERTEX\" source=\"#tri-v\" "
    "offset=\"0\"/><p>0 1 2</p></triangles>\n"
    "</mesh></geometry>\n";

struct Parts {
  std::string asset = "<asset><unit name=\"meter\" meter=\"1\"/><up_axis>Y_UP</up_axis></asset>\n";
  std::string lights, effects, materials, geometries = kTriangle;
  std::string nodes = "<node id=\"n\"><instance_geometry url=\"#tri\"/></node>\n";
  std::string camera_node =
      "<node id=\"camnode\"><translate>0 0 5</translate><instance_camera url=\"#cam\"/></node>\n";
};

std::string Document(const Parts& p) {
  return kHeader + p.asset + kCamera + "<library_lights>" + p.lights + "</library_lights>\n" +
         "<library_effects>" + p.effects + "</library_effects>\n" + "<library_materials>" +
         p.materials + "</library_materials>\n" + "<library_geometries>" + p.geometries +
         "</library_geometries>\n" +
         "<library_visual_scenes><visual_scene id=\"s\">\n" + p.camera_node + p.nodes +
         "</visual_scene></library_visual_scenes>\n"
         "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";
}

StatusOr<Scene> Load(const Parts& p) { return LoadColladaSceneFromString(Document(p), "t.dae"); }

Scene LoadOk(const Parts& p) {
  StatusOr<Scene> s = Load(p);
  EXPECT_TRUE(s.ok()) << s.status().message() << "\n" << Document(p);
  return s.ok() ? std::move(*s) : Scene();
}

// The 1-based line of the first occurrence of `marker` in the document of `p`.
int LineOf(const Parts& p, const std::string& marker) {
  const std::string doc = Document(p);
  const size_t at = doc.find(marker);
  EXPECT_NE(at, std::string::npos) << marker;
  return 1 + int(std::count(doc.begin(), doc.begin() + std::min(at, doc.size()), '\n'));
}

// The load fails with a message naming t.dae at the line of `marker` and holding `words`.
void ExpectError(const Parts& p, const std::string& marker, const std::vector<std::string>& words) {
  StatusOr<Scene> s = Load(p);
  ASSERT_FALSE(s.ok()) << "expected an error for " << marker;
  const std::string& m = s.status().message();
  const std::string where = "t.dae:" + std::to_string(LineOf(p, marker)) + ":";
  EXPECT_NE(m.find(where), std::string::npos) << "no '" << where << "' in: " << m;
  for (const std::string& w : words)
    EXPECT_NE(m.find(w), std::string::npos) << "'" << w << "' missing from: " << m;
}

void ExpectNear(const Vec3f& a, const Vec3f& b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(ColladaLoader, PolylistTrianglesPolygons) {
  Parts p;
  p.geometries =
      "<geometry id=\"g\"><mesh>\n"
      "<source id=\"g-p\"><float_array id=\"g-pa\" count=\"15\">0 0 0 1 0 0 1 1 0 0 1 0 "
      "0.5 2 0</float_array><technique_common><accessor source=\"#g-pa\" count=\"5\" "
      "stride=\"3\"><param name=\"X\"/><param name=\"Y\"/><param name=\"Z\"/></accessor>"
      "</technique_common></source>\n"
      "<vertices id=\"g-v\"><input semantic=\"POSITION\" source=\"#g-p\"/></vertices>\n"
      "<polylist count=\"1\"><input semantic=\"VERTEX\" source=\"#g-v\" offset=\"0\"/>"
      "<vcount>4</vcount><p>0 1 2 3</p></polylist>\n"
      "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#g-v\" offset=\"0\"/>"
      "<p>3 2 4</p></triangles>\n"
      "<polygons count=\"1\"><input semantic=\"VERTEX\" source=\"#g-v\" offset=\"0\"/>"
      "<p>0 1 2 4 3</p></polygons>\n"
      "</mesh></geometry>\n";
  p.nodes = "<node id=\"n\"><instance_geometry url=\"#g\"/></node>\n";
  const Scene s = LoadOk(p);
  // A quad (2 triangles), a triangle, a fan-triangulated pentagon (3): 3 meshes, 6 triangles.
  ASSERT_EQ(s.meshes.size(), 3u);
  ASSERT_EQ(s.triangles.size(), 6u);
  ExpectNear(s.triangles.V0(1), {0, 0, 0});
  ExpectNear(s.triangles.V1(1), {1, 1, 0});
  ExpectNear(s.triangles.V2(1), {0, 1, 0});
  ExpectNear(s.triangles.V2(2), {0.5f, 2, 0});
  ExpectNear(s.triangles.V2(5), {0, 1, 0});
}

TEST(ColladaLoader, AccessorStrideOffsetNormalsTexcoords) {
  Parts p;
  // Positions interleaved with a junk number (stride 4, offset 1); normals and texcoords with
  // their own index offsets in <p>.
  p.geometries =
      "<geometry id=\"g\"><mesh>\n"
      "<source id=\"g-p\"><float_array id=\"g-pa\" count=\"13\">9 0 0 0 9 2 0 0 9 0 2 0 "
      "9</float_array><technique_common><accessor source=\"#g-pa\" count=\"3\" stride=\"4\" "
      "offset=\"1\"><param name=\"X\"/><param name=\"Y\"/><param name=\"Z\"/></accessor>"
      "</technique_common></source>\n"
      "<source id=\"g-n\"><float_array id=\"g-na\" count=\"3\">0 0 2</float_array>"
      "<technique_common><accessor source=\"#g-na\" count=\"1\" stride=\"3\"><param name=\"X\"/>"
      "<param name=\"Y\"/><param name=\"Z\"/></accessor></technique_common></source>\n"
      "<source id=\"g-t\"><float_array id=\"g-ta\" count=\"6\">0 0 1 0 0 1</float_array>"
      "<technique_common><accessor source=\"#g-ta\" count=\"3\" stride=\"2\"><param name=\"S\"/>"
      "<param name=\"T\"/></accessor></technique_common></source>\n"
      "<vertices id=\"g-v\"><input semantic=\"POSITION\" source=\"#g-p\"/></vertices>\n"
      "<polylist count=\"1\"><input semantic=\"VERTEX\" source=\"#g-v\" offset=\"0\"/>"
      "<input semantic=\"NORMAL\" source=\"#g-n\" offset=\"1\"/>"
      "<input semantic=\"TEXCOORD\" source=\"#g-t\" offset=\"2\" set=\"0\"/>"
      "<vcount>3</vcount><p>0 0 0 1 0 1 2 0 2</p></polylist>\n"
      "</mesh></geometry>\n";
  p.nodes = "<node id=\"n\"><instance_geometry url=\"#g\"/></node>\n";
  const Scene s = LoadOk(p);
  ASSERT_EQ(s.triangles.size(), 1u);
  ExpectNear(s.triangles.V0(0), {0, 0, 0});
  ExpectNear(s.triangles.V1(0), {2, 0, 0});
  ExpectNear(s.triangles.V2(0), {0, 2, 0});
  ASSERT_EQ(s.meshes.has_normals[0], 1);
  ASSERT_EQ(s.meshes.has_uvs[0], 1);
  const uint32_t v1 = s.shading.vertex1[0];
  EXPECT_FLOAT_EQ(s.vertices.n_z[v1], 1.0f);  // normalised
  EXPECT_FLOAT_EQ(s.vertices.u[v1], 1.0f);
  EXPECT_FLOAT_EQ(s.vertices.v[v1], 0.0f);
}

TEST(ColladaLoader, NodeTransformsInOrderNestedAndInstanced) {
  Parts p;
  p.nodes =
      "<node id=\"a\"><translate>1 0 0</translate><scale>2 2 2</scale>"
      "<instance_geometry url=\"#tri\"/></node>\n"
      "<node id=\"b\"><translate>0 10 0</translate>"
      "<node id=\"c\"><rotate>0 0 1 90</rotate><instance_geometry url=\"#tri\"/></node></node>\n"
      "<node id=\"d\"><matrix>1 0 0 0 0 1 0 0 0 0 1 -3 0 0 0 1</matrix>"
      "<instance_node url=\"#c\"/></node>\n";
  const Scene s = LoadOk(p);
  ASSERT_EQ(s.triangles.size(), 3u);
  // translate then scale: (1,0,0) -> 1 + 2·1.
  ExpectNear(s.triangles.V1(0), {3, 0, 0});
  // the parent's translation after the child's rotation: (1,0,0) -> (0,1,0) -> (0,11,0).
  ExpectNear(s.triangles.V1(1), {0, 11, 0});
  // instance_node c under d: rotation, then z -3.
  ExpectNear(s.triangles.V1(2), {0, 1, -3});
}

TEST(ColladaLoader, UpAxisAndUnit) {
  Parts p;
  p.asset = "<asset><unit name=\"cm\" meter=\"0.01\"/><up_axis>Z_UP</up_axis></asset>\n";
  const Scene s = LoadOk(p);
  ASSERT_EQ(s.triangles.size(), 1u);
  // Z_UP: (x, y, z) -> (x, z, -y), then centimetres to metres.
  ExpectNear(s.triangles.V1(0), {0.01f, 0, 0});
  ExpectNear(s.triangles.V2(0), {0, 0, -0.01f});
}

TEST(ColladaLoader, CameraFieldOfViewAndCs184Placement) {
  Parts p;
  const Scene s = LoadOk(p);
  EXPECT_FLOAT_EQ(s.camera.fov_deg, 60.0f);
  EXPECT_EQ(s.camera.width, 480);
  EXPECT_EQ(s.camera.height, 240);
  EXPECT_TRUE(s.camera.keep_vertical_fov);
  EXPECT_FLOAT_EQ(s.camera.near_clip, 0.1f);
  EXPECT_FLOAT_EQ(s.camera.far_clip, 100.0f);
  // A new film size keeps the vertical field of view (CS184's -r).
  CameraDesc square = s.camera;
  ResizeFilm(&square, 300, 300);
  const double tan_v = std::tan(30.0 * kPi / 180.0) * 240.0 / 480.0;
  EXPECT_NEAR(std::tan(square.fov_deg * kPi / 360.0), tan_v, 1e-6);
  // CS184 aims along the file camera's direction (-z) at the centre of the geometry's bounds,
  // from 1.5 times their diagonal.
  const Vec3f centre{0.5f, 0.5f, 0};
  const Vec3f origin = s.camera.camera_to_world.ApplyPoint({0, 0, 0});
  ExpectNear(origin, centre + Vec3f{0, 0, 1.5f * std::sqrt(2.0f)}, 1e-4f);
  ExpectNear(s.camera.camera_to_world.ApplyVector({0, 0, 1}), {0, 0, -1});
  ExpectNear(s.camera.camera_to_world.ApplyVector({0, 1, 0}), {0, 1, 0});
  // yfov with aspect_ratio: the horizontal fov follows.
  Parts q;
  std::string doc = Document(q);
  doc.replace(doc.find("<xfov>60</xfov>"), 15, "<yfov>60</yfov>");
  StatusOr<Scene> y = LoadColladaSceneFromString(doc, "t.dae");
  ASSERT_TRUE(y.ok()) << y.status().message();
  EXPECT_NEAR(y->camera.fov_deg, 2 * std::atan(std::tan(kPi / 6) * 2) * 180 / kPi, 1e-3);
  // CS184 defaults.
  EXPECT_EQ(s.sampler.sample_count, 1u);
  EXPECT_EQ(s.integrator.type, IntegratorDesc::Type::kPathEms);
  EXPECT_EQ(s.integrator.max_depth, 1);
  EXPECT_EQ(s.integrator.light_samples, 1);
  EXPECT_FLOAT_EQ(s.camera.focus_distance, 4.7f);
}

TEST(ColladaLoader, Lights) {
  Parts p;
  p.lights =
      "<light id=\"pt\"><technique_common><point><color>1 2 3</color>"
      "<quadratic_attenuation>0.1</quadratic_attenuation></point></technique_common></light>\n"
      "<light id=\"amb\"><technique_common><ambient><color>0.5 0.5 0.5</color></ambient>"
      "</technique_common></light>\n"
      "<light id=\"dark\"><technique_common><ambient><color>0 0 0</color></ambient>"
      "</technique_common></light>\n"
      "<light id=\"area\"><technique_common><point><color>1 1 1</color></point>"
      "</technique_common><extra><technique profile=\"CGL\"><area><color>10 20 30</color>"
      "</area></technique></extra></light>\n";
  p.nodes +=
      "<node id=\"l1\"><translate>1 2 3</translate><instance_light url=\"#pt\"/></node>\n"
      "<node id=\"l2\"><instance_light url=\"#amb\"/><instance_light url=\"#dark\"/></node>\n"
      "<node id=\"l3\"><translate>0 4 0</translate><scale>0.6 0.8 1</scale>"
      "<instance_light url=\"#area\"/></node>\n";
  const Scene s = LoadOk(p);
  ASSERT_EQ(s.point_lights.size(), 1u);
  ExpectNear(s.point_lights.position[0], {1, 2, 3});
  EXPECT_FLOAT_EQ(s.point_lights.power[0].g, 2 * 4 * kPi);  // intensity 2 W/sr
  ASSERT_EQ(s.distant_disks.size(), 1u);  // the black ambient light adds nothing
  EXPECT_FLOAT_EQ(DistantDiskRadiance(s.distant_disks, 0, {0, 1, 0}).r, 0.5f);
  EXPECT_FLOAT_EQ(DistantDiskRadiance(s.distant_disks, 0, {0, -1, 0}).r, 0.0f);
  ASSERT_EQ(s.area_lights.size(), 1u);
  EXPECT_EQ(s.area_lights.radiance[0].b, 30.0f);
  EXPECT_NEAR(s.area_lights.area[0], 0.6f * 0.8f, 1e-6f);
  const uint32_t mesh = s.area_lights.mesh[0];
  const uint32_t t = s.meshes.first_triangle[mesh];
  const Vec3f n = Cross(s.triangles.V1(t) - s.triangles.V0(t), s.triangles.V2(t) - s.triangles.V0(t));
  EXPECT_LT(n.z, 0.0f);  // faces the light's local -z
  EXPECT_EQ(s.emitters.size(), 3u);
}

TEST(ColladaLoader, DirectionalAndSpotLights) {
  Parts p;
  p.lights =
      "<light id=\"sun\"><technique_common><directional><color>1 2 3</color></directional>"
      "</technique_common></light>\n"
      "<light id=\"spot\"><technique_common><spot><color>4 5 6</color>"
      "<constant_attenuation>1</constant_attenuation><falloff_angle>60</falloff_angle>"
      "<falloff_exponent>2.5</falloff_exponent></spot></technique_common></light>\n"
      "<light id=\"wide\"><technique_common><spot><color>1 1 1</color></spot>"
      "</technique_common></light>\n";
  // The sun's -z turned to (0, -1, 0) and scaled (the direction is normalised); the spot at
  // (1, 2, 3) with -z turned about y by 90° to (-1, 0, 0); the default spot shines down -z.
  p.nodes +=
      "<node id=\"l1\"><rotate>1 0 0 -90</rotate><scale>3 3 3</scale>"
      "<instance_light url=\"#sun\"/></node>\n"
      "<node id=\"l2\"><translate>1 2 3</translate><rotate>0 1 0 90</rotate>"
      "<instance_light url=\"#spot\"/></node>\n"
      "<node id=\"l3\"><instance_light url=\"#wide\"/></node>\n";
  const Scene s = LoadOk(p);
  ASSERT_EQ(s.directional_lights.size(), 1u);
  ExpectNear(s.directional_lights.direction[0], {0, -1, 0});
  EXPECT_EQ(s.directional_lights.radiance[0].b, 3.0f);
  ASSERT_EQ(s.spot_lights.size(), 2u);
  ExpectNear(s.spot_lights.position[0], {1, 2, 3});
  ExpectNear(s.spot_lights.axis[0], {-1, 0, 0});
  EXPECT_EQ(s.spot_lights.intensity[0].g, 5.0f);
  EXPECT_NEAR(s.spot_lights.cos_half_angle[0], std::sqrt(3.0f) / 2, 1e-7f);  // half of 60°
  EXPECT_EQ(s.spot_lights.exponent[0], 2.5f);
  ExpectNear(s.spot_lights.axis[1], {0, 0, -1});
  EXPECT_EQ(s.spot_lights.cos_half_angle[1], 0.0f);  // COLLADA's defaults: 180°, exponent 0
  EXPECT_EQ(s.spot_lights.exponent[1], 0.0f);
  ASSERT_EQ(s.emitters.size(), 3u);
  EXPECT_EQ(s.emitters[0].tag(), EmitterTag::kDirectional);
  EXPECT_EQ(s.emitters[1].tag(), EmitterTag::kSpot);
  EXPECT_EQ(s.emitters[2].index(), 1u);
}

// Effects bound to one triangle each through bind_material.
Scene LoadWithEffect(const std::string& cgl_or_common) {
  Parts p;
  p.effects = "<effect id=\"e\">" + cgl_or_common + "</effect>\n";
  p.materials = "<material id=\"mat\"><instance_effect url=\"#e\"/></material>\n";
  p.nodes = "<node id=\"n\"><instance_geometry url=\"#tri\"><bind_material><technique_common>"
            "<instance_material symbol=\"m\" target=\"#mat\"/></technique_common>"
            "</bind_material></instance_geometry></node>\n";
  return LoadOk(p);
}

std::string Cgl(const std::string& body) {
  return "<extra><technique profile=\"CGL\">" + body + "</technique></extra>";
}

TEST(ColladaLoader, EffectsMapToPtlabModels) {
  Scene s = LoadWithEffect(Cgl("<diffuse><reflectance>0.1 0.2 0.3</reflectance></diffuse>"));
  ASSERT_EQ(s.meshes.material[0].tag(), MaterialTag::kDiffuse);
  EXPECT_FLOAT_EQ(s.materials.diffuse.Albedo(s.meshes.material[0].index()).g, 0.2f);

  s = LoadWithEffect(Cgl("<mirror><reflectance>1 1 1</reflectance></mirror>"));
  EXPECT_EQ(s.meshes.material[0].tag(), MaterialTag::kMirror);
  EXPECT_EQ(s.materials.mirror.Reflectance(s.meshes.material[0].index()).g, 1.0f);
  s = LoadWithEffect(Cgl("<mirror><reflectance>0.9 0.5 0.25</reflectance></mirror>"));
  ASSERT_EQ(s.meshes.material[0].tag(), MaterialTag::kMirror);
  EXPECT_EQ(s.materials.mirror.Reflectance(s.meshes.material[0].index()).r, 0.9f);
  EXPECT_EQ(s.materials.mirror.Reflectance(s.meshes.material[0].index()).g, 0.5f);
  EXPECT_EQ(s.materials.mirror.Reflectance(s.meshes.material[0].index()).b, 0.25f);

  s = LoadWithEffect(Cgl("<glass><reflectance>1 1 1</reflectance><transmittance>1 1 1"
                         "</transmittance><roughness>0</roughness><ior>1.45</ior></glass>"));
  ASSERT_EQ(s.meshes.material[0].tag(), MaterialTag::kDielectric);
  EXPECT_FLOAT_EQ(s.materials.dielectric.int_ior[0], 1.45f);
  EXPECT_FLOAT_EQ(s.materials.dielectric.ext_ior[0], 1.0f);
  EXPECT_EQ(s.materials.dielectric.Flags(0), kDielectricSchlick | kDielectricScaleRadiance);
  EXPECT_FALSE(s.materials.dielectric.tinted());

  s = LoadWithEffect(Cgl("<glass><reflectance>1 1 1</reflectance><transmittance>1 0.75 0.5"
                         "</transmittance><ior>1.45</ior></glass>"));
  ASSERT_TRUE(s.materials.dielectric.tinted());
  EXPECT_FLOAT_EQ(s.materials.dielectric.Transmittance(0).b, 0.5f);

  s = LoadWithEffect(Cgl("<refraction><transmittance>1 1 1</transmittance><roughness>0"
                         "</roughness><ior>1.45</ior></refraction>"));
  EXPECT_EQ(s.materials.dielectric.Flags(0),
            kDielectricSchlick | kDielectricScaleRadiance | kDielectricRefractOnly);

  s = LoadWithEffect(Cgl("<microfacet><alpha>0.25</alpha><eta>0.1 0.2 0.3</eta>"
                         "<k>4 5 6</k></microfacet>"));
  ASSERT_EQ(s.meshes.material[0].tag(), MaterialTag::kConductor);
  EXPECT_FLOAT_EQ(s.materials.conductor.alpha[0], 0.25f);
  EXPECT_FLOAT_EQ(s.materials.conductor.eta_b[0], 0.3f);
  EXPECT_FLOAT_EQ(s.materials.conductor.k_r[0], 4.0f);

  s = LoadWithEffect(Cgl("<emission><radiance>5 6 7</radiance></emission>"));
  ASSERT_EQ(s.area_lights.size(), 1u);
  EXPECT_EQ(s.area_lights.radiance[0].g, 6.0f);
  EXPECT_EQ(s.meshes.emitter[0].tag(), EmitterTag::kArea);

  // No CGL technique: the common profile's diffuse color.
  s = LoadWithEffect(
      "<profile_COMMON><technique sid=\"common\"><phong><emission><color>0 0 0 1</color>"
      "</emission><diffuse><color sid=\"diffuse\">0.6 0.2 0.2 1</color></diffuse><specular>"
      "<color>0.5 0.5 0.5 1</color></specular><shininess><float>50</float></shininess>"
      "</phong></technique></profile_COMMON>");
  ASSERT_EQ(s.meshes.material[0].tag(), MaterialTag::kDiffuse);
  EXPECT_FLOAT_EQ(s.materials.diffuse.Albedo(0).r, 0.6f);
}

TEST(ColladaLoader, CglSphere) {
  Parts p;
  p.geometries += "<geometry id=\"sph\"><extra><technique profile=\"CGL\"><sphere><radius>.5"
                  "</radius></sphere></technique></extra></geometry>\n";
  p.effects = "<effect id=\"glow\">" +
              std::string(
                  "<extra><technique profile=\"CGL\"><emission>"
                  "<radiance>1 1 1</radiance></emission></technique></extra>") +
              "</effect>\n";
  p.materials = "<material id=\"lamp\"><instance_effect url=\"#glow\"/></material>\n";
  // Translated, and rotated and scaled uniformly: analytic spheres.
  p.nodes =
      "<node id=\"a\"><translate>0 1 0</translate><instance_geometry url=\"#sph\"/>"
      "</node>\n<node id=\"b\"><translate>5 0 0</translate><rotate>1 1 0 30</rotate>"
      "<scale>2 2 2</scale><instance_geometry url=\"#sph\"/></node>\n";
  Scene s = LoadOk(p);
  ASSERT_EQ(s.spheres.size(), 2u);
  EXPECT_EQ(s.triangles.size(), 0u);
  ExpectNear(s.spheres.Center(0), {0, 1, 0});
  EXPECT_EQ(s.spheres.radius[0], 0.5f);
  EXPECT_EQ(s.spheres.material[0].tag(), MaterialTag::kDiffuse);  // CS184's default
  ExpectNear(s.spheres.Center(1), {5, 0, 0});
  EXPECT_NEAR(s.spheres.radius[1], 1.0f, 1e-6f);
  // A non-uniform scale (an ellipsoid) and an emissive sphere stay UV-sphere meshes.
  p.nodes =
      "<node id=\"a\"><translate>0 1 0</translate><scale>1 2 1</scale>"
      "<instance_geometry url=\"#sph\"/></node>\n"
      "<node id=\"b\"><instance_geometry url=\"#sph\"><bind_material><technique_common>"
      "<instance_material symbol=\"x\" target=\"#lamp\"/></technique_common>"
      "</bind_material></instance_geometry></node>\n";
  s = LoadOk(p);
  EXPECT_EQ(s.spheres.size(), 0u);
  EXPECT_EQ(s.triangles.size(), size_t(2 * 2 * kSphereSegments * (kSphereRings - 1)));
  float max_y = -1;
  for (size_t t = 0; t < s.triangles.size(); ++t) max_y = std::max(max_y, s.triangles.V0(t).y);
  EXPECT_FLOAT_EQ(max_y, 2.0f);
  ASSERT_EQ(s.area_lights.size(), 1u);
}

TEST(ColladaLoader, MalformedFilesNameFileAndLine) {
  {
    Parts p;
    p.nodes = "<node id=\"n\"><instance_geometry url=\"#nothere\"/></node>\n";
    ExpectError(p, "#nothere", {"names no element", "<geometry>"});
  }
  {
    Parts p;
    p.geometries = kTriangle;
    p.geometries.replace(p.geometries.find("stride=\"3\""), 10, "stride=\"2\"");
    ExpectError(p, "stride=\"2\"", {"stride", "expected stride >= the number of params"});
  }
  {
    Parts p;
    p.geometries.replace(p.geometries.find("count=\"3\" stride"), 9, "count=\"4\"");
    ExpectError(p, "count=\"4\"", {"reaches past"});
  }
  {
    // A triangle count far beyond its index list (fuzzing found one asking for 4 GiB).
    Parts p;
    p.geometries.replace(p.geometries.find("count=\"1\""), 9, "count=\"1101986441\"");
    ExpectError(p, "<triangles", {"has 3 indices", "1101986441 polygons", "need 3305959323"});
  }
  {
    Parts p;
    p.geometries.replace(p.geometries.find("<p>0 1 2</p>"), 12, "<p>0 1 7</p>");
    ExpectError(p, "<triangles", {"index 7", "out of range"});
  }
  {
    Parts p;
    p.geometries.replace(p.geometries.find("0 0 0 1 0 0 0 1 0"), 17, "0 0 0 1 0 0 0 x 0");
    ExpectError(p, "<float_array", {"'x'", "not a number"});
  }
  {
    Parts p;
    p.geometries.replace(p.geometries.find("count=\"9\""), 9, "count=\"8\"");
    ExpectError(p, "<float_array", {"count=\"8\"", "holds 9"});
  }
  {
    Parts p;
    p.nodes = "<node id=\"a\"><node id=\"b\"><instance_node url=\"#a\"/></node></node>\n";
    ExpectError(p, "<node id=\"a\"", {"cycle"});
  }
  for (const char* falloff : {"<falloff_exponent>-1</falloff_exponent>",
                              "<falloff_exponent>2e4</falloff_exponent>",
                              "<falloff_angle>0</falloff_angle>",
                              "<falloff_angle>180.5</falloff_angle>",
                              "<falloff_angle>-30</falloff_angle>"}) {
    Parts p;
    p.lights = std::string("<light id=\"sp\"><technique_common><spot><color>1 1 1</color>\n") +
               falloff + "</spot></technique_common></light>";
    const std::string element = std::string(falloff).substr(0, std::string(falloff).find('>') + 1);
    ExpectError(p, element, {element.substr(1, element.size() - 2), "out of range"});
  }
  // Light bodies (and a node instancing them) with the element the error names.
  struct BadLight {
    const char* body;
    const char* node;
    const char* marker;
    const char* word;
  };
  for (const BadLight& bad : std::vector<BadLight>{
           {"<spot><color>1 1 1</color>\n<falloff_angle>wide</falloff_angle></spot>", "",
            "<falloff_angle>", "wide"},
           {"<directional><color>1 x 1</color></directional>", "", "<color>1 x", "x"},
           {"<directional><color>1 1 1</color><falloff_angle>30</falloff_angle></directional>",
            "", "<falloff_angle>", "falloff_angle"},
           {"<directional><color>1 1 1</color></directional>",
            "<node id=\"flat\"><scale>1 1 0</scale><instance_light url=\"#l\"/></node>\n",
            "<instance_light", "no direction"}}) {
    Parts p;
    p.lights = std::string("<light id=\"l\"><technique_common>") + bad.body +
               "</technique_common></light>";
    p.nodes += bad.node;
    ExpectError(p, bad.marker, {bad.word});
  }
  {
    Parts p;
    p.effects = "<effect id=\"e\">" + Cgl("\n<mirror><reflectance>1 1.5 1</reflectance></mirror>") +
                "</effect>";
    ExpectError(p, "<mirror>", {"mirror reflectance above 1"});
  }
  {
    Parts p;
    p.geometries.replace(p.geometries.find("<p>0 1 2</p>"), 12, "<p>0 1</p>");
    ExpectError(p, "<triangles", {"has 2 indices", "need 3"});
  }
  {
    Parts p;
    p.geometries.replace(p.geometries.find("<triangles"), 10, "<lines");
    p.geometries.replace(p.geometries.find("</triangles>"), 12, "</lines>");
    ExpectError(p, "<lines", {"not supported yet: <lines>"});
  }
  {
    Parts p;
    p.nodes = "<node id=\"n\"><lookat>0 0 0 1 0 0 0 1 0</lookat></node>\n";
    ExpectError(p, "<lookat>", {"not supported yet: <lookat>"});
  }
  {
    Parts p;
    p.nodes = "<node id=\"n\"><instance_geometry url=\"#tri\"><bind_material><technique_common>"
              "<instance_material symbol=\"other\" target=\"#nomat\"/></technique_common>"
              "</bind_material></instance_geometry></node>\n";
    ExpectError(p, "<instance_material", {"#nomat", "names no element"});
  }
  {
    Parts p;
    p.materials = "<material id=\"mat\"><instance_effect url=\"#tri\"/></material>\n";
    ExpectError(p, "<instance_effect", {"names a <geometry>", "expected a <effect>"});
  }
  {
    Parts p;
    p.camera_node = "";
    ExpectError(p, "<visual_scene", {"no camera"});
  }
  {
    StatusOr<Scene> s = LoadColladaSceneFromString("<scene/>", "t.dae");
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.status().message().find("t.dae:1:1:"), std::string::npos) << s.status().message();
    EXPECT_NE(s.status().message().find("expected <COLLADA>"), std::string::npos);
  }
}

TEST(ColladaLoader, FormatByExtensionOrRoot) {
  EXPECT_EQ(SceneFormatOf("a/b/scene.DAE"), SceneFormat::kCollada);
  EXPECT_EQ(SceneFormatOf("scene.xml"), SceneFormat::kNoriXml);
}

const std::string kSky = test_data::Path("cs184/dae/sky/");

const char* const kCs184Scenes[] = {
    "CBbunny_microfacet_cu.dae", "CBempty.dae",           "CBgems.dae",
    "CBspheres.dae",             "CBspheres_lambertian.dae", "CBspheres_microfacet_al_ag.dae",
    "CBspheres_refract.dae",     "bunny_microfacet_cu_unlit.dae", "bunny_unlit.dae"};

TEST(ColladaLoader, EveryCs184SceneLoads) {
  PTLAB_REQUIRE_DATA(kSky);
  for (const char* name : kCs184Scenes) {
    SCOPED_TRACE(name);
    StatusOr<Scene> s = LoadSceneFile(kSky + name);
    ASSERT_TRUE(s.ok()) << s.status().message();
    EXPECT_GT(s->triangles.size(), 0u);
    const bool unlit = std::string(name).find("unlit") != std::string::npos;
    const bool point_only = std::string(name) == "CBempty.dae";
    EXPECT_EQ(s->emitters.size(), unlit ? 0u : 1u);
    EXPECT_EQ(s->area_lights.size(), unlit || point_only ? 0u : 1u);
    EXPECT_EQ(s->point_lights.size(), point_only ? 1u : 0u);
    // Only CBgems has the 15-number camera matrix that CS184 reads leniently.
    EXPECT_EQ(s->load_warnings.size(), std::string(name) == "CBgems.dae" ? 1u : 0u);
  }
}

// The η and k of the CGL <microfacet> elements reach the conductor table as written.
TEST(ColladaLoader, MicrofacetEtaKReachTheConductorAsWritten) {
  PTLAB_REQUIRE_DATA(kSky);
  struct Row {
    float alpha, eta[3], k[3];
  };
  const auto expect_rows = [](const Scene& s, const std::vector<Row>& rows) {
    const ConductorTable& c = s.materials.conductor;
    ASSERT_EQ(c.size(), rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
      // Rows are made in the order the materials are first instanced; match by alpha.
      size_t j = 0;
      while (j < c.size() && c.alpha[j] != rows[i].alpha) ++j;
      ASSERT_LT(j, c.size()) << "alpha " << rows[i].alpha;
      EXPECT_EQ(c.eta_r[j], rows[i].eta[0]);
      EXPECT_EQ(c.eta_g[j], rows[i].eta[1]);
      EXPECT_EQ(c.eta_b[j], rows[i].eta[2]);
      EXPECT_EQ(c.k_r[j], rows[i].k[0]);
      EXPECT_EQ(c.k_g[j], rows[i].k[1]);
      EXPECT_EQ(c.k_b[j], rows[i].k[2]);
    }
  };
  StatusOr<Scene> al_ag = LoadSceneFile(kSky + "CBspheres_microfacet_al_ag.dae");
  ASSERT_TRUE(al_ag.ok()) << al_ag.status().message();
  expect_rows(*al_ag, {{0.25f, {0.059193f, 0.059881f, 0.047366f}, {4.1283f, 3.5892f, 2.8132f}},
                       {0.025f, {1.3352f, 1.0109f, 0.68955f}, {7.3398f, 6.6157f, 5.6471f}}});
  StatusOr<Scene> cu = LoadSceneFile(kSky + "CBbunny_microfacet_cu.dae");
  ASSERT_TRUE(cu.ok()) << cu.status().message();
  expect_rows(*cu, {{0.05f, {0.33228f, 1.0162f, 1.2474f}, {3.1646f, 2.5785f, 2.4603f}}});
}

}  // namespace
}  // namespace ptlab
