// The render driver: thread-count independence, interruption, and the integrators' basics.
#include "engine/render/render.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <gtest/gtest.h>

#include "engine/bvh/bvh.h"
#include "engine/io/collada_loader.h"
#include "engine/io/xml_loader.h"
#include "tests/engine/render/packet_render_for_test.h"

namespace ptlab {
namespace {

// A closed box (six inward-facing walls) with an emitting square under the ceiling and a
// cube on the floor; the camera is inside. Our own scene, in our XML dialect.
std::string BoxScene(const char* integrator, int spp) {
  const char* walls[6] = {
      R"(<rotate axis="1,0,0" angle="-90"/><translate value="0,-1,0"/>)",  // floor
      R"(<rotate axis="1,0,0" angle="90"/><translate value="0,1,0"/>)",    // ceiling
      R"(<translate value="0,0,-1"/>)",                                      // back
      R"(<rotate axis="0,1,0" angle="180"/><translate value="0,0,1"/>)",    // front
      R"(<rotate axis="0,1,0" angle="90"/><translate value="-1,0,0"/>)",    // left
      R"(<rotate axis="0,1,0" angle="-90"/><translate value="1,0,0"/>)"};   // right
  std::string xml = std::string(R"(<scene>
  <integrator type=")") + integrator + R"("/>
  <sampler type="independent"><integer name="sampleCount" value=")" + std::to_string(spp) +
                    R"("/></sampler>
  <camera type="perspective">
    <transform name="toWorld"><lookat origin="0,0,0.95" target="0,0,0" up="0,1,0"/></transform>
    <float name="fov" value="70"/>
    <integer name="width" value="48"/><integer name="height" value="40"/>
  </camera>
  <shape type="cube">
    <transform name="toWorld"><scale value="0.3,0.5,0.3"/><rotate axis="0,1,0" angle="25"/>
      <translate value="-0.3,-0.5,-0.2"/></transform>
  </shape>
  <shape type="rectangle">
    <transform name="toWorld"><scale value="0.3,0.3,1"/><rotate axis="1,0,0" angle="90"/>
      <translate value="0,0.98,0"/></transform>
    <emitter type="area"><color name="radiance" value="8,8,8"/></emitter>
  </shape>
)";
  for (const char* wall : walls)
    xml += std::string(R"(  <shape type="rectangle"><transform name="toWorld">)") + wall +
           R"(</transform><bsdf type="diffuse"><color name="albedo" value="0.6,0.5,0.4"/></bsdf></shape>
)";
  return xml + "</scene>";
}

Scene LoadOrDie(const std::string& xml) {
  StatusOr<Scene> scene = LoadSceneFromString(xml, ".", "box.xml");
  EXPECT_TRUE(scene.ok()) << scene.status().message();
  return scene.ok() ? std::move(*scene) : Scene{};
}

