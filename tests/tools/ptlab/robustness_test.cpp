// Issue 41's classes of hostile input, one test per class, on inputs written here: no input
// is overwritten, nothing crashes, no unbounded work or memory, no silent garbage, and every
// message names the file and the accepted range. Each run is a tiny render (8x8, 1 spp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/tools/command_test_util.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;
using test_util::ReadFile;
using test_util::RunShell;

const std::string kPtlab = std::string(PTLAB_BINARY_DIR) + "/bin/ptlab";
const std::string kImgdiff = std::string(PTLAB_BINARY_DIR) + "/bin/imgdiff";
const std::string kChi2 = std::string(PTLAB_BINARY_DIR) + "/bin/chi2";

// A Nori scene of one sphere under a quad light, W x H pixels (8x8), one sample.
constexpr const char* kSceneTemplate = R"(<scene>
  <integrator type="path_mis"/>
  <sampler type="independent"><integer name="sampleCount" value="1"/></sampler>
  <camera type="perspective">
    <transform name="toWorld"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <float name="fov" value="40"/>
    <integer name="width" value="W"/><integer name="height" value="H"/>
  </camera>
  <shape type="sphere"><point name="center" value="0, 0, 0"/><float name="radius" value="1"/>
    <bsdf type="diffuse"/></shape>
  <shape type="rectangle">
    <transform name="toWorld"><rotate axis="1, 0, 0" angle="90"/><translate value="0, 3, 0"/></transform>
    <emitter type="area"><color name="radiance" value="5, 5, 5"/></emitter>
  </shape>
</scene>
)";

std::string SceneText(int width, int height) {
  std::string s = kSceneTemplate;
  s.replace(s.find("\"W\""), 3, "\"" + std::to_string(width) + "\"");
  s.replace(s.find("\"H\""), 3, "\"" + std::to_string(height) + "\"");
  return s;
}
const std::string kScene = SceneText(8, 8);

// A COLLADA file: a camera at (0, 0, 5), one triangle, `library_nodes` and the visual scene's
// `nodes`.
std::string Collada(const std::string& library_nodes, const std::string& nodes) {
  return "<?xml version=\"1.0\"?>\n<COLLADA version=\"1.4.1\">\n"
         "<library_cameras><camera id=\"cam\"><optics><technique_common><perspective>"
         "<yfov>40</yfov><aspect_ratio>1</aspect_ratio><znear>0.1</znear><zfar>100</zfar>"
         "</perspective></technique_common></optics></camera></library_cameras>\n"
         "<library_geometries><geometry id=\"tri\"><mesh>"
         "<source id=\"p\"><float_array id=\"pa\" count=\"9\">0 0 0 1 0 0 0 1 0</float_array>"
         "<technique_common><accessor source=\"#pa\" count=\"3\" stride=\"3\">"
         "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
         "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>"
         "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>"
         "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
         "<p>0 1 2</p></triangles></mesh></geometry></library_geometries>\n"
         "<library_nodes>" + library_nodes + "</library_nodes>\n"
         "<library_visual_scenes><visual_scene id=\"s\">\n"
         "<node id=\"c\"><translate>0 0 5</translate><instance_camera url=\"#cam\"/></node>\n" +
         nodes + "</visual_scene></library_visual_scenes>\n"
         "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";
}

class Robustness : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test_util::TempDir(std::string("robustness_") +
                              ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  // Runs a command line; returns its exit status (-1: a signal) and keeps its output in Log().
  int Run(const std::string& command) { return RunShell(command, dir_ / "log"); }
  std::string Log() const { return ReadFile(dir_ / "log"); }
  // The command exits `code` and its output holds every one of `words`.
  void Expect(const std::string& command, int code, std::initializer_list<std::string> words) {
    SCOPED_TRACE(command);
    EXPECT_EQ(Run(command), code) << Log();
    for (const std::string& w : words) EXPECT_NE(Log().find(w), std::string::npos) << w << "\n" << Log();
  }
  fs::path dir_;
};

