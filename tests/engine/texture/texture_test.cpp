// EvalTexture (engine/texture/texture.h) against values computed by hand; the texture image
// reader's sRGB decode; the Mitsuba loader's textures (bitmap, checkerboard, mesh_attribute).
#include "engine/texture/texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "engine/image/image_io.h"
#include "engine/image/texture_image.h"
#include "engine/io/mitsuba_loader.h"
#include "engine/io/ply_loader.h"
#include "engine/render/interaction.h"
#include "engine/texture/texture_site.h"

namespace ptlab {
namespace {

// A w x h bitmap row whose texel (x, y) is (x, y, 10 y + x) (red = column, green = row).
uint32_t AddIndexBitmap(TextureTable* t, uint32_t w, uint32_t h, TextureFilter filter,
                        TextureWrap wrap) {
  const uint32_t id = t->AddRow(TextureKind::kBitmap, w, h, size_t(3) * w * h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      float* p = &t->data[t->offset[id] + 3 * (size_t(y) * w + x)];
      p[0] = float(x), p[1] = float(y), p[2] = float(10 * y + x);
    }
  t->filter[id] = uint8_t(filter), t->wrap[id] = uint8_t(wrap);
  return id;
}

Color3f At(const TextureTable& t, uint32_t id, float u, float v) {
  return EvalTexture(t, id, {{u, v}, {0, 0, 0}, 0});
}

TEST(Texture, WrapTexelModes) {
  EXPECT_EQ(WrapTexel(-1, 4, TextureWrap::kRepeat), 3);
  EXPECT_EQ(WrapTexel(5, 4, TextureWrap::kRepeat), 1);
  EXPECT_EQ(WrapTexel(-8, 4, TextureWrap::kRepeat), 0);
  EXPECT_EQ(WrapTexel(-3, 4, TextureWrap::kClamp), 0);
  EXPECT_EQ(WrapTexel(9, 4, TextureWrap::kClamp), 3);
  // Mirror: 0 1 2 3 | 3 2 1 0 | 0 1 ...
  EXPECT_EQ(WrapTexel(4, 4, TextureWrap::kMirror), 3);
  EXPECT_EQ(WrapTexel(7, 4, TextureWrap::kMirror), 0);
  EXPECT_EQ(WrapTexel(8, 4, TextureWrap::kMirror), 0);
  EXPECT_EQ(WrapTexel(-1, 4, TextureWrap::kMirror), 0);
  EXPECT_EQ(WrapTexel(-5, 4, TextureWrap::kMirror), 3);
  for (const TextureWrap w : {TextureWrap::kRepeat, TextureWrap::kMirror, TextureWrap::kClamp})
    for (const int32_t i : {-16777217, -3, -1, 0, 1, 2, 16777217}) EXPECT_EQ(WrapTexel(i, 1, w), 0);
}

TEST(Texture, NearestPicksTheTexelUnderUvFromTheTopLeft) {
  TextureTable t;
  const uint32_t rep = AddIndexBitmap(&t, 4, 2, TextureFilter::kNearest, TextureWrap::kRepeat);
  const uint32_t clamp = AddIndexBitmap(&t, 4, 2, TextureFilter::kNearest, TextureWrap::kClamp);
  const uint32_t mirror = AddIndexBitmap(&t, 4, 2, TextureFilter::kNearest, TextureWrap::kMirror);
  // u = 0.6 -> x = 2.4 -> column 2; v = 0.7 -> y = 1.4 -> row 1 (the bottom row).
  EXPECT_EQ(At(t, rep, 0.6f, 0.7f).b, 12.0f);
  EXPECT_EQ(At(t, rep, 0.0f, 0.0f).b, 0.0f);
  // Exactly on a texel border: the texel on the right / below.
  EXPECT_EQ(At(t, rep, 0.25f, 0.5f).b, 11.0f);
  // u = 1.1 -> x = 4.4: repeat 0, clamp 3, mirror 3; u = -0.1 -> x = -0.4 -> -1: 3, 0, 0.
  EXPECT_EQ(At(t, rep, 1.1f, 0.2f).r, 0.0f);
  EXPECT_EQ(At(t, clamp, 1.1f, 0.2f).r, 3.0f);
  EXPECT_EQ(At(t, mirror, 1.1f, 0.2f).r, 3.0f);
  EXPECT_EQ(At(t, rep, -0.1f, 0.2f).r, 3.0f);
  EXPECT_EQ(At(t, clamp, -0.1f, 0.2f).r, 0.0f);
  EXPECT_EQ(At(t, mirror, -0.1f, 0.2f).r, 0.0f);
  // Far outside: clamped to ±2^24 texels, still a texel of the image.
  for (const uint32_t id : {rep, clamp, mirror}) {
    const Color3f c = At(t, id, 1e30f, -1e30f);
    EXPECT_TRUE(c.r >= 0 && c.r <= 3 && c.g >= 0 && c.g <= 1) << id;
  }
}

TEST(Texture, BilinearBlendsTheFourTexelsAroundUv) {
  TextureTable t;
  const uint32_t rep = AddIndexBitmap(&t, 4, 2, TextureFilter::kBilinear, TextureWrap::kRepeat);
  const uint32_t clamp = AddIndexBitmap(&t, 4, 2, TextureFilter::kBilinear, TextureWrap::kClamp);
  // Texel centres: u = (x + 0.5) / 4, v = (y + 0.5) / 2 give the texel itself.
  EXPECT_EQ(At(t, rep, 2.5f / 4, 1.5f / 2).b, 12.0f);
  // x = 0.5 * 4 - 0.5 = 1.5 (half way between columns 1 and 2), y = 0.25 * 2 - 0.5 = 0: row 0.
  EXPECT_EQ(At(t, rep, 0.5f, 0.25f).r, 1.5f);
  EXPECT_EQ(At(t, rep, 0.5f, 0.25f).g, 0.0f);
  // y = 0.5 * 2 - 0.5 = 0.5: half way between rows 0 and 1; x = 0.375*4 - 0.5 = 1 -> column 1.
  EXPECT_EQ(At(t, rep, 0.375f, 0.5f).g, 0.5f);
  EXPECT_EQ(At(t, rep, 0.375f, 0.5f).b, 6.0f);  // (1 + 11) / 2
  // At u = 0 the left neighbour is column -1: repeat wraps it to column 3, clamp to 0.
  // x = -0.5: columns -1 and 0 weighted 0.5 each.
  EXPECT_EQ(At(t, rep, 0.0f, 0.25f).r, 1.5f);    // (3 + 0) / 2
  EXPECT_EQ(At(t, clamp, 0.0f, 0.25f).r, 0.0f);  // (0 + 0) / 2
  // A quarter of the way: x = 0.3125 * 4 - 0.5 = 0.75: 0.25 * column 0 + 0.75 * column 1.
  EXPECT_EQ(At(t, rep, 0.3125f, 0.25f).r, 0.75f);
}

TEST(Texture, OneByOneBitmapIsConstant) {
  TextureTable t;
  for (const TextureWrap w : {TextureWrap::kRepeat, TextureWrap::kMirror, TextureWrap::kClamp}) {
    for (const TextureFilter f : {TextureFilter::kBilinear, TextureFilter::kNearest}) {
      const uint32_t id = t.AddRow(TextureKind::kBitmap, 1, 1, 3);
      t.data[t.offset[id]] = 0.25f, t.data[t.offset[id] + 1] = 0.5f;
      t.data[t.offset[id] + 2] = 0.75f;
      t.filter[id] = uint8_t(f), t.wrap[id] = uint8_t(w);
      for (const float u : {-7.3f, -1.0f, 0.0f, 0.5f, 1.0f, 123.456f}) {
        const Color3f c = At(t, id, u, -u);
        EXPECT_EQ(c.r, 0.25f);
        EXPECT_EQ(c.g, 0.5f);
        EXPECT_EQ(c.b, 0.75f);
      }
    }
  }
}

TEST(Texture, ToUvMapsBeforeTheLookup) {
  TextureTable t;
  const uint32_t id = AddIndexBitmap(&t, 4, 2, TextureFilter::kNearest, TextureWrap::kClamp);
  // uv' = (2u - 0.5, 2v - 0.5) as texture_interp's to_uv (scale 2, then translate -0.5).
  t.m00[id] = 2, t.m02[id] = -0.5f, t.m11[id] = 2, t.m12[id] = -0.5f;
  // u = 0.5 -> u' = 0.5 -> x = 2; v = 0.6 -> v' = 0.7 -> y = 1.4 -> row 1.
  EXPECT_EQ(At(t, id, 0.5f, 0.6f).b, 12.0f);
  // u = 0.1 -> u' = -0.3: clamped to column 0.
  EXPECT_EQ(At(t, id, 0.1f, 0.6f).r, 0.0f);
}

TEST(Texture, CheckerboardParity) {
  TextureTable t;
  const uint32_t id = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
  float* c = &t.data[t.offset[id]];
  c[0] = c[1] = c[2] = 0.4f, c[3] = c[4] = c[5] = 0.2f;
  // color0 where (frac u > 1/2) == (frac v > 1/2).
  EXPECT_EQ(At(t, id, 0.25f, 0.25f).r, 0.4f);
  EXPECT_EQ(At(t, id, 0.75f, 0.25f).r, 0.2f);
  EXPECT_EQ(At(t, id, 0.25f, 0.75f).r, 0.2f);
  EXPECT_EQ(At(t, id, 0.75f, 0.75f).r, 0.4f);
  EXPECT_EQ(At(t, id, 0.5f, 0.25f).r, 0.4f);     // 0.5 is not > 0.5
  EXPECT_EQ(At(t, id, -0.25f, 0.25f).r, 0.2f);   // frac(-0.25) = 0.75
  EXPECT_EQ(At(t, id, 3.75f, -0.25f).r, 0.4f);   // both > 0.5
  // to_uv scales the squares: u' = 4u.
  t.m00[id] = 4;
  EXPECT_EQ(At(t, id, 0.1875f, 0.25f).r, 0.2f);  // u' = 0.75
}

TEST(Texture, TexturedFloatIsTheLuminanceOfTheRowsTexture) {
  TextureTable t;
  const uint32_t id = t.AddRow(TextureKind::kCheckerboard, 1, 1, 6);
  float* c = &t.data[t.offset[id]];
  c[0] = c[1] = c[2] = 0.7f;                     // a one-channel color0: its value
  c[3] = 1.0f, c[4] = 0.0f, c[5] = -2.0f;        // an RGB color1 with a negative channel
  TextureSite site{&t, {{0.25f, 0.25f}, {0, 0, 0}, 0}};
  AlignedVector<uint32_t> column = {kNoTexture, id};
  EXPECT_EQ(TexturedFloat(column, 0, 0.3f, site), 0.3f);  // no texture for row 0
  EXPECT_EQ(TexturedFloat(AlignedVector<uint32_t>{}, 1, 0.3f, site), 0.3f);  // empty column
  EXPECT_FLOAT_EQ(TexturedFloat(column, 1, 0.3f, site), 0.7f);
  site.at.uv = {0.75f, 0.25f};                   // color1: 0.212671 − 2 · 0.072169 > 0
  EXPECT_FLOAT_EQ(TexturedFloat(column, 1, 0.3f, site), 0.212671f - 2 * 0.072169f);
  c[3] = 0.0f;                                   // luminance −0.144 clamps to 0
  EXPECT_EQ(TexturedFloat(column, 1, 0.3f, site), 0.0f);
}

TEST(Texture, MeshAttributesOfTheRowsTrianglesOnly) {
  TextureTable t;
  // Face attribute over scene triangles 5 and 6.
  const uint32_t face = t.AddRow(TextureKind::kFaceAttribute, 5, 2, 6);
  for (int k = 0; k < 6; ++k) t.data[t.offset[face] + k] = float(k + 1);
  EXPECT_EQ(EvalTexture(t, face, {{0, 0}, {0, 0, 0}, 6}).g, 5.0f);
  EXPECT_EQ(EvalTexture(t, face, {{0, 0}, {0, 0, 0}, 4}).g, 0.0f);
  EXPECT_EQ(EvalTexture(t, face, {{0, 0}, {0, 0, 0}, 7}).g, 0.0f);
  EXPECT_EQ(EvalTexture(t, face, {{0, 0}, {0, 0, 0}, 0x80000005u}).g, 0.0f);  // a sphere hit
  // Vertex attribute: triangle v0 = (1, 0, 0), red = 0.5 + (p - v0) · (1, 0.5, 0).
  const uint32_t vert = t.AddRow(TextureKind::kVertexAttribute, 0, 1, kVertexAttributeFloats);
  float* v = &t.data[t.offset[vert]];
  v[0] = 1, v[1] = 0, v[2] = 0;
  v[3] = 0.5f, v[4] = 1, v[5] = 0.5f, v[6] = 0;
  EXPECT_EQ(EvalTexture(t, vert, {{0, 0}, {1.25f, 0.5f, 0}, 0}).r, 1.0f);  // 0.5 + 0.25 + 0.25
}

TEST(TextureImage, DecodesSrgbUnlessRaw) {
  const std::string dir = std::string(PTLAB_BINARY_DIR) + "/texture_image_test";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/one.png";
  // WritePng sRGB-encodes: the linear value of code 128 comes back as the byte 128.
  Image image(1, 1);
  const double code = 128.0 / 255.0;
  const float linear = float(std::pow((code + 0.055) / 1.055, 2.4));  // IEC 61966-2-1
  image.Set(0, 0, {linear, linear, linear});
  ASSERT_TRUE(WritePng(path, image).ok());
  StatusOr<Image> decoded = ReadTextureImage(path, /*raw=*/false);
  ASSERT_TRUE(decoded.ok()) << decoded.status().message();
  EXPECT_NEAR(decoded->rgb[0], 0.2158605f, 1e-6f);
  StatusOr<Image> raw = ReadTextureImage(path, /*raw=*/true);
  ASSERT_TRUE(raw.ok());
  EXPECT_EQ(raw->rgb[0], float(code));
  EXPECT_FALSE(ReadTextureImage(dir + "/missing.png", false).ok());
}

const std::string kMitsubaScenes =
    std::string(PTLAB_SOURCE_DIR) + "/../shared/data/mitsuba3/tests/scenes/";

TEST(MitsubaTextures, VertexAttributeInterpolatesThePlyValues) {
  const std::string scene_path =
      kMitsubaScenes + "mesh_attributes/test_mesh_attributes_3_vertex_direct.xml";
  if (!std::filesystem::exists(scene_path)) GTEST_SKIP() << "no Mitsuba test data";
  StatusOr<Scene> scene = LoadMitsubaScene(scene_path);
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  StatusOr<MeshData> ply =
      LoadPly(kMitsubaScenes + "mesh_attributes/meshes/sphere_attribute.ply");
  ASSERT_TRUE(ply.ok()) << ply.status().message();
  const MeshAttribute* color = nullptr;
  for (const MeshAttribute& a : ply->attributes)
    if (a.name == "vertex_color") color = &a;
  ASSERT_NE(color, nullptr);
  ASSERT_EQ(scene->textures.size(), 1u);
  ASSERT_EQ(scene->triangles.size(), ply->triangle_count());
  // At each corner and the centroid of every triangle: the PLY's values, barycentric.
  double worst = 0;
  for (uint32_t tri = 0; tri < scene->triangles.size(); ++tri) {
    const Vec3f p[3] = {scene->triangles.V0(tri), scene->triangles.V1(tri),
                        scene->triangles.V2(tri)};
    for (int corner = 0; corner < 4; ++corner) {
      const float w[3] = {corner == 3 ? 1 / 3.0f : float(corner == 0),
                          corner == 3 ? 1 / 3.0f : float(corner == 1),
                          corner == 3 ? 1 / 3.0f : float(corner == 2)};
      const Vec3f at = p[0] * w[0] + p[1] * w[1] + p[2] * w[2];
      const Color3f got = EvalTexture(scene->textures, 0, {{0, 0}, at, tri});
      for (int k = 0; k < 3; ++k) {
        double want = 0;
        for (int c = 0; c < 3; ++c)
          want += w[c] * color->values[ply->indices[3 * tri + c] * 3 + k];
        worst = std::max(worst, std::abs(double((&got.r)[k]) - want));
      }
    }
  }
  EXPECT_LT(worst, 1e-5);
}

TEST(MitsubaTextures, BitmapAndCheckerboardRows) {
  const std::string base = kMitsubaScenes + "texture_interp";
  if (!std::filesystem::exists(base)) GTEST_SKIP() << "no Mitsuba test data";
  const std::string xml = R"(<scene version="3.0.0">
    <path value="../../../common"/>
    <sensor type="perspective"/>
    <shape type="rectangle">
      <bsdf type="diffuse">
        <texture type="bitmap" name="reflectance">
          <string name="filename" value="textures/carrot.png"/>
          <string name="wrap_mode" value="mirror"/>
          <string name="filter_type" value="nearest"/>
          <transform name="to_uv"><scale value="2"/><translate value="-.5,-.5, 0"/></transform>
        </texture>
      </bsdf>
    </shape>
    <texture type="checkerboard" id="c"><rgb name="color0" value="0.1, 0.2, 0.3"/></texture>
    <shape type="cube"><bsdf type="diffuse"><ref name="reflectance" id="c"/></bsdf></shape>
  </scene>)";
  StatusOr<Scene> scene = LoadMitsubaSceneFromString(xml, base, "textures.xml");
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  const TextureTable& t = scene->textures;
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.Kind(0), TextureKind::kBitmap);
  EXPECT_EQ(TextureWrap(t.wrap[0]), TextureWrap::kMirror);
  EXPECT_EQ(TextureFilter(t.filter[0]), TextureFilter::kNearest);
  EXPECT_EQ(t.m00[0], 2.0f);
  EXPECT_EQ(t.m02[0], -0.5f);
  EXPECT_EQ(t.m12[0], -0.5f);
  EXPECT_GT(t.width[0], 1u);
  EXPECT_EQ(t.Kind(1), TextureKind::kCheckerboard);
  EXPECT_EQ(t.data[t.offset[1] + 2], 0.3f);
  EXPECT_EQ(t.data[t.offset[1] + 3], 0.2f);  // color1's default
  ASSERT_TRUE(scene->materials.diffuse.textured());
  EXPECT_EQ(scene->materials.diffuse.albedo_texture[0], 0u);
  EXPECT_EQ(scene->materials.diffuse.albedo_texture[1], 1u);
}