// A diffuse floor (albedo 0.5) under a point light 2 units above it, seen straight down through
// a narrow one-pixel camera: L = albedo/π · power/(4π r²) · cos θ = 0.5/π · 16π²/(16π) = 0.5.
// Every integrator that samples emitters sees it; BSDF sampling alone cannot (a delta light).
TEST(Render, PointLightFollowsTheInverseSquareLaw) {
  const auto xml = [](const char* integrator) {
    const float p = 16.0f * kPi * kPi;
    return std::string(R"(<scene><integrator type=")") + integrator + R"("/>
  <camera type="perspective">
    <transform name="toWorld"><lookat origin="0,1,0" target="0,0,0" up="0,0,1"/></transform>
    <float name="fov" value="0.01"/><integer name="width" value="1"/><integer name="height" value="1"/>
  </camera>
  <shape type="rectangle">
    <transform name="toWorld"><scale value="10,10,1"/><rotate axis="1,0,0" angle="-90"/></transform>
    <bsdf type="diffuse"><color name="albedo" value="0.5,0.5,0.5"/></bsdf>
  </shape>
  <emitter type="point"><point name="position" value="0,2,0"/>
    <color name="power" value=")" + std::to_string(p) + "," + std::to_string(2 * p) + "," +
           std::to_string(p) + R"("/></emitter>
</scene>)";
  };
  for (const char* integrator : {"direct_ems", "direct_mis", "whitted", "path_ems", "path_mis"}) {
    SCOPED_TRACE(integrator);
    const Scene scene = LoadOrDie(xml(integrator));
    ASSERT_EQ(scene.point_lights.size(), 1u);
    const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
    RenderOptions options;
    options.spp = 16;
    const RenderResult r = Render(scene, bvh, options);
    const Color3f c = r.image.At(0, 0);
    EXPECT_NEAR(c.r, 0.5f, 1e-4f);
    EXPECT_NEAR(c.g, 1.0f, 2e-4f);
    EXPECT_NEAR(c.b, 0.5f, 1e-4f);
    // The wavefront gives the same bits here: the SIMD diffuse sample's weight is the albedo
    // exactly and no bounced ray finds anything.
    const Color3f p = RenderWithPackets(scene, options).image.At(0, 0);
    EXPECT_EQ(p.r, c.r);
    EXPECT_EQ(p.g, c.g);
    EXPECT_EQ(p.b, c.b);
  }
  const Scene mats = LoadOrDie(xml("direct_mats"));
  const Bvh bvh = BuildBvh(mats.triangles);
  RenderOptions options;
  options.spp = 16;
  EXPECT_EQ(Render(mats, bvh, options).image.At(0, 0).g, 0.0f);
}

// A CS184-style scene of our own: a diffuse floor (albedo 0.5, the plane y = 0 facing +y,
// 20 × 20) and the COLLADA light `light` instanced by a node with `transform`.
Scene FloorUnderColladaLight(const std::string& light, const std::string& transform) {
  const std::string dae = R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<library_cameras><camera id="cam"><optics><technique_common><perspective><yfov>30</yfov>
  <aspect_ratio>1</aspect_ratio><znear>0.01</znear><zfar>100</zfar></perspective>
  </technique_common></optics></camera></library_cameras>
<library_lights><light id="l"><technique_common>)" + light + R"(</technique_common></light>
</library_lights>
<library_effects><effect id="e"><extra><technique profile="CGL"><diffuse>
  <reflectance>0.5 0.5 0.5</reflectance></diffuse></technique></extra></effect></library_effects>
<library_materials><material id="m"><instance_effect url="#e"/></material></library_materials>
<library_geometries><geometry id="floor"><mesh>
  <source id="fp"><float_array id="fpa" count="12">-10 0 -10 10 0 -10 10 0 10 -10 0 10
  </float_array><technique_common><accessor source="#fpa" count="4" stride="3"><param name="X"/>
  <param name="Y"/><param name="Z"/></accessor></technique_common></source>
  <vertices id="fv"><input semantic="POSITION" source="#fp"/></vertices>
  <triangles material="s" count="2"><input semantic="VERTEX" source="#fv" offset="0"/>
  <p>0 3 2 0 2 1</p></triangles></mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="vs">
  <node id="c"><translate>0 1 5</translate><instance_camera url="#cam"/></node>
  <node id="f"><instance_geometry url="#floor"><bind_material><technique_common>
    <instance_material symbol="s" target="#m"/></technique_common></bind_material>
  </instance_geometry></node>
  <node id="ln">)" + transform + R"(<instance_light url="#l"/></node>
</visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#vs"/></scene></COLLADA>
)";
  StatusOr<Scene> scene = LoadColladaSceneFromString(dae, "floor.dae");
  EXPECT_TRUE(scene.ok()) << scene.status().message();
  return scene.ok() ? std::move(*scene) : Scene{};
}