// Class "inputs overwritten": every output that is an input (or another output) is refused
// with exit 2 before rendering, naming both files, and the input keeps its bytes.
TEST_F(Robustness, InputsOverwritten) {
  const std::string scene = Write("scene.xml", kScene);
  const std::string png_scene = Write("picture.png", kScene);  // a scene named like an image
  const std::string camera = Write("camera.txt",
                                   "50 35 1.5 0.01 100\n2 1 5 7 1 5\n0 0 5 0.5 50\n"
                                   "0 0 -1 0 1 0 1 0 0\n960 640 1\n3.5 0.25\n");
  const std::string render = kPtlab + " render -q ";
  const auto unchanged = [&](const std::string& path, const std::string& bytes) {
    EXPECT_EQ(ReadFile(path), bytes) << path;
  };
  // The default output of picture.png is picture.exr + picture.png: the scene itself.
  Expect("cd " + dir_.string() + " && " + render + "picture.png", 2,
         {"is the same file as the input", "picture.png' (scene)"});
  unchanged(png_scene, kScene);
  Expect(render + scene + " -o " + (dir_ / "a.exr").string() + " --tile-times " + scene, 2,
         {"(--tile-times) is the same file as the input '" + scene + "' (scene)"});
  unchanged(scene, kScene);
  Expect(render + scene + " -o " + (dir_ / "a.exr").string() + " --tile-times " +
             (dir_ / "a.png").string(),
         2, {"are the same file"});
  // -e env.exr -o env.exr: first make an env map, then try to render over it.
  ASSERT_EQ(Run(render + scene + " -o " + (dir_ / "env.exr").string()), 0) << Log();
  const std::string env = ReadFile(dir_ / "env.exr");
  Expect(render + scene + " -e " + (dir_ / "env.exr").string() + " -o " +
             (dir_ / "env.exr").string(),
         2, {"(EXR output) is the same file as the input"});
  unchanged((dir_ / "env.exr").string(), env);
  Expect(kPtlab + " envmap-pdf " + (dir_ / "env.exr").string() + " -o " +
             (dir_ / "./env.exr").string(),
         2, {"is the same file as the input"});
  unchanged((dir_ / "env.exr").string(), env);
  // A symbolic link to the scene as --tile-times.
  fs::create_symlink(dir_ / "scene.xml", dir_ / "times.csv");
  Expect(render + scene + " -o " + (dir_ / "b.exr").string() + " --tile-times " +
             (dir_ / "times.csv").string(),
         2, {"is the same file as the input"});
  unchanged(scene, kScene);
  // --tile-times into a missing folder fails before the render, and writes no image.
  Expect(render + scene + " -o " + (dir_ / "c.exr").string() + " --tile-times " +
             (dir_ / "missing" / "t.csv").string(),
         3, {"does not exist"});
  EXPECT_FALSE(fs::exists(dir_ / "c.exr"));
  // --tile-times over the -c camera file.
  const std::string camera_bytes = ReadFile(camera);
  Expect(render + scene + " -c " + camera + " -o " + (dir_ / "d.exr").string() + " --tile-times " +
             camera,
         2, {"(--tile-times) is the same file as the input '" + camera + "' (-c camera file)"});
  unchanged(camera, camera_bytes);
  // imgdiff's heat map over its reference.
  Expect(kImgdiff + " " + (dir_ / "env.exr").string() + " " + (dir_ / "env.exr").string() +
             " --heatmap " + (dir_ / "env.exr").string(),
         2, {"(--heatmap) is the same file as the input"});
  unchanged((dir_ / "env.exr").string(), env);
}

