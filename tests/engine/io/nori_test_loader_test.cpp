// Tests of the Nori test-file loader: the shipped files, defaults, and each malformed input.
#include "engine/io/nori_test_loader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "tests/test_data.h"

namespace ptlab {
namespace {

std::string NoriDir() { return test_data::Path("nori"); }

#define PTLAB_SKIP_WITHOUT_NORI_DATA() PTLAB_REQUIRE_DATA(NoriDir())

StatusOr<NoriTestFile> Parse(const std::string& xml) {
  return LoadNoriTestFileFromString(xml, PTLAB_SOURCE_DIR "/tests/data/scene", "bad.xml");
}

// The error starts with "bad.xml:line:" and contains every word of `words`.
void ExpectError(const std::string& xml, int line, const std::vector<std::string>& words) {
  SCOPED_TRACE(xml);
  const StatusOr<NoriTestFile> result = Parse(xml);
  ASSERT_FALSE(result.ok()) << "expected an error";
  const std::string& message = result.status().message();
  const std::string prefix = "bad.xml:" + std::to_string(line) + ":";
  EXPECT_EQ(message.rfind(prefix, 0), 0u)
      << "message does not start with '" << prefix << "': " << message;
  for (const std::string& w : words)
    EXPECT_NE(message.find(w), std::string::npos) << "'" << w << "' missing from: " << message;
}

const std::string kScene =
    "<scene><integrator type=\"normals\"/><camera type=\"perspective\"/></scene>\n";

TEST(NoriTestLoader, TTestOfBsdfs) {
  PTLAB_SKIP_WITHOUT_NORI_DATA();
  const std::string path = NoriDir() + "/eth-cg/scenes/pa4/tests/ttest-dielectric.xml";
  const StatusOr<NoriTestFile> file = LoadNoriTestFile(path);
  ASSERT_TRUE(file.ok()) << file.status().message();
  EXPECT_EQ(file->path, path);
  EXPECT_EQ(file->type, NoriTestType::kTTest);
  EXPECT_FLOAT_EQ(file->properties.significance_level, 0.01f);
  EXPECT_EQ(file->properties.sample_count, 100000);
  ASSERT_EQ(file->properties.angles.size(), 12u);
  ASSERT_EQ(file->properties.references.size(), 24u);
  EXPECT_FLOAT_EQ(file->properties.angles[11], 180.0f);
  EXPECT_FLOAT_EQ(file->properties.references[9], 2.18016f);
  EXPECT_FLOAT_EQ(file->properties.references[23], 0.390068f);
  ASSERT_EQ(file->bsdfs.size(), 2u);
  EXPECT_TRUE(file->scenes.empty());
  EXPECT_EQ(file->bsdfs[1].tag(), MaterialTag::kDielectric);
  EXPECT_FLOAT_EQ(file->materials.dielectric.int_ior[file->bsdfs[1].index()], 1.000277f);
  EXPECT_FLOAT_EQ(file->materials.dielectric.ext_ior[file->bsdfs[1].index()], 1.7f);
  EXPECT_EQ(file->child_lines, (std::vector<int>{8, 13}));
}

TEST(NoriTestLoader, TTestOfScenesAndChi2Test) {
  PTLAB_SKIP_WITHOUT_NORI_DATA();
  StatusOr<NoriTestFile> file =
      LoadNoriTestFile(NoriDir() + "/eth2015/scenes/pa4/tests/test-furnace.xml");
  ASSERT_TRUE(file.ok()) << file.status().message();
  ASSERT_EQ(file->scenes.size(), 4u);
  EXPECT_EQ(file->properties.references, (std::vector<float>{2, 5, 2, 5}));
  EXPECT_EQ(file->scenes[2].integrator.type, IntegratorDesc::Type::kPathMis);
  EXPECT_GT(file->scenes[0].triangles.size(), 0u);
  EXPECT_EQ(file->scenes[0].area_lights.size(), 1u);
  EXPECT_EQ(file->scenes[0].source_path, file->path);

  file = LoadNoriTestFile(NoriDir() + "/epfl/scenes/pa5/tests/chi2test-microfacet.xml");
  ASSERT_TRUE(file.ok()) << file.status().message();
  EXPECT_EQ(file->type, NoriTestType::kChi2Test);
  EXPECT_EQ(file->properties.resolution, 10);
  EXPECT_EQ(file->properties.min_exp_frequency, 5);
  EXPECT_EQ(file->properties.test_count, 5);
  EXPECT_EQ(file->properties.sample_count, 10 * 20 * 5000);  // Nori's automatic count
  ASSERT_EQ(file->bsdfs.size(), 3u);
  EXPECT_EQ(file->bsdfs[2].tag(), MaterialTag::kRoughPlastic);
  EXPECT_FLOAT_EQ(file->materials.rough_plastic.alpha[file->bsdfs[2].index()], 0.6f);
  EXPECT_FLOAT_EQ(file->materials.rough_plastic.kd_b[file->bsdfs[1].index()], 0.6f);
}

TEST(NoriTestLoader, PropertiesOverrideDefaults) {
  const StatusOr<NoriTestFile> file = Parse(
      "<test type=\"chi2test\"><float name=\"significanceLevel\" value=\"0.05\"/>"
      "<integer name=\"resolution\" value=\"6\"/><integer name=\"minExpFrequency\" value=\"7\"/>"
      "<integer name=\"testCount\" value=\"2\"/><bsdf type=\"diffuse\"/></test>");
  ASSERT_TRUE(file.ok()) << file.status().message();
  EXPECT_FLOAT_EQ(file->properties.significance_level, 0.05f);
  EXPECT_EQ(file->properties.resolution, 6);
  EXPECT_EQ(file->properties.min_exp_frequency, 7);
  EXPECT_EQ(file->properties.test_count, 2);
  EXPECT_EQ(file->properties.sample_count, 6 * 12 * 5000);
  const StatusOr<NoriTestFile> t = Parse(
      "<test type=\"ttest\"><integer name=\"sampleCount\" value=\"1000\"/>"
      "<string name=\"references\" value=\" 1,2\n3 \"/>" +
      kScene + kScene + kScene + "</test>");
  ASSERT_TRUE(t.ok()) << t.status().message();
  EXPECT_EQ(t->properties.sample_count, 1000);
  EXPECT_EQ(t->properties.references, (std::vector<float>{1, 2, 3}));
  EXPECT_EQ(t->scenes.size(), 3u);
}

TEST(NoriTestLoader, MalformedFiles) {
  ExpectError("<test type=\"ttest\">\n<string name=\"reference\" value=\"1\"/></test>", 2,
              {"unknown property 'reference'", "references"});
  ExpectError("<test type=\"chi2test\">\n<string name=\"angles\" value=\"1\"/></test>", 2,
              {"unknown property 'angles'", "testCount"});
  ExpectError("<test type=\"ttest\">\n<float name=\"references\" value=\"1\"/></test>", 2,
              {"wrong type <float>", "<string>"});
  ExpectError(
      "<test type=\"ttest\"><string name=\"references\" value=\"1\"/>\n"
      "<string name=\"references\" value=\"1\"/></test>",
      2, {"duplicate property 'references'", "line 1"});
  ExpectError("<test type=\"ttest\">\n<string name=\"references\" value=\"1, x2\"/></test>", 2,
              {"malformed number 'x2'"});
  ExpectError("<test type=\"ttest\">\n<string name=\"references\" value=\"1,,2\"/></test>", 2,
              {"malformed list"});
  ExpectError("<test type=\"ttest\">\n<float name=\"significanceLevel\" value=\"1.5\"/></test>", 2,
              {"out of range", "(0, 1)"});
  ExpectError("<test type=\"ttest\">\n<integer name=\"sampleCount\" value=\"1\"/></test>", 2,
              {"sampleCount", "2..1000000000"});
  ExpectError("<test type=\"chi2test\">\n<integer name=\"testCount\" value=\"0\"/></test>", 2,
              {"testCount", "1..10000"});
  ExpectError("<test type=\"ttest\">\n<integer name=\"sampleCount\" value=\"1.5\"/></test>", 2,
              {"integer '1.5' is not an integer", "[-2147483648, 2147483647]"});
  ExpectError("<test type=\"ttest\">\n<integer name=\"sampleCount\" value=\"99999999999\"/></test>",
              2, {"integer '99999999999' is out of range [-2147483648, 2147483647]"});
  ExpectError("\n<test type=\"ztest\"/>", 2, {"unknown test type 'ztest'", "ttest or chi2test"});
  ExpectError("\n<test kind=\"ttest\"/>", 2, {"unknown attribute 'kind'"});
  ExpectError("\n<scene/>", 2, {"root element <scene>", "<test"});
  ExpectError("<test type=\"ttest\">\n<mesh type=\"obj\"/></test>", 2,
              {"<mesh> is not allowed", "<scene> or <bsdf>"});
  ExpectError("<test type=\"chi2test\">\n" + kScene + "</test>", 2,
              {"<scene> is not allowed", "<bsdf>"});
  ExpectError("<test type=\"ttest\">\n<string name=\"references\" value=\"1\"/>\n</tes>", 3,
              {"XML syntax error"});
}

TEST(NoriTestLoader, CountMismatches) {
  ExpectError("<test type=\"ttest\">\n" + kScene + "</test>", 1, {"missing", "references"});
  ExpectError("<test type=\"ttest\">\n<string name=\"references\" value=\"1\"/></test>", 1,
              {"no <scene> or <bsdf>"});
  ExpectError(
      "<test type=\"ttest\">\n<string name=\"references\" value=\"1 2\"/>\n" + kScene + "</test>",
      2, {"2 references for 1 scenes"});
  ExpectError(
      "<test type=\"ttest\"><string name=\"references\" value=\"1\"/>\n"
      "<string name=\"angles\" value=\"0\"/>\n" +
          kScene + "</test>",
      2, {"'angles' in a t-test of scenes"});
  ExpectError(
      "<test type=\"ttest\"><string name=\"references\" value=\"1\"/>\n<bsdf "
      "type=\"diffuse\"/></test>",
      1, {"missing the required property", "angles"});
  ExpectError(
      "<test type=\"ttest\">\n<string name=\"references\" value=\"1 2 3\"/>"
      "<string name=\"angles\" value=\"0 45\"/><bsdf type=\"diffuse\"/>"
      "<bsdf type=\"diffuse\"/></test>",
      2, {"3 references for 2 angles and 2 BSDFs"});
  ExpectError("<test type=\"ttest\"><string name=\"references\" value=\"1\"/>" + kScene +
                  "\n<bsdf type=\"diffuse\"/></test>",
              3, {"not both"});
  ExpectError("<test type=\"chi2test\">\n</test>", 1, {"no <bsdf>"});
}

TEST(NoriTestLoader, ErrorsInsideScenesAndBsdfsNameTheirLine) {
  ExpectError(
      "<test type=\"ttest\"><string name=\"angles\" value=\"0\"/>"
      "<string name=\"references\" value=\"1\"/>\n<bsdf type=\"diffuse\">\n"
      "<color name=\"albedo\" value=\"2, 0, 0\"/></bsdf></test>",
      3, {"'albedo' = (2, 0, 0) is out of range"});
  ExpectError(
      "<test type=\"ttest\"><string name=\"references\" value=\"1\"/>\n<scene>"
      "<integrator type=\"normals\"/></scene></test>",
      2, {"no <camera>"});
  ExpectError(
      "<test type=\"ttest\"><string name=\"references\" value=\"1\"/>\n<scene>"
      "<integrator type=\"normals\"/><camera type=\"perspective\"/>\n"
      "<emitter type=\"spot\"/></scene></test>",
      3, {"emitter type 'spot' is not supported yet"});
}

}  // namespace
}  // namespace ptlab
