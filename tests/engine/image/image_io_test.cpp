// Tests of engine/image/image_io (round trips, HDR read, errors, atomic writes) and srgb.h.
#include "engine/image/image_io.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "engine/core/rng.h"
#include "engine/image/srgb.h"
#include "tests/test_data.h"

namespace ptlab {
namespace {

namespace fs = std::filesystem;

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// Random values over many magnitudes and both signs, plus the special floats.
Image TestImage(int w, int h, uint64_t seed) {
  Pcg32 rng(seed, 7);
  Image img(w, h);
  for (float& v : img.rgb) {
    const float mantissa = rng.NextFloat() - 0.25f;  // first: operands are unsequenced
    v = mantissa * std::ldexp(1.0f, int(rng.NextUint() % 40) - 20);
  }
  img.rgb[0] = std::numeric_limits<float>::denorm_min();
  img.rgb[1] = -0.0f;
  img.rgb[2] = std::numeric_limits<float>::max();
  img.rgb[3] = std::numeric_limits<float>::infinity();
  img.rgb[4] = std::numeric_limits<float>::quiet_NaN();
  return img;
}

bool BitEqual(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.rgb.size() == b.rgb.size() &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

// Paths of files in `dir` whose name contains ".tmp-" (leftover temporaries).
std::vector<std::string> Temporaries(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().filename().string().find(".tmp-") != std::string::npos) out.push_back(e.path());
  }
  return out;
}

class ImageIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("ptlab_image_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST(ImageIoSrgb, ExactPiecewiseCurve) {
  EXPECT_EQ(SrgbToLinear(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(SrgbToLinear(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(LinearToSrgb(1.0f), 1.0f);
  // Toe: v / 12.92 below 0.04045; power law above.
  EXPECT_FLOAT_EQ(SrgbToLinear(10.0f / 255.0f), float(10.0 / 255.0 / 12.92));
  EXPECT_FLOAT_EQ(SrgbToLinear(128.0f / 255.0f), 0.21586050011389926f);
  EXPECT_FLOAT_EQ(LinearToSrgb(0.5f), 0.7353569830524495f);
  EXPECT_FLOAT_EQ(LinearToSrgb(0.001f), 0.01292f);
  // The two pieces meet at the thresholds.
  EXPECT_NEAR(LinearToSrgb(0.0031308f), 0.04045f, 1e-6);
  EXPECT_NEAR(SrgbToLinear(0.04045f), 0.0031308f, 1e-7);
  for (int k = 0; k <= 255; ++k) {
    const float v = k / 255.0f;
    EXPECT_NEAR(LinearToSrgb(SrgbToLinear(v)), v, 1e-6) << k;
  }
  const Color3f c = LinearToSrgb(Color3f{0.5f, 0.001f, 1.0f});
  EXPECT_FLOAT_EQ(c.r, 0.7353569830524495f);
  EXPECT_FLOAT_EQ(c.g, 0.01292f);
}

TEST_F(ImageIo, ExrRoundTripIsBitExactWithAttributes) {
  const Image img = TestImage(37, 23, 1);
  const std::vector<std::pair<std::string, std::string>> attrs = {
      {"ptlab.scene", "cbox \"quoted\" ü"}, {"ptlab.spp", "64"}};
  const std::string path = Path("a.exr");
  ASSERT_TRUE(WriteExr(path, img, attrs).ok());
  StatusOr<Image> back = ReadImage(path);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_TRUE(BitEqual(img, *back));
  auto read_attrs = ReadExrStringAttributes(path);
  ASSERT_TRUE(read_attrs.ok()) << read_attrs.status().message();
  EXPECT_EQ(*read_attrs, attrs);
  // ZIP compression: the "compression" attribute (type "compression", 1 byte) holds 3.
  const std::string bytes = ReadBytes(path);
  const std::string key("compression\0compression\0\x01\0\0\0", 28);
  const size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(int(bytes[at + key.size()]), 3);
  EXPECT_TRUE(Temporaries(dir_).empty());
}

TEST_F(ImageIo, PfmRoundTripIsBitExactAndBottomToTop) {
  const Image img = TestImage(5, 3, 2);
  const std::string path = Path("a.pfm");
  ASSERT_TRUE(WritePfm(path, img).ok());
  StatusOr<Image> back = ReadImage(path);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_TRUE(BitEqual(img, *back));
  const std::string bytes = ReadBytes(path);
  const std::string header = "PF\n5 3\n-1.0\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  ASSERT_EQ(bytes.size(), header.size() + 5 * 3 * 3 * 4);
  float first;  // The first stored pixel is the bottom-left one, little endian.
  std::memcpy(&first, bytes.data() + header.size(), 4);
  EXPECT_EQ(first, img.At(0, 2).r);
}

TEST_F(ImageIo, PfmReadsBigEndianGreyscale) {
  // "Pf" = one channel; positive scale = big endian; rows bottom to top.
  std::string bytes = "Pf\n2 2\n1.0\n";
  for (float v : {1.0f, 2.0f, 3.0f, 4.0f}) {
    const uint32_t u = std::bit_cast<uint32_t>(v);
    for (int s = 24; s >= 0; s -= 8) bytes += char((u >> s) & 0xff);
  }
  WriteBytes(Path("g.pfm"), bytes);
  StatusOr<Image> img = ReadImage(Path("g.pfm"));
  ASSERT_TRUE(img.ok()) << img.status().message();
  ASSERT_EQ(img->width, 2);
  ASSERT_EQ(img->height, 2);
  EXPECT_EQ(img->At(0, 1).r, 1.0f);  // first stored row = bottom row
  EXPECT_EQ(img->At(1, 1).g, 2.0f);
  EXPECT_EQ(img->At(0, 0).b, 3.0f);
  EXPECT_EQ(img->At(1, 0).r, 4.0f);
}

TEST_F(ImageIo, PngRoundTripQuantisesInSrgb) {
  Pcg32 rng(3, 1);
  Image img(17, 9);
  for (float& v : img.rgb) v = rng.NextFloat();
  img.rgb[0] = 5.0f;                                     // clamps to 255
  img.rgb[1] = -1.0f;                                    // clamps to 0
  img.rgb[2] = std::numeric_limits<float>::quiet_NaN();  // becomes 0
  const std::string path = Path("a.png");
  ASSERT_TRUE(WritePng(path, img).ok());
  StatusOr<Image> back = ReadImage(path);
  ASSERT_TRUE(back.ok()) << back.status().message();
  ASSERT_EQ(back->width, 17);
  ASSERT_EQ(back->height, 9);
  EXPECT_EQ(back->rgb[0], 1.0f);
  EXPECT_EQ(back->rgb[1], 0.0f);
  EXPECT_EQ(back->rgb[2], 0.0f);
  for (size_t i = 3; i < img.rgb.size(); ++i) {
    const long k = std::lround(LinearToSrgb(img.rgb[i]) * 255.0f);
    ASSERT_EQ(back->rgb[i], SrgbToLinear(float(k / 255.0))) << i;
  }
}

TEST_F(ImageIo, PngDecodesEveryCodeWithTheExactCurve) {
  std::vector<unsigned char> codes(256 * 3);
  for (int k = 0; k < 256; ++k) codes[3 * k] = codes[3 * k + 1] = codes[3 * k + 2] = uint8_t(k);
  ASSERT_NE(stbi_write_png(Path("ramp.png").c_str(), 256, 1, 3, codes.data(), 256 * 3), 0);
  StatusOr<Image> img = ReadImage(Path("ramp.png"));
  ASSERT_TRUE(img.ok()) << img.status().message();
  for (int k = 0; k < 256; ++k) {
    const double v = k / 255.0;
    const double linear = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    ASSERT_FLOAT_EQ(img->At(k, 0).g, float(linear)) << k;
  }
}

TEST_F(ImageIo, ReadsRadianceHdr) {
  // Powers of two and 0.75 are exact in RGBE when the pixel's largest channel sets the exponent.
  const float pixels[] = {0.5f,  0.25f,  0.125f, 2.0f, 1.0f, 0.0f,
                          0.75f, 0.375f, 0.0f,   8.0f, 4.0f, 6.0f};
  ASSERT_NE(stbi_write_hdr(Path("a.hdr").c_str(), 2, 2, 3, pixels), 0);
  StatusOr<Image> img = ReadImage(Path("a.hdr"));
  ASSERT_TRUE(img.ok()) << img.status().message();
  ASSERT_EQ(img->width, 2);
  ASSERT_EQ(img->height, 2);
  for (int i = 0; i < 12; ++i) EXPECT_EQ(img->rgb[size_t(i)], pixels[i]) << i;
}

TEST_F(ImageIo, DetectsFormatByMagicNotExtension) {
  const Image img = TestImage(4, 4, 5);
  ASSERT_TRUE(WritePfm(Path("really_pfm.exr"), img).ok());
  ASSERT_TRUE(WriteExr(Path("really_exr.png"), img).ok());
  StatusOr<Image> a = ReadImage(Path("really_pfm.exr"));
  StatusOr<Image> b = ReadImage(Path("really_exr.png"));
  ASSERT_TRUE(a.ok()) << a.status().message();
  ASSERT_TRUE(b.ok()) << b.status().message();
  EXPECT_TRUE(BitEqual(img, *a));
  EXPECT_TRUE(BitEqual(img, *b));
  EXPECT_EQ(DetectImageFormat(reinterpret_cast<const unsigned char*>("#?RADIANCE\n"), 11),
            ImageFormat::kHdr);
  EXPECT_EQ(DetectImageFormat(reinterpret_cast<const unsigned char*>("PF"), 2),
            ImageFormat::kUnknown);
}

TEST_F(ImageIo, WriteImageDispatchesOnExtension) {
  const Image img = TestImage(3, 2, 6);
  ASSERT_TRUE(WriteImage(Path("x.EXR"), img).ok());
  ASSERT_TRUE(WriteImage(Path("x.pfm"), img).ok());
  EXPECT_EQ(ReadBytes(Path("x.EXR")).substr(0, 4), "\x76\x2f\x31\x01");
  EXPECT_EQ(ReadBytes(Path("x.pfm")).substr(0, 3), "PF\n");
  const Status s = WriteImage(Path("x.jpg"), img);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("x.jpg"), std::string::npos) << s.message();
}

// Every read error names the file and says what was wrong.
void ExpectReadError(const std::string& path, const std::string& what) {
  StatusOr<Image> img = ReadImage(path);
  ASSERT_FALSE(img.ok()) << path;
  EXPECT_NE(img.status().message().find(path), std::string::npos) << img.status().message();
  EXPECT_NE(img.status().message().find(what), std::string::npos) << img.status().message();
}

TEST_F(ImageIo, UnreadableFilesGiveErrorsNamingTheFile) {
  ExpectReadError(Path("missing.exr"), "No such file");
  ExpectReadError(dir_.string(), "directory");
  WriteBytes(Path("empty.png"), "");
  ExpectReadError(Path("empty.png"), "empty");
  WriteBytes(Path("garbage.exr"), "GARBAGE!garbage");
  ExpectReadError(Path("garbage.exr"), "unknown image format");
  WriteBytes(Path("bad_size.pfm"), std::string("PF\n-3 2\n-1.0\n") + std::string(100, '\0'));
  ExpectReadError(Path("bad_size.pfm"), "bad PFM header");
  WriteBytes(Path("bad_scale.pfm"), std::string("PF\n1 1\nzero\n") + std::string(12, '\0'));
  ExpectReadError(Path("bad_scale.pfm"), "bad PFM header");
}

// Issue 12, finding 7: a header claiming far more pixels than the file holds is refused before
// the pixels are allocated (a 16383x16383 Radiance HDR of 100 bytes allocated 3 GB).
TEST_F(ImageIo, HeadersClaimingMorePixelsThanTheFileHoldsAreRefused) {
  ExpectReadError(PTLAB_SOURCE_DIR "/tests/data/bad/huge_claim.hdr", "can hold");
  // An EXR of one pixel whose dataWindow is patched to one line of 2^24 pixels: OpenEXR 3
  // refuses it itself (bytes per scanline; taller windows: the line offset table runs past
  // the end of the file) before ptlab's own pixels-per-byte check is reached.
  Image one(1, 1);
  ASSERT_TRUE(WriteExr(Path("one.exr"), one, {}).ok());
  std::ifstream in(Path("one.exr"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0';
  const size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  const int32_t box[4] = {0, 0, (1 << 24) - 1, 0};
  std::memcpy(&bytes[at + key.size() + 4], box, sizeof(box));
  WriteBytes(Path("claim.exr"), bytes);
  ExpectReadError(Path("claim.exr"), "EXR");
}

// Issue 12, finding 6: a device or a FIFO is refused before it is read (/dev/zero used to be
// read until memory ran out, a FIFO blocked forever).
TEST_F(ImageIo, DevicesAndFifosAreRefusedBeforeReading) {
  ExpectReadError("/dev/zero", "not a regular file");
  const std::string fifo = Path("pipe.exr");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  ExpectReadError(fifo, "not a regular file");
}

TEST_F(ImageIo, TruncatedFilesGiveErrorsNamingTheFile) {
  const Image img = TestImage(64, 48, 7);
  ASSERT_TRUE(WriteExr(Path("t.exr"), img).ok());
  ASSERT_TRUE(WritePfm(Path("t.pfm"), img).ok());
  ASSERT_TRUE(WritePng(Path("t.png"), img).ok());
  for (const char* name : {"t.exr", "t.pfm", "t.png"}) {
    const std::string full = ReadBytes(Path(name));
    WriteBytes(Path(name), full.substr(0, full.size() / 2));
  }
  ExpectReadError(Path("t.exr"), "EXR");
  ExpectReadError(Path("t.pfm"), "truncated PFM");
  ExpectReadError(Path("t.png"), "PNG");
  // Cut inside the header too.
  const std::string exr = ReadBytes(Path("t.exr"));
  WriteBytes(Path("h.exr"), exr.substr(0, 40));
  ExpectReadError(Path("h.exr"), "EXR");
  WriteBytes(Path("h.pfm"), "PF\n64 48");
  ExpectReadError(Path("h.pfm"), "PFM");
}

TEST_F(ImageIo, WriteIntoMissingDirectoryFailsCleanly) {
  const Image img = TestImage(4, 4, 8);
  const std::string path = Path("no/such/dir/out.exr");
  for (const Status& s : {WriteExr(path, img), WritePng(path, img), WritePfm(path, img)}) {
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.message().find(path), std::string::npos) << s.message();
  }
  EXPECT_FALSE(fs::exists(Path("no")));
  EXPECT_TRUE(Temporaries(dir_).empty());
}

TEST_F(ImageIo, FailedWriteLeavesExistingFileUntouched) {
  const Image old_image = TestImage(8, 8, 9);
  const Image new_image = TestImage(16, 16, 10);
  const std::string path = Path("out.exr");
  ASSERT_TRUE(WriteExr(path, old_image).ok());
  const std::string old_bytes = ReadBytes(path);
  // Block the temporary: a directory where the writer wants to create its temporary file.
  const std::string blocker = path + ".tmp-" + std::to_string(::getpid());
  fs::create_directory(blocker);
  for (const Status& s :
       {WriteExr(path, new_image), WritePng(path, new_image), WritePfm(path, new_image)}) {
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.message().find(path), std::string::npos) << s.message();
  }
  EXPECT_TRUE(fs::is_directory(blocker));  // not ours: left alone
  fs::remove(blocker);
  EXPECT_EQ(ReadBytes(path), old_bytes);
  // A header attribute OpenEXR reserves fails before anything is written.
  EXPECT_FALSE(WriteExr(path, new_image, {{"compression", "none"}}).ok());
  EXPECT_FALSE(WriteExr(path, new_image, {{"", "x"}}).ok());
  // An inconsistent image fails validation.
  Image broken(4, 4);
  broken.rgb.resize(5);
  EXPECT_FALSE(WritePfm(path, broken).ok());
  EXPECT_EQ(ReadBytes(path), old_bytes);
  EXPECT_TRUE(Temporaries(dir_).empty());
  // A successful write replaces it.
  ASSERT_TRUE(WriteExr(path, new_image).ok());
  StatusOr<Image> back = ReadImage(path);
  ASSERT_TRUE(back.ok());
  EXPECT_TRUE(BitEqual(*back, new_image));
  EXPECT_TRUE(Temporaries(dir_).empty());
}

TEST_F(ImageIo, FailedRenameRemovesTheTemporary) {
  // The output path is a non-empty directory: the temporary is written, the rename fails.
  const std::string path = Path("occupied.png");
  fs::create_directories(path + "/child");
  const Status s = WritePng(path, TestImage(4, 4, 11));
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find(path), std::string::npos) << s.message();
  EXPECT_TRUE(fs::is_directory(path + "/child"));
  EXPECT_TRUE(Temporaries(dir_).empty());
}

TEST(ImageIoNori, BunnyReference) {
  const std::string path = test_data::Path("nori/epfl/references/bunny.exr");
  PTLAB_REQUIRE_DATA(path);
  StatusOr<Image> img = ReadImage(path);
  ASSERT_TRUE(img.ok()) << img.status().message();
  ASSERT_EQ(img->width, 768);
  ASSERT_EQ(img->height, 768);
  double sum[3] = {0, 0, 0};
  for (size_t i = 0; i < img->rgb.size(); ++i) sum[i % 3] += img->rgb[i];
  const double n = 768.0 * 768.0;
  EXPECT_NEAR(sum[0] / n, 0.1267, 1e-3);
  EXPECT_NEAR(sum[1] / n, 0.1378, 1e-3);
  EXPECT_NEAR(sum[2] / n, 0.2568, 1e-3);
}

TEST(ImageIoNori, EnvmapHdrMatchesItsLosslessExr) {
  // SOURCES.md: the envmap .exr files are lossless float32 conversions of the .hdr originals.
  const std::string base = test_data::Path("envmaps/pedestrian_overpass_1k");
  PTLAB_REQUIRE_DATA(base + ".hdr");
  PTLAB_REQUIRE_DATA(base + ".exr");
  StatusOr<Image> hdr = ReadImage(base + ".hdr");
  StatusOr<Image> exr = ReadImage(base + ".exr");
  ASSERT_TRUE(hdr.ok()) << hdr.status().message();
  ASSERT_TRUE(exr.ok()) << exr.status().message();
  EXPECT_EQ(hdr->width, 1024);
  EXPECT_EQ(hdr->height, 512);
  EXPECT_TRUE(BitEqual(*hdr, *exr));
}

}  // namespace
}  // namespace ptlab