// Class "unclear messages": numbers out of range say the range, NaN is refused, and a NUL byte
// does not cut the message.
TEST_F(Robustness, UnclearMessages) {
  const std::string scene = Write("scene.xml", kScene);
  const std::string out = " -q -o " + (dir_ / "x.exr").string();
  Expect(kPtlab + " render " + scene + " -d 1e-320" + out, 2, {"-d", "out of range [1e-6, 1e12]"});
  Expect(kPtlab + " render " + scene + " -d 1e-50" + out, 2, {"out of range [1e-6, 1e12]"});
  Expect(kPtlab + " render " + scene + " -d 1e20 -b 0.1" + out, 2, {"out of range [1e-6, 1e12]"});
  Expect(kImgdiff + " a.exr b.exr --tol 1e-320x", 2, {"--tol", "is not a number"});
  Expect(kChi2 + " check --domain square --samples x.csv --pdf-cmd true --pdf-timeout nan", 2,
         {"--pdf-timeout", "'nan' is not a finite number; expected a number in [0.01, 1e6]"});
  Expect(kChi2 + " --alpha nan --all", 2, {"not a finite number"});
  // A -c camera file with a NUL byte and a number past float range.
  Write("nul.txt", std::string("1\0x 2\n", 6));
  Expect(kPtlab + " render " + scene + " -c " + (dir_ / "nul.txt").string() + out, 2,
         {"nul.txt:1: '1\\0x' is not a number"});
  Write("big.txt", "60 1e38\n");
  Expect(kPtlab + " render " + scene + " -c " + (dir_ / "big.txt").string() + out, 2,
         {"big.txt:1: '1e38' is out of range [-1e12, 1e12]"});
  // A CS184 sphere of radius 1e20 is named as the sphere, not blamed on the camera.
  std::string dae = Collada("", "<node><instance_geometry url=\"#sph\"/></node>\n"
                                "<node><instance_geometry url=\"#tri\"/></node>\n");
  dae.replace(dae.find("<library_geometries>") + 20, 0,
              "<geometry id=\"sph\"><extra><technique profile=\"CGL\"><sphere><radius>1e20"
              "</radius></sphere></technique></extra></geometry>");
  Expect(kPtlab + " render " + Write("big_sphere.dae", dae) + out, 2,
         {"big_sphere.dae:", "the sphere (world radius 1e20", "[-1e12, 1e12]"});
  EXPECT_EQ(Log().find("camera"), std::string::npos) << Log();
  // chi2 check sample files: file and line in every message; a NaN first line is a sample.
  Write("nan_first.csv", "NaN,0.5\n0.5,0.5\n");
  Expect(kChi2 + " check --domain square --pdf-cmd true --samples " + (dir_ / "nan_first.csv").string(),
         2, {"nan_first.csv:1: the sample is not finite"});
  Write("bad.csv", "x,y\n0.5,0.5\n0.5,zero\n");
  Expect(kChi2 + " check --domain square --pdf-cmd true --samples " + (dir_ / "bad.csv").string(), 2,
         {"bad.csv:3: 'zero' is not a number"});
  Write("grid.txt", "2 2\n1 1\n1 1e400\n");
  Expect(kChi2 + " check --domain square --samples " + (dir_ / "bad.csv").string() + " --pdf-grid " +
             (dir_ / "grid.txt").string(),
         2, {"bad.csv:3"});
  Write("ok.csv", "0.5,0.5\n");
  Expect(kChi2 + " check --domain square --samples " + (dir_ / "ok.csv").string() + " --pdf-grid " +
             (dir_ / "grid.txt").string(),
         2, {"grid.txt:3: density '1e400' is out of range [0, 1e300]"});
}

// Class "crashes": inputs that used to abort (uncaught std::stod, std::filesystem on a path
// past PATH_MAX) end with a clear error and no signal.
TEST_F(Robustness, Crashes) {
  const std::string scene = Write("scene.xml", kScene);
  Expect(kImgdiff + " a.exr b.exr --tol 1e-320", 2, {"a.exr"});  // parsed, then a missing file
  std::string deep = dir_.string() + "/";
  while (deep.size() < 4200) deep += "dddddddddd/";
  Expect(kPtlab + " render -q " + scene + " -o " + deep + "x.exr", 2, {"PATH_MAX"});
  Expect(kPtlab + " render -q " + scene + " -o " + (dir_ / (std::string(250, 'n') + ".exr")).string(),
         2, {"NAME_MAX"});
  Expect(kPtlab + " converge " + scene + " --ref auto --spp 1 -o " + deep, 2, {"PATH_MAX"});
}