TEST(MitsubaTextures, ErrorsNameTheProblem) {
  const std::string base = kMitsubaScenes + "texture_interp";
  const auto load = [&](const std::string& texture) {
    return LoadMitsubaSceneFromString(
        "<scene version=\"3.0.0\"><path value=\"../../../common\"/><sensor type=\"perspective\"/>"
        "<shape type=\"cube\">"
        "<bsdf type=\"diffuse\">" + texture + "</bsdf></shape></scene>",
        base, "bad.xml");
  };
  const auto message = [&](const std::string& texture) {
    StatusOr<Scene> s = load(texture);
    return s.ok() ? std::string("(loaded)") : s.status().message();
  };
  EXPECT_NE(message(R"(<texture type="bitmap" name="reflectance"><string name="filename" value="textures/carrot.png"/><string name="wrap_mode" value="wrap"/></texture>)")
                .find("expected repeat, mirror or clamp"),
            std::string::npos);
  EXPECT_NE(message(R"(<texture type="bitmap" name="reflectance"><string name="filename" value="nope.png"/></texture>)")
                .find("bad.xml:1:"),
            std::string::npos);
  EXPECT_NE(message(R"(<texture type="volume" name="reflectance"/>)").find("unsupported"),
            std::string::npos);
  EXPECT_NE(message(R"(<texture type="mesh_attribute" name="reflectance"><string name="name" value="vertex_nothing"/></texture>)")
                .find("has no attribute 'vertex_nothing'"),
            std::string::npos);
}

}  // namespace
}  // namespace ptlab
