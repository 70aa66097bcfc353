// Rendered images of Mitsuba scene features: hide_emitters and the orthographic sensor on the
// scalar path, the oracle's wavefront and the SIMD packets; a projector on a diffuse plane.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/bvh/bvh.h"
#include "engine/io/mitsuba_loader.h"
#include "engine/render/render.h"
#include "tests/engine/render/packet_render_for_test.h"

namespace ptlab {
namespace {

Scene LoadOrDie(const std::string& xml) {
  StatusOr<Scene> s = LoadMitsubaSceneFromString(xml, ".", "features.xml");
  EXPECT_TRUE(s.ok()) << s.status().message();
  return s.ok() ? std::move(*s) : Scene{};
}

// An orthographic view (3 × 2 world units across a 24 × 16 film) down -z onto a diffuse
// rectangle of half-size 0.75 (albedo 0.5) in a constant environment of radiance 1.
std::string OrthographicFurnace(const std::string& integrator, bool hide) {
  return std::string(R"(<scene version="3.0.0">
  <integrator type=")") +
         integrator + R"(">
    <boolean name="hide_emitters" value=")" +
         (hide ? "true" : "false") + R"("/>
  </integrator>
  <sensor type="orthographic">
    <float name="near_clip" value="0.5"/>
    <transform name="to_world"><scale x="1.5" y="1.5"/>
      <lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="16"/>
      <rfilter type="box"/></film>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
  <shape type="rectangle"><transform name="to_world"><scale value="0.75"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
</scene>)";
}

// Pixel (x, y) sees the rectangle when its whole footprint lies on it: pixels are 0.125 world
// units; the rectangle spans [-0.75, 0.75]², i.e. pixels 6..17 across and 2..13 down.
bool OnRectangle(int x, int y) { return x >= 6 && x < 18 && y >= 2 && y < 14; }
bool OffRectangle(int x, int y) { return x < 5 || x > 18 || y < 1 || y > 14; }

// With hide_emitters the environment seen directly is black, and the rectangle's pixels are
// those of the same render without it, bit for bit (hiding changes no random number).
// Without, the background is the environment's radiance 1 exactly; the rectangle converges to
// albedo × 1 = 0.5 (its pixels' mean within 4 standard errors).
TEST(MitsubaFeaturesRender, HideEmittersAndOrthographicSensor) {
  for (const char* integrator : {"path", "direct"}) {
    SCOPED_TRACE(integrator);
    const Scene shown = LoadOrDie(OrthographicFurnace(integrator, false));
    const Scene hidden = LoadOrDie(OrthographicFurnace(integrator, true));
    ASSERT_FALSE(shown.integrator.hide_emitters);
    ASSERT_TRUE(hidden.integrator.hide_emitters);
    RenderOptions options;
    options.spp = 64;
    options.seed = 5;
    const Bvh bvh_shown = BuildBvh(shown.triangles, shown.spheres);
    const Bvh bvh_hidden = BuildBvh(hidden.triangles, hidden.spheres);
    for (int path = 0; path < 3; ++path) {
      SCOPED_TRACE(path == 0 ? "scalar" : path == 1 ? "oracle wavefront" : "simd");
      const auto render = [&](const Scene& s, const Bvh& bvh) {
        if (path == 0) return Render(s, bvh, options).image;
        if (path == 1) return RenderWithOracleWavefront(s, options).image;
        return RenderWithPackets(s, options).image;
      };
      const Image a = render(shown, bvh_shown), b = render(hidden, bvh_hidden);
      double sum = 0, sum2 = 0;
      int n = 0;
      for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 24; ++x) {
          const Color3f ca = a.At(x, y), cb = b.At(x, y);
          if (OffRectangle(x, y)) {
            EXPECT_EQ(ca.g, 1.0f) << x << " " << y;
            EXPECT_EQ(cb.g, 0.0f) << x << " " << y;
          }
          if (OnRectangle(x, y)) {
            EXPECT_EQ(ca.g, cb.g) << x << " " << y;
            sum += ca.g, sum2 += double(ca.g) * ca.g, ++n;
          }
        }
      }
      const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / (n - 1));
      EXPECT_NEAR(mean, 0.5, 4 * se + 1e-6) << "standard error " << se;
    }
  }
}

// A projector (fov 90°, scale 1, irradiance 0.5) one unit above a diffuse plane (albedo 0.8),
// seen by an orthographic camera from above: the lit square |x|, |y| <= 1 sends out
// albedo / π × π × 0.5 = 0.4 exactly (one delta sample per pixel sample, no noise); outside
// it, black.
TEST(MitsubaFeaturesRender, ProjectorLightsASquareUniformly) {
  const Scene scene = LoadOrDie(R"(<scene version="3.0.0">
  <integrator type="direct"/>
  <sensor type="orthographic">
    <transform name="to_world"><scale x="2" y="2"/>
      <lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/>
      <rfilter type="box"/></film>
    <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
  </sensor>
  <emitter type="projector"><float name="fov" value="90"/>
    <rgb name="irradiance" value="0.5"/>
    <transform name="to_world"><lookat origin="0, 0, 1" target="0, 0, 0" up="0, 1, 0"/>
    </transform></emitter>
  <shape type="rectangle"><transform name="to_world"><scale value="4"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.8"/></bsdf></shape>
</scene>)");
  ASSERT_EQ(scene.projectors.size(), 1u);
  RenderOptions options;
  options.spp = 4;
  const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
  for (int path = 0; path < 2; ++path) {
    SCOPED_TRACE(path == 0 ? "scalar" : "simd");
    const Image im =
        path == 0 ? Render(scene, bvh, options).image : RenderWithPackets(scene, options).image;
    // Pixels are 0.25 world units; the lit square spans pixels 4..11.
    for (int y = 0; y < 16; ++y) {
      for (int x = 0; x < 16; ++x) {
        const float g = im.At(x, y).g;
        if (x >= 4 && x < 12 && y >= 4 && y < 12) {
          EXPECT_NEAR(g, 0.4f, 2e-5f) << x << " " << y;
        }
        if (x < 3 || x > 12 || y < 3 || y > 12) {
          EXPECT_EQ(g, 0.0f) << x << " " << y;
        }
      }
    }
  }
}

}  // namespace
}  // namespace ptlab