// Class "silent garbage": setups that made a black, constant or one-pixel-high image with exit
// 0 are errors naming the parameter and its range; a chi² box so large its area is infinite is
// refused, not tested with -1 degrees of freedom.
TEST_F(Robustness, SilentGarbage) {
  const std::string scene = Write("scene.xml", kScene);
  const std::string out = " -q -o " + (dir_ / "x.exr").string();
  const auto camera_file = [&](const std::string& name, const std::string& hfov,
                               const std::string& vfov, const std::string& ar) {
    return Write(name, hfov + " " + vfov + " " + ar +
                           " 0.01 100\n2 1 5 7 1 5\n0 0 5 0.5 50\n0 0 -1 0 1 0 1 0 0\n"
                           "960 640 1\n3.5 0.25\n");
  };
  // yfov 179 on a wide film: the horizontal field of view is past 179 degrees.
  Expect(kPtlab + " render " + scene + " -r 480 8 -c " + camera_file("wide.txt", "50", "179", "1.5") + out,
         2, {"horizontal field of view", "out of range [0.001, 179] degrees"});
  Expect(kPtlab + " render " + scene + " -c " + camera_file("thin.txt", "50", "1e-30", "1.5") + out, 2,
         {"field of view", "out of range [0.001, 179] degrees"});
  Expect(kPtlab + " render " + scene + " -c " + camera_file("ar.txt", "50", "35", "1e-20") + out, 2,
         {"ar.txt:1: ar 1e-20 is out of range [1e-3, 1e3]"});
  // A 480x1 film keeps 40 degrees across: its vertical field is 0.08 degrees, which is fine;
  // 65536x1 is not.
  Expect(kPtlab + " render " + scene + " -r 65536 1" + out, 2,
         {"vertical field of view", "out of range [0.001, 179] degrees"});
  // A point light whose node transforms overflow float: a non-finite world position.
  const std::string light =
      "<node><scale>1e20 1e20 1e20</scale><node><scale>1e20 1e20 1e20</scale>"
      "<translate>1 1 1</translate><instance_light url=\"#L\"/></node></node>\n";
  std::string dae = Collada("", light + "<node><instance_geometry url=\"#tri\"/></node>\n");
  dae.replace(dae.find("<library_geometries>"), 0,
              "<library_lights><light id=\"L\"><technique_common><point><color>1 1 1</color>"
              "</point></technique_common></light></library_lights>\n");
  Expect(kPtlab + " render " + Write("far_light.dae", dae) + out, 2,
         {"far_light.dae: point light 0: position", "or not finite"});
  EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
  Write("ok.csv", "0.5,0.5\n");
  Expect(kChi2 + " check --domain box:-1e308,-1e308,1e308,1e308 --pdf-cmd true --samples " +
             (dir_ / "ok.csv").string(),
         2, {"corner 1 '-1e308' is out of range [-1e150, 1e150]"});
}