// Outgoing radiance of the floor at (x, 0, z), seen straight down through a one-pixel camera of
// 0.01° (the pixel covers a spot 2e-4 wide), by the scalar loop; the wavefront must give the
// same bits. A delta light lights the spot from one direction, so the estimate has no variance
// beyond the spot's extent: the expected values below hold to float rounding.
Color3f FloorRadianceAt(Scene scene, float x, float z) {
  scene.camera.camera_to_world =
      Transform::Translate({x, 1, z}) * Transform::Rotate({1, 0, 0}, 90);  // +z to -y
  scene.camera.fov_deg = 0.01f;
  scene.camera.width = scene.camera.height = 1;
  const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
  RenderOptions options;
  options.spp = 16;
  const Color3f c = Render(scene, bvh, options).image.At(0, 0);
  const Color3f p = RenderWithPackets(scene, options).image.At(0, 0);
  EXPECT_EQ(p.r, c.r);
  EXPECT_EQ(p.g, c.g);
  EXPECT_EQ(p.b, c.b);
  return c;
}

// A Lambertian surface under a directional light of radiance E at incidence θ sends out
// albedo/π · E cos θ: 0.5/π · 2π (1, 2, 3) = (1, 2, 3) head-on, half that at θ = 60°.
TEST(Render, DirectionalLightGivesTheLambertianRadiance) {
  const std::string sun =
      "<directional><color>6.2831853 12.566371 18.849556</color></directional>";
  // The light's -z turned to -y (head-on), then tilted 60° about z.
  const Scene head_on = FloorUnderColladaLight(sun, "<rotate>1 0 0 -90</rotate>");
  ASSERT_EQ(head_on.directional_lights.size(), 1u);
  for (const float x : {0.0f, 3.0f, -7.5f}) {
    const Color3f c = FloorRadianceAt(head_on, x, 0.25f);
    EXPECT_NEAR(c.r, 1.0f, 1e-5f);
    EXPECT_NEAR(c.g, 2.0f, 2e-5f);
    EXPECT_NEAR(c.b, 3.0f, 3e-5f);
  }
  // Every integrator that samples emitters sees it, MIS or not (a delta light gets no MIS
  // weight: BSDF sampling cannot reach it); BSDF sampling alone sees nothing.
  Scene tilted =
      FloorUnderColladaLight(sun, "<rotate>0 0 1 60</rotate><rotate>1 0 0 -90</rotate>");
  using T = IntegratorDesc::Type;
  for (const T type : {T::kDirectEms, T::kDirectMis, T::kWhitted, T::kPathEms, T::kPathMis}) {
    SCOPED_TRACE(IntegratorTypeName(type));
    tilted.integrator.type = type;
    tilted.integrator.max_depth = -1;
    const Color3f c = FloorRadianceAt(tilted, 1.0f, -2.0f);
    EXPECT_NEAR(c.r, 0.5f, 1e-5f);
    EXPECT_NEAR(c.b, 1.5f, 2e-5f);
  }
  tilted.integrator.type = T::kDirectMats;
  EXPECT_EQ(FloorRadianceAt(tilted, 1.0f, -2.0f).g, 0.0f);
  // From below the horizon the floor gets nothing.
  const Scene below = FloorUnderColladaLight(sun, "<rotate>1 0 0 90</rotate>");
  EXPECT_EQ(FloorRadianceAt(below, 0.0f, 0.0f).g, 0.0f);
}

