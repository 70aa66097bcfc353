// ptlab and chi2 under mpirun (Open MPI): bit-identical images for any ranks x threads, the same
// chi² verdicts, and clear ends for bad input, a dead rank and an interrupt.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "engine/image/image_io.h"
#include "tests/test_data.h"
#include "tests/tools/command_test_util.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

#ifdef PTLAB_MPIEXEC
const std::string kMpirun = std::string(PTLAB_MPIEXEC) + " --allow-run-as-root --oversubscribe";
#endif
const std::string kBin = std::string(PTLAB_BINARY_DIR) + "/bin/";
const std::string kCbox = std::string(PTLAB_SOURCE_DIR) + "/scenes/cbox.xml";
const std::string kTable = test_data::Path("nori/epfl/scenes/pa5/table/table_mis.xml");

using test_util::ReadFile;
using test_util::RunShell;

fs::path TempDir(const std::string& name) { return test_util::TempDir("mpi/" + name); }

// Pixel data equal bit for bit (headers differ: seconds, ranks, threads).
void ExpectSameBits(const fs::path& a, const fs::path& b) {
  StatusOr<Image> ia = ReadImage(a.string()), ib = ReadImage(b.string());
  ASSERT_TRUE(ia.ok()) << ia.status().message();
  ASSERT_TRUE(ib.ok()) << ib.status().message();
  ASSERT_EQ(ia->width, ib->width);
  ASSERT_EQ(ia->height, ib->height);
  ASSERT_EQ(ia->rgb.size(), ib->rgb.size());
  EXPECT_EQ(std::memcmp(ia->rgb.data(), ib->rgb.data(),
                        ia->rgb.size() * sizeof(ia->rgb[0])),
            0)
      << a << " and " << b << " differ";
}

std::string Attribute(const fs::path& exr, const std::string& name) {
  auto attrs = ReadExrStringAttributes(exr.string());
  if (!attrs.ok()) return "";
  for (const auto& [k, v] : *attrs)
    if (k == name) return v;
  return "";
}

#ifdef PTLAB_MPIEXEC

// Shell text that waits (up to 120 s, polling every 0.1 s) until `log` shows the render's first
// progress line, so a signal is sent to a render that has started, however slow the machine.
std::string WaitForProgress(const fs::path& log) {
  return "for i in $(seq 1200); do grep -q '^progress' " + log.string() +
         " 2>/dev/null && break; sleep 0.1; done; ";
}

TEST(MpiRender, BitIdenticalToOneProcessForAnyRanksAndThreads) {
  // Two scenes, two integrators (cbox: direct_mis, table: path_mis), two passes of 16 spp.
  PTLAB_REQUIRE_DATA(kTable);
  for (const std::string& scene : {kCbox, kTable}) {
    const fs::path dir = TempDir(fs::path(scene).stem().string());
    const std::string args = " render " + scene + " --spp 32 --width 64 --height 48 --seed 5 -q";
    ASSERT_EQ(RunShell(kBin + "ptlab" + args + " --threads 1 -o " + (dir / "one.exr").string(),
                  dir / "one.log"),
              0)
        << ReadFile(dir / "one.log");
    for (const auto& [ranks, threads] : {std::pair{1, 1}, {2, 1}, {3, 1}, {2, 2}}) {
      const std::string name = std::to_string(ranks) + "x" + std::to_string(threads);
      const fs::path out = dir / (name + ".exr");
      ASSERT_EQ(RunShell(kMpirun + " -np " + std::to_string(ranks) + " " + kBin + "ptlab" + args +
                        " --threads " + std::to_string(threads) + " -o " + out.string(),
                    dir / (name + ".log")),
                0)
          << ReadFile(dir / (name + ".log"));
      ExpectSameBits(dir / "one.exr", out);
      EXPECT_EQ(Attribute(out, "ptlab:ranks"), std::to_string(ranks));
      EXPECT_EQ(Attribute(out, "ptlab:threads"), std::to_string(threads));
      EXPECT_FALSE(fs::exists(dir / (name + ".exr.tmp")));
    }
  }
}

// Two ranks started in two folders read "scene.xml" from each: same path, other bytes.
void WriteSceneIn(const fs::path& dir, const std::string& sample_count) {
  fs::create_directories(dir);
  std::string xml = ReadFile(kCbox);
  const std::string from = "name=\"sampleCount\" value=\"64\"";
  const size_t at = xml.find(from);
  ASSERT_NE(at, std::string::npos);
  xml.replace(at, from.size(), "name=\"sampleCount\" value=\"" + sample_count + "\"");
  std::ofstream(dir / "scene.xml") << xml;
}

// mpirun starting `command` once in dir/a (rank 0) and once in dir/b (rank 1).
std::string TwoFolders(const fs::path& dir, const std::string& command) {
  return kMpirun + " -np 1 -wdir " + (dir / "a").string() + " " + command + " : -np 1 -wdir " +
         (dir / "b").string() + " " + command;
}