// Class "unbounded work or memory from a tiny file": instanced geometry is counted before it
// is expanded, nesting has a depth limit, per-render memory is estimated up front against
// --max-memory, sample files and FIFOs are refused or streamed, a pdf program's output is
// capped, a read-only or impossible output folder fails before anything renders, and converge
// --width checks the film size as render does.
TEST_F(Robustness, UnboundedWork) {
  const std::string scene = Write("scene.xml", kScene);
  // 30 levels of nodes, each instancing the one below twice: 2^30 triangles from ~3 KB.
  std::string library = "<node id=\"l0\"><instance_geometry url=\"#tri\"/></node>\n";
  for (int i = 1; i <= 30; ++i)
    library += "<node id=\"l" + std::to_string(i) + "\"><instance_node url=\"#l" +
               std::to_string(i - 1) + "\"/><instance_node url=\"#l" + std::to_string(i - 1) +
               "\"/></node>\n";
  const std::string doubling =
      Write("doubling.dae", Collada(library, "<node id=\"top\"><instance_node url=\"#l30\"/></node>\n"));
  EXPECT_LT(fs::file_size(doubling), 5000u);
  Expect(kPtlab + " render -q " + doubling + " -o " + (dir_ / "d.exr").string(), 2,
         {"doubling.dae:", "instances 1073741824 triangles", "would take about 160 GiB",
          "--max-memory"});
  // 10,000 nested nodes: a depth limit instead of a stack overflow.
  std::string deep;
  for (int i = 0; i < 10000; ++i) deep += "<node>";
  deep += "<instance_geometry url=\"#tri\"/>";
  for (int i = 0; i < 10000; ++i) deep += "</node>";
  Expect(kPtlab + " render -q " + Write("deep.dae", Collada("", deep + "\n")) + " -o " +
             (dir_ / "e.exr").string(),
         2, {"deep.dae:", "nested deeper than 256 levels"});
  // A Nori file of 4000 tessellated spheres (16 M triangles): every shape is counted before it
  // is appended, and the load stops at the budget (here --max-memory 0.05 GiB, ~84 spheres).
  std::string spheres = kScene.substr(0, kScene.find("<shape type=\"sphere\">"));
  for (int i = 0; i < 4000; ++i)
    spheres += "<shape type=\"sphere\"><point name=\"center\" value=\"0, 0, -" +
               std::to_string(i) + "\"/><float name=\"radius\" value=\"0.1\"/></shape>\n";
  Expect(kPtlab + " render -q " + Write("spheres.xml", spheres + "</scene>\n") +
             " --max-memory 0.05 -o " + (dir_ / "s.exr").string(),
         2, {"spheres.xml:", "with <shape type=\"sphere\"> the scene's", "--max-memory"});
  // -l at its documented maximum on a 1024x1024 film: refused with the estimate.
  Expect(kPtlab + " render -q " + scene + " -l 65536 --width 1024 --height 1024 --max-memory 4 -o " +
             (dir_ / "f.exr").string(),
         2, {"wavefronts", "for -l 65536", "expected at most 4 GiB (--max-memory)"});
  // A FIFO and a device as a sample file; a pdf program that prints forever.
  ASSERT_EQ(Run("mkfifo " + (dir_ / "fifo").string()), 0);
  Expect(kChi2 + " check --domain square --pdf-cmd true --samples " + (dir_ / "fifo").string(), 2,
         {"fifo: cannot read the sample file: it is not a regular file"});
  Expect(kChi2 + " check --domain square --pdf-cmd true --samples /dev/zero", 2,
         {"not a regular file"});
  // A 1 GiB raw sample file (sparse: no disk used) is refused from its size, before a read.
  ASSERT_EQ(Run("truncate -s 1G " + (dir_ / "big.f32").string()), 0);
  Expect(kChi2 + " check --domain square --dims 2 --pdf-cmd true --samples " +
             (dir_ / "big.f32").string(),
         2, {"big.f32: holds 134217728+ samples; expected at most 67108864"});
  fs::remove(dir_ / "big.f32");
  Write("ok.csv", "0.5,0.5\n0.25,0.75\n");
  Expect("timeout 60 " + kChi2 + " check --domain square --samples " + (dir_ / "ok.csv").string() +
             " --pdf-cmd \"yes 1\"",
         2, {"printed more than", "(killed)"});
  Expect(kPtlab + " converge " + scene + " --ref auto --spp 1 -o /proc/ptlab_no_such_folder", 3,
         {"cannot create the output folder"});
  EXPECT_EQ(Log().find("rendering the reference"), std::string::npos) << Log();
  const std::string tall = Write("tall.xml", SceneText(8, 4000));
  Expect(kPtlab + " converge " + tall + " --ref auto --spp 1 --width 16384 -o " +
             (dir_ / "conv").string(),
         2, {"--width", "expected each side in 1..65536"});
}


// The second probe of issue 41 (the newer surfaces: Mitsuba 3 scenes, bitmap textures,
// --strategies). A Mitsuba 3 scene of a 16x16 sensor and a constant emitter, with `body`.
std::string Mitsuba(const std::string& body) {
  return "<scene version=\"3.0.0\"><sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>"
         "<transform name=\"to_world\"><lookat origin=\"0,0,5\" target=\"0,0,0\" up=\"0,1,0\"/>"
         "</transform><sampler type=\"independent\"><integer name=\"sample_count\" value=\"1\"/>"
         "</sampler><film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/>"
         "<integer name=\"height\" value=\"16\"/></film></sensor><emitter type=\"constant\"/>\n" +
         body + "</scene>\n";
}