// A spot 2 above the floor shining down (full cone 90°, exponent 2, intensity I = 4π): the floor
// at distance x from its foot sees θ = atan(x/2), r² = 4 + x², and sends out
// albedo/π · I cos²θ / r² · cos θ = 2 cos³θ / r²; nothing outside the 45° half angle.
TEST(Render, SpotLightFollowsItsFalloffAndCone) {
  const Scene scene = FloorUnderColladaLight(
      "<spot><color>12.566371 12.566371 12.566371</color><falloff_angle>90</falloff_angle>"
      "<falloff_exponent>2</falloff_exponent></spot>",
      "<translate>0 2 0</translate><rotate>1 0 0 -90</rotate>");
  ASSERT_EQ(scene.spot_lights.size(), 1u);
  for (const float x : {0.0f, 1.0f, 1.9f}) {
    SCOPED_TRACE(x);
    const double r2 = 4.0 + double(x) * x, cos_theta = 2.0 / std::sqrt(r2);
    const double expected = 2.0 * std::pow(cos_theta, 3.0) / r2;
    const Color3f c = FloorRadianceAt(scene, x, 0.0f);
    EXPECT_NEAR(c.r, expected, 1e-5 * expected);
    EXPECT_EQ(c.g, c.r);
  }
  // Past the cone's edge at x = 2 (θ = 45°).
  EXPECT_EQ(FloorRadianceAt(scene, 2.1f, 0.0f).r, 0.0f);
  EXPECT_EQ(FloorRadianceAt(scene, 0.0f, -5.0f).r, 0.0f);
  // Exponent 0 and the full 180° cone: a point light of intensity I (0.5 on the axis).
  const Scene wide = FloorUnderColladaLight(
      "<spot><color>12.566371 12.566371 12.566371</color></spot>",
      "<translate>0 2 0</translate><rotate>1 0 0 -90</rotate>");
  EXPECT_NEAR(FloorRadianceAt(wide, 0.0f, 0.0f).r, 0.5f, 5e-6f);
  const double far_r2 = 4.0 + 36.0, far_cos = 2.0 / std::sqrt(far_r2);
  EXPECT_NEAR(FloorRadianceAt(wide, 6.0f, 0.0f).r, 2.0 * far_cos / far_r2, 1e-6);
}

TEST(Render, SameImageForAnyThreadCount) {
  for (const char* integrator : {"direct_mis", "whitted"}) {
    const Scene scene = LoadOrDie(BoxScene(integrator, 5));
    const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
    RenderOptions one;
    one.spp = 5;
    one.seed = 7;
    one.threads = 1;
    RenderOptions two = one;
    two.threads = 2;
    RenderOptions three = one;
    three.threads = 3;
    const Image a = Render(scene, bvh, one).image;
    const Image b = Render(scene, bvh, two).image;
    const Image c = Render(scene, bvh, three).image;
    EXPECT_EQ(a.rgb, b.rgb) << integrator;
    EXPECT_EQ(a.rgb, c.rgb) << integrator;
    double sum = 0;
    for (float v : a.rgb) sum += v;
    EXPECT_GT(sum, 0.0) << integrator;
    // A different seed gives a different (noisy) image.
    RenderOptions other = one;
    other.seed = 8;
    EXPECT_NE(Render(scene, bvh, other).image.rgb, a.rgb);
  }
}

// The render's memory: the film and one block per tile (tile plus the filter's border) are
// 4 floats a pixel, exactly; the wavefronts exist on the packet path only; a workspace that
// renders a tile it has rendered before allocates nothing more.
TEST(Render, MemoryOfFilmBlocksAndWavefronts) {
  const Scene scene = LoadOrDie(BoxScene("path_mis", 4));
  const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
  RenderOptions options;
  options.spp = 4;
  const int w = scene.camera.width, h = scene.camera.height;  // 48 x 40: tiles 32, 16 x 32, 8
  const int border = int(std::ceil(scene.filter.radius));
  size_t pixels = size_t(w) * size_t(h);
  for (int y = 0; y < h; y += 32)
    for (int x = 0; x < w; x += 32)
      pixels += size_t(std::min(32, w - x) + 2 * border) * size_t(std::min(32, h - y) + 2 * border);
  const RenderResult scalar = Render(scene, bvh, options);
  EXPECT_EQ(scalar.memory.film, pixels * 4 * sizeof(float));
  EXPECT_EQ(scalar.memory.wavefront, 0u);
  for (int threads : {1, 2}) {
    options.threads = threads;
    const RenderResult packets = RenderWithPackets(scene, options);
    EXPECT_EQ(packets.memory.film, pixels * 4 * sizeof(float)) << threads;
    // At least the path state of one wave: a sampler and a radiance sum per path.
    const size_t paths = size_t(std::min(w, 32)) * 4 * options.spp;
    EXPECT_GT(packets.memory.wavefront, paths * (sizeof(PathSampler) + sizeof(Color3f))) << threads;
  }

  const RenderSetup setup(scene, KernelChoice::kSimd);
  const WavefrontKernels& kernels = setup.kernels();
  const Camera camera(scene.camera);
  const PixelFilter filter(scene.filter);
  const RenderContext ctx{scene, bvh};
  WavefrontWorkspace workspace;
  EXPECT_EQ(workspace.Bytes(), 0u);
  size_t bytes = 0;
  for (int round = 0; round < 2; ++round) {
    FilmBlock block(-border, -border, 32 + 2 * border, 32 + 2 * border);
    TileSampleStats stats;
    RenderTilePacket8(ctx, kernels, camera, filter, 0, 0, 32, 32, 0, 4, 3, &block, &stats, nullptr,
                      &workspace);
    if (round == 0) bytes = workspace.Bytes();
  }
  EXPECT_GT(bytes, 0u);
  EXPECT_EQ(workspace.Bytes(), bytes);
}