TEST(MpiRender, RankReadingOtherBytesStopsTheJobNamingTheFile) {
  const fs::path dir = TempDir("other_bytes");
  WriteSceneIn(dir / "a", "64");
  WriteSceneIn(dir / "b", "65");
  const fs::path out = dir / "out.exr";
  const std::string render = kBin + "ptlab render scene.xml --spp 4 --width 32 --height 32 -q -o " +
                             out.string();
  const int rc = RunShell(TwoFolders(dir, render), dir / "log");
  const std::string log = ReadFile(dir / "log");
  EXPECT_NE(rc, 0) << log;
  EXPECT_NE(log.find("rank 1: scene.xml: its bytes differ from rank 0"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out));
}

TEST(MpiRender, RankThatCannotLoadStopsTheJobNamingRankAndReason) {
  const fs::path dir = TempDir("load_error");
  WriteSceneIn(dir / "a", "64");
  fs::create_directories(dir / "b");
  std::ofstream(dir / "b" / "scene.xml") << "<scene><integrator type=\"nope\"/></scene>\n";
  const fs::path out = dir / "out.exr";
  const std::string render = kBin + "ptlab render scene.xml --spp 4 -q -o " + out.string();
  const int rc = RunShell(TwoFolders(dir, render), dir / "log");
  const std::string log = ReadFile(dir / "log");
  EXPECT_NE(rc, 0) << log;
  EXPECT_NE(log.find("rank 1: scene.xml:1:"), std::string::npos) << log;
  EXPECT_EQ(log.find("rank 0:"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out));
}

TEST(MpiRender, KilledRankEndsTheJobWithoutOutput) {
  const fs::path dir = TempDir("killed_rank");
  const fs::path out = dir / "killed.exr";
  // A long render; once it reports progress, rank 1 (found by its OMPI_COMM_WORLD_RANK) is
  // killed.
  const std::string command =
      kMpirun + " -np 2 " + kBin + "ptlab render " + kCbox +
      " --spp 64000 --width 64 --height 48 --threads 1 -o " + out.string() + " 2> " +
      (dir / "job.err").string() + " & job=$!; " + WaitForProgress(dir / "job.err") +
      "for p in $(pgrep -f \"ptlab render .*killed.exr\"); do "
      "grep -qz OMPI_COMM_WORLD_RANK=1 /proc/$p/environ 2>/dev/null && kill -KILL $p; done; "
      "wait $job";
  const int rc = RunShell(command, dir / "log");
  const std::string log = ReadFile(dir / "log") + ReadFile(dir / "job.err");
  EXPECT_NE(rc, 0) << log;
  EXPECT_NE(log.find("rank 1"), std::string::npos) << log;
  EXPECT_NE(log.find("signal 9"), std::string::npos) << log;
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().rfind("killed", 0), std::string::npos)
        << "left behind: " << entry.path();
}

// SIGINT once the render has reported progress (polled, not a fixed sleep): the job ends with a
// non-zero status (the ranks exit 130), the image holds whole passes, and it is bit for bit the
// image one process renders with the recorded samples per pixel. The render is sized to last
// about 20 s uninterrupted, so that the signal, which mpirun forwards, reaches the ranks
// before the last pass on a loaded machine (at 3200 spp a faster render once finished first).
TEST(MpiRender, InterruptWritesTheCompletedPasses) {
  const fs::path dir = TempDir("interrupt");
  const fs::path out = dir / "int.exr";
  const std::string args = " --width 64 --height 48 --threads 1 ";
  const std::string command = kMpirun + " -np 2 " + kBin + "ptlab render " + kCbox +
                              " --spp 64000" + args + "-o " + out.string() + " 2> " +
                              (dir / "job.err").string() + " & job=$!; " +
                              WaitForProgress(dir / "job.err") + "kill -INT $job; wait $job";
  const int rc = RunShell(command, dir / "log");
  const std::string log = ReadFile(dir / "log") + ReadFile(dir / "job.err");
  EXPECT_NE(rc, 0) << "an interrupted job must not report success\n" << log;
  ASSERT_TRUE(fs::exists(out)) << log;
  EXPECT_TRUE(fs::exists(dir / "int.png"));
  EXPECT_NE(log.find("interrupted, wrote partial image"), std::string::npos) << log;
  EXPECT_EQ(Attribute(out, "ptlab:interrupted"), "true");
  EXPECT_EQ(Attribute(out, "ptlab:ranks"), "2");
  const int spp = std::atoi(Attribute(out, "ptlab:spp").c_str());
  EXPECT_GT(spp, 0);
  EXPECT_LT(spp, 64000);
  EXPECT_EQ(spp % 16, 0) << "only whole passes are kept";
  const fs::path one = dir / "one.exr";
  ASSERT_EQ(RunShell(kBin + "ptlab render " + kCbox + " --spp " + std::to_string(spp) + args +
                         "-q -o " + one.string(),
                     dir / "one.log"),
            0)
      << ReadFile(dir / "one.log");
  ExpectSameBits(out, one);
}