// Class "unbounded expansion of a small Mitsuba file": a parameter doubled in <default>s
// (2^34 x 16 bytes from 2 KB: hung), a file included 10 times by a file included 10 times
// ... 7 levels (10^7 spheres: hung; now at most 65536 includes and 32 MiB read again), and
// 2000 spheres in a shapegroup placed by 10^4 instances through repeated includes (48 KB:
// 20 M spheres, 3.3 GB RSS, exit 0). Each is refused by a budget that names its limit.
TEST_F(Robustness, MitsubaExpansion) {
  std::string laughs = "<default name=\"a0\" value=\"0123456789abcdef\"/>\n";
  for (int i = 1; i <= 34; ++i)
    laughs += "<default name=\"a" + std::to_string(i) + "\" value=\"$a" + std::to_string(i - 1) +
              "$a" + std::to_string(i - 1) + "\"/>\n";
  const std::string doubling = Write("doubling.xml", Mitsuba(laughs));
  Expect("timeout 60 " + kPtlab + " render -q " + doubling + " -o " + (dir_ / "a.exr").string(), 2,
         {"doubling.xml:", "would grow past 1048576 bytes"});
  Write("inc0.xml", "<scene version=\"3.0.0\"><shape type=\"sphere\"/></scene>\n");
  for (int level = 1; level <= 7; ++level) {
    std::string includes;
    for (int j = 0; j < 10; ++j)
      includes += "<include filename=\"inc" + std::to_string(level - 1) + ".xml\"/>\n";
    Write("inc" + std::to_string(level) + ".xml",
          "<scene version=\"3.0.0\">" + includes + "</scene>\n");
  }
  const std::string fan = Write("fan.xml", Mitsuba("<include filename=\"inc7.xml\"/>\n"));
  Expect("timeout 60 " + kPtlab + " render -q " + fan + " -o " + (dir_ / "b.exr").string(), 2,
         {"inc2.xml:9:1:", "more than 65536 includes read"});
  // Fewer, larger files included again and again: the bytes read again are budgeted too.
  Write("big0.xml", "<scene version=\"3.0.0\">" + std::string(1 << 20, ' ') + "</scene>\n");
  std::string big_includes;
  for (int j = 0; j < 40; ++j) big_includes += "<include filename=\"big0.xml\"/>\n";
  const std::string big = Write("big.xml", Mitsuba(big_includes));
  Expect("timeout 60 " + kPtlab + " render -q " + big + " -o " + (dir_ / "b2.exr").string(), 2,
         {"big.xml:", "is included again", "expected at most 33554432"});
  std::string group = "<scene version=\"3.0.0\"><shape type=\"shapegroup\" id=\"g\">\n";
  for (int i = 0; i < 2000; ++i) group += "<shape type=\"sphere\"/>\n";
  Write("group.xml", group + "</shape><include filename=\"ii4.xml\"/></scene>\n");
  Write("ii0.xml", "<scene version=\"3.0.0\"><shape type=\"instance\"><ref id=\"g\"/></shape></scene>\n");
  for (int level = 1; level <= 4; ++level) {
    std::string includes;
    for (int j = 0; j < 10; ++j)
      includes += "<include filename=\"ii" + std::to_string(level - 1) + ".xml\"/>\n";
    Write("ii" + std::to_string(level) + ".xml",
          "<scene version=\"3.0.0\">" + includes + "</scene>\n");
  }
  const std::string instances = Write("instances.xml", Mitsuba("<include filename=\"group.xml\"/>\n"));
  Expect("timeout 60 " + kPtlab + " render -q " + instances + " --max-memory 0.1 -o " +
             (dir_ / "c.exr").string(),
         2, {"ii0.xml:", "the instanced spheres and sdfgrids", "--max-memory"});
}

// Class "crash on deep nesting": 30,000 nested elements in one Mitsuba shape overflowed the
// stack of the recursive copy (SIGSEGV); now a depth limit.
TEST_F(Robustness, MitsubaDeepNesting) {
  std::string deep = "<shape type=\"sphere\">";
  for (int i = 0; i < 30000; ++i) deep += "<a>";
  for (int i = 0; i < 30000; ++i) deep += "</a>";
  const std::string scene = Write("deep.xml", Mitsuba(deep + "</shape>\n"));
  Expect(kPtlab + " render -q " + scene + " -o " + (dir_ / "a.exr").string(), 2,
         {"deep.xml:", "nested deeper than 256 levels"});
}