TEST(Render, CancelledBeforeStartKeepsNothing) {
  const Scene scene = LoadOrDie(BoxScene("direct_ems", 4));
  const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
  std::atomic<bool> cancel{true};
  RenderOptions options;
  options.spp = 4;
  options.cancel = &cancel;
  const RenderResult r = Render(scene, bvh, options);
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.spp_done, 0u);
}

TEST(Render, InterruptKeepsCompletedPasses) {
  const Scene scene = LoadOrDie(BoxScene("direct_ems", 64));
  const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
  std::atomic<bool> cancel{false};
  RenderOptions options;
  options.spp = 64;  // 4 passes of 16
  options.threads = 1;
  options.cancel = &cancel;
  // Cancel once the first pass is done; when the flag is seen depends on timing, but the
  // result must always be whole passes and equal a render asked for that many samples.
  const uint64_t pass_samples = uint64_t(48) * 40 * SamplesPerPass(64);
  options.on_progress = [&](const RenderProgress& p) {
    if (p.samples_done > pass_samples) cancel = true;
  };
  const RenderResult r = Render(scene, bvh, options);
  ASSERT_TRUE(r.interrupted);
  ASSERT_GE(r.spp_done, SamplesPerPass(64));
  ASSERT_LT(r.spp_done, 64u);
  EXPECT_EQ(r.spp_done % SamplesPerPass(64), 0u);
  RenderOptions whole = options;
  whole.spp = r.spp_done;
  whole.cancel = nullptr;
  whole.on_progress = nullptr;
  EXPECT_EQ(Render(scene, bvh, whole).image.rgb, r.image.rgb);
}

// Mean radiance of the box image rendered with `integrator` at spp samples per pixel.
double BoxMean(const char* integrator, uint32_t spp) {
  const Scene scene = LoadOrDie(BoxScene(integrator, int(spp)));
  const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
  RenderOptions options;
  options.spp = spp;
  options.threads = 2;
  const Image img = Render(scene, bvh, options).image;
  double sum = 0;
  for (float v : img.rgb) sum += v;
  return sum / double(img.rgb.size());
}

// Emitter sampling, BSDF sampling and MIS estimate the same direct illumination. Tolerances
// are about 4 standard deviations of the image mean, measured over seeds: BSDF sampling of
// this small light has σ ≈ 1.4 % at 256 spp (0.5 % at 2048), MIS and emitter sampling < 0.05 %.
TEST(Render, DirectStrategiesAgreeInMean) {
  const double ems = BoxMean("direct_ems", 256);
  EXPECT_NEAR(BoxMean("direct_mats", 2048) / ems, 1.0, 0.02);
  EXPECT_NEAR(BoxMean("direct_mis", 256) / ems, 1.0, 0.002);
}

// The three path tracers estimate the same radiance in the closed box (many bounces count).
// σ of path_mats ≈ 0.5 % at 512 spp; path_ems vs path_mis < 0.05 %.
TEST(Render, PathStrategiesAgreeInMean) {
  const double mis = BoxMean("path_mis", 128);
  EXPECT_NEAR(BoxMean("path_ems", 128) / mis, 1.0, 0.002);
  EXPECT_NEAR(BoxMean("path_mats", 512) / mis, 1.0, 0.02);
}

}  // namespace
}  // namespace ptlab