TEST(MpiChi2, SameVerdictsAndPValuesAsOneProcess) {
  const fs::path dir = TempDir("chi2");
  const std::string subjects =
      " warp/uniform_square warp/tent warp/uniform_disk broken/tent_pdf_scaled "
      "warp/cosine_hemisphere distribution/2d area_light/quad broken/uniform_disk_linear_r";
  ASSERT_EQ(RunShell(kBin + "chi2" + subjects, dir / "one.log"), 0) << ReadFile(dir / "one.log");
  ASSERT_EQ(RunShell(kMpirun + " -np 2 " + kBin + "chi2" + subjects, dir / "two.log"), 0)
      << ReadFile(dir / "two.log");
  // Every line after the run's header line (which adds the rank count) is the same.
  const std::string one = ReadFile(dir / "one.log"), two = ReadFile(dir / "two.log");
  EXPECT_NE(two.find(", 2 ranks\n"), std::string::npos) << two;
  EXPECT_EQ(one.substr(one.find('\n')), two.substr(two.find('\n')));
}

TEST(MpiNoriTest, SameLinesAsOneProcess) {
  // Scene t-tests, BSDF t-tests and BSDF chi2 tests, their cases shared among 2 ranks.
  const fs::path dir = TempDir("nori_test");
  const std::string tests = test_data::Path("nori/epfl/scenes/pa5/tests/");
  PTLAB_REQUIRE_DATA(tests);
  for (const std::string name : {"test-direct", "ttest-microfacet", "chi2test-microfacet"}) {
    const std::string file = tests + name + ".xml";
    ASSERT_EQ(RunShell(kBin + "ptlab test " + file, dir / (name + ".one")), 0)
        << ReadFile(dir / (name + ".one"));
    ASSERT_EQ(RunShell(kMpirun + " -np 2 " + kBin + "ptlab test " + file, dir / (name + ".two")), 0)
        << ReadFile(dir / (name + ".two"));
    // Equal but for the run time in the summary line.
    auto without_time = [](std::string s) {
      const size_t at = s.rfind(" (");
      return at == std::string::npos ? s : s.substr(0, at);
    };
    EXPECT_EQ(without_time(ReadFile(dir / (name + ".one"))),
              without_time(ReadFile(dir / (name + ".two"))));
  }
}

// Issue 41, class "MPI ranks that disagree": ranks with other effective options or other
// bytes of a -c file stop before rendering, every one of them, naming the rank and the option
// or file; nothing is written (different -s used to write and then hang).
TEST(MpiRender, RanksThatDisagreeStopNamingTheRankAndTheOptionOrFile) {
  const fs::path dir = TempDir("disagree");
  WriteSceneIn(dir / "a", "4");
  WriteSceneIn(dir / "b", "4");
  const fs::path out = dir / "out.exr";
  const std::string render =
      kBin + "ptlab render scene.xml --width 32 --height 32 -q -o " + out.string();
  const auto run = [&](const std::string& a, const std::string& b, const std::string& expect) {
    SCOPED_TRACE(a + " | " + b);
    const std::string command = kMpirun + " -np 1 -wdir " + (dir / "a").string() + " " + render +
                                a + " : -np 1 -wdir " + (dir / "b").string() + " " + render + b;
    const int rc = RunShell("timeout 60 " + command, dir / "log");
    const std::string log = ReadFile(dir / "log");
    EXPECT_NE(rc, 0) << log;
    EXPECT_NE(rc, 124) << "hung: " << log;
    EXPECT_NE(log.find(expect), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(out));
  };
  run(" --spp 4", " --spp 8",
      "rank 1: option samples per pixel (-s) is '8' here but '4' on rank 0");
  run(" --seed 1", " --seed 2", "rank 1: option seed (--seed) is '2' here but '1' on rank 0");
  run(" -b 0.1", " -b 0.2", "rank 1: option lens radius (-b)");
  std::ofstream(dir / "a" / "camera.txt") << "50 35 1.5 0.01 100\n2 1 5 7 1 5\n0 0 5 0.5 50\n"
                                             "0 0 -1 0 1 0 1 0 0\n960 640 1\n3.5 0.25\n";
  std::ofstream(dir / "b" / "camera.txt") << "50 35 1.5 0.01 100\n2 1 5 7 1 5\n0 0 5 0.5 50\n"
                                             "0 0 -1 0 1 0 1 0 0\n960 640 1\n3.5 0.5\n";
  run(" -c camera.txt", " -c camera.txt",
      "rank 1: camera.txt: its bytes differ from rank 0's copy");
}

#else

TEST(MpiRender, NeedsMpi) {
  GTEST_SKIP() << "ptlab was built without MPI (./lab installs libopenmpi-dev and openmpi-bin)";
}

#endif

}  // namespace
}  // namespace ptlab