// Class "texture inputs not checked like other inputs": a bitmap texture that is a FIFO or
// /dev/zero read forever, a directory threw std::ios_base::failure past main (SIGABRT), and a
// 71-byte PNG claiming 16000x16000 pixels peaked at 3 GB. Now the input-file check (regular
// file, at most 2 GiB), the header-against-size check and the expansion budget.
TEST_F(Robustness, TextureInputChecks) {
  const auto scene_with = [&](const std::string& name, const std::string& texture) {
    return Write(name, Mitsuba("<shape type=\"sphere\"><bsdf type=\"diffuse\"><texture "
                               "type=\"bitmap\" name=\"reflectance\"><string name=\"filename\" "
                               "value=\"" + texture + "\"/></texture></bsdf></shape>\n"));
  };
  ASSERT_EQ(Run("mkfifo " + (dir_ / "fifo.png").string()), 0);
  fs::create_directory(dir_ / "folder.png");
  Expect("timeout 60 " + kPtlab + " render -q " + scene_with("fifo.xml", "fifo.png") + " -o " +
             (dir_ / "a.exr").string(),
         2, {"fifo.xml:", "fifo.png: cannot read the texture image: it is not a regular file"});
  Expect("timeout 60 " + kPtlab + " render -q " + scene_with("zero.xml", "/dev/zero") + " -o " +
             (dir_ / "b.exr").string(),
         2, {"zero.xml:", "/dev/zero: cannot read the texture image: it is not a regular file"});
  Expect(kPtlab + " render -q " + scene_with("dir.xml", "folder.png") + " -o " +
             (dir_ / "c.exr").string(),
         2, {"dir.xml:", "folder.png: cannot read the texture image: it is a directory"});
  // An 8-bit RGB PNG: signature, IHDR (16000 x 16000), IEND; stb reads the size from IHDR.
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) +
                          std::string("\0\0\0\x0dIHDR\0\0\x3e\x80\0\0\x3e\x80\x08\x02\0\0\0", 21) +
                          std::string("\0\0\0\0", 4) + std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  Write("claim.png", png);
  Expect(kPtlab + " render -q " + scene_with("claim.xml", "claim.png") + " -o " +
             (dir_ / "d.exr").string(),
         2, {"claim.xml:", "claim.png: header claims 16000x16000 pixels"});
}

// Class "--strategies not an output until the end": a --strategies DIR that is a file (the
// scene, the EXR output) failed only after the render and the image were written; a
// strategy image named like the -o output was not caught. Now DIR is created and probed, and
// its images join the output guard, before the render.
TEST_F(Robustness, StrategiesOutputCheckedFirst) {
  const std::string scene = Write("scene.xml", kScene);
  const std::string render = kPtlab + " render -q --integrator bdpt " + scene;
  Expect(render + " -o " + (dir_ / "a.exr").string() + " --strategies " + scene, 3,
         {"--strategies: cannot create the output folder '" + scene + "'"});
  EXPECT_FALSE(fs::exists(dir_ / "a.exr"));
  EXPECT_EQ(ReadFile(scene), kScene);
  Expect(render + " -o " + (dir_ / "s1_t2.exr").string() + " --strategies " + dir_.string(), 2,
         {"s1_t2.exr' (EXR output)", "(--strategies image) are the same file"});
  EXPECT_FALSE(fs::exists(dir_ / "s1_t2.exr"));
}

// Class "ambiguous converge variants": a key given twice in one --variant (ptlab's or a
// peer's) ran with whichever came last, exit 0; now a usage error before any render.
TEST_F(Robustness, ConvergeDuplicateVariantKeys) {
  const std::string scene = Write("scene.xml", kScene);
  const std::string converge = kPtlab + " converge " + scene + " --ref auto --spp 1 --no-plots -o " +
                               (dir_ / "conv").string() + " --variant ";
  Expect(converge + "integrator=bdpt,integrator=path_mis", 2,
         {"key 'integrator' is given twice; expected each key at most once"});
  Expect(converge + "renderer=mitsuba3,variant=scalar_rgb,variant=llvm_ad_rgb", 2,
         {"peer key 'variant' is given twice; expected each key at most once"});
  EXPECT_FALSE(fs::exists(dir_ / "conv" / "converge.csv"));
}

// Class "a scene's sample count past -s's range": a Mitsuba sample_count (or a Nori
// sampleCount) of 2e9 in a 600-byte file rendered for hours; now 1..1048576, as -s.
TEST_F(Robustness, SceneSampleCountRange) {
  std::string text = Mitsuba("");
  text.replace(text.find("\"sample_count\" value=\"1\""), 24, "\"sample_count\" value=\"2000000000\"");
  const std::string scene = Write("spp.xml", text);
  Expect("timeout 60 " + kPtlab + " render -q " + scene + " -o " + (dir_ / "a.exr").string(), 2,
         {"spp.xml:", "sample_count 2000000000 is out of range; expected 1..1048576 (as -s)"});
}

}  // namespace
}  // namespace ptlab
