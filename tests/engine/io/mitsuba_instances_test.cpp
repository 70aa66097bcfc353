// Mitsuba instancing in the loader: <shape type="shapegroup"> and <shape type="instance">,
// the InstanceTable they fill, and the file:line:col errors of what Mitsuba forbids.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/io/mitsuba_loader.h"

namespace ptlab {
namespace {

std::string SceneText(const std::string& body) {
  return "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film type=\"hdrfilm\">"
         "<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>"
         "</sensor>\n" +
         body + "\n</scene>\n";
}

StatusOr<Scene> Load(const std::string& body) {
  return LoadMitsubaSceneFromString(SceneText(body), ".", "inst.xml");
}

std::string Error(const std::string& body) {
  StatusOr<Scene> s = Load(body);
  EXPECT_FALSE(s.ok());
  return s.ok() ? "" : s.status().message();
}

constexpr const char* kGroup =
    "<shape type=\"shapegroup\" id=\"g\">\n"
    "  <shape type=\"rectangle\"/>\n"
    "  <shape type=\"cube\"/>\n"
    "  <shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/>"
    "<point name=\"center\" x=\"1\" y=\"0\" z=\"0\"/></shape>\n"
    "</shape>\n";

TEST(MitsubaInstances, GroupRowsOnceInstancesAndTheirSpheres) {
  // An instance before the group it names (refs are global), one after it.
  StatusOr<Scene> s = Load(
      "<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">"
      "<scale value=\"2\"/><translate x=\"5\"/></transform></shape>\n" +
      std::string(kGroup) + "<shape type=\"rectangle\"/>\n<shape type=\"instance\"><ref id=\"g\"/></shape>");
  ASSERT_TRUE(s.ok()) << s.status().message();
  const InstanceTable& in = s->instances;
  ASSERT_EQ(in.groups(), 1u);
  ASSERT_EQ(in.size(), 2u);
  EXPECT_EQ(in.group_first_row[0], 0u);
  EXPECT_EQ(in.group_row_count[0], 2u + 12u);  // rectangle and cube, stored once
  EXPECT_EQ(s->triangles.size(), 14u + 2u);    // plus the top-level rectangle
  EXPECT_EQ(in.first_prim[0], 0u);
  EXPECT_EQ(in.first_prim[1], 14u);
  // The group's sphere: one world sphere per instance, none of its own.
  ASSERT_EQ(s->spheres.size(), 2u);
  EXPECT_FLOAT_EQ(s->spheres.center_x[0], 7.0f);  // (1, 0, 0) * 2 + (5, 0, 0)
  EXPECT_FLOAT_EQ(s->spheres.radius[0], 1.0f);
  EXPECT_FLOAT_EQ(s->spheres.center_x[1], 1.0f);
  EXPECT_FLOAT_EQ(s->spheres.radius[1], 0.5f);
}

TEST(MitsubaInstances, ErrorsNameTheElement) {
  // A reference to something that is not a shape group.
  EXPECT_NE(Error("<bsdf type=\"diffuse\" id=\"b\"/>\n<shape type=\"instance\">\n  <ref id=\"b\"/></shape>")
                .find("inst.xml:5:3: <shape type=\"instance\"> refers to <bsdf type=\"diffuse\"> "
                      "(at inst.xml:3:1); expected a <shape type=\"shapegroup\">"),
            std::string::npos);
  EXPECT_NE(Error("<shape type=\"rectangle\" id=\"r\"/>\n<shape type=\"instance\"><ref id=\"r\"/></shape>")
                .find("refers to <shape type=\"rectangle\">"),
            std::string::npos);
  // Nested instancing (which is also how a cycle would be written): rejected.
  EXPECT_NE(Error("<shape type=\"shapegroup\" id=\"g\">\n  <shape type=\"instance\"><ref id=\"g\"/>"
                  "</shape></shape>")
                .find("inst.xml:4:3: nested instancing: <shape type=\"instance\"> inside <shape "
                      "type=\"shapegroup\">"),
            std::string::npos);
  EXPECT_NE(Error("<shape type=\"shapegroup\" id=\"g\">\n  <shape type=\"shapegroup\" id=\"h\"/>"
                  "</shape>")
                .find("inst.xml:4:3: nested instancing"),
            std::string::npos);
  // Emitters in a group: Mitsuba does not allow them.
  EXPECT_NE(Error("<shape type=\"shapegroup\" id=\"g\">\n  <shape type=\"rectangle\">\n"
                  "    <emitter type=\"area\"/></shape></shape>")
                .find("inst.xml:5:5: an emitter in a shape of <shape type=\"shapegroup\">"),
            std::string::npos);
  EXPECT_NE(Error("<shape type=\"instance\"><ref id=\"nothing\"/></shape>")
                .find("names no object"),
            std::string::npos);
  EXPECT_NE(Error("<shape type=\"shapegroup\" id=\"g\"><shape type=\"rectangle\"/></shape>\n"
                  "<shape type=\"instance\"><ref id=\"g\"/><float name=\"radius\" value=\"1\"/>"
                  "</shape>")
                .find("unknown property 'radius'"),
            std::string::npos);
  // A group sphere stays a sphere only under a similarity.
  EXPECT_NE(Error(std::string(kGroup) +
                  "<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">"
                  "<scale x=\"2\"/></transform></shape>")
                .find("unsupported: shape \"instance\" (an instance of a group with a sphere "
                      "under a non-uniform scale or shear)"),
            std::string::npos);
  EXPECT_NE(Error(std::string(kGroup) +
                  "<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">"
                  "<scale value=\"1e13\"/></transform></shape>")
                .find("beyond the world's coordinate limit"),
            std::string::npos);
}

}  // namespace
}  // namespace ptlab
