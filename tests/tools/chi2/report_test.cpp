// Unit tests of the chi-square lab's reports: heat-map layout and the written PNG/CSV pair.
#include "tools/chi2/report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/image/image_io.h"

namespace ptlab {
namespace {

Chi2Result SmallResult() {
  Chi2Result r;
  r.name = "test/small grid";
  r.domain = Chi2Domain::UnitSquare();
  r.xres = 4, r.yres = 2;
  r.observed = {10, 10, 10, 3, 10, 10, 10, 10};
  r.expected = {10, 10, 10, 0, 10, 10, 10, 10};  // cell (3, 0): samples, zero mass
  return r;
}

TEST(Chi2Report, HeatmapsHaveThreePanelsWithYUp) {
  const Image img = Chi2Heatmaps(SmallResult());
  // 360 / 4 = 90 pixels per cell; 3 panels of 360 x 180 and 6-pixel margins.
  EXPECT_EQ(img.width, 3 * 360 + 4 * 6);
  EXPECT_EQ(img.height, 180 + 2 * 6);
  // Cell (3, 0) is at the bottom right of the difference panel, magenta.
  const Color3f c = img.At(6 + 2 * (360 + 6) + 3 * 90 + 45, 6 + 90 + 45);
  EXPECT_NEAR(c.r, 1.0f, 1e-6);
  EXPECT_NEAR(c.g, 0.0f, 1e-6);
  EXPECT_NEAR(c.b, 1.0f, 1e-6);
  // Observed == expected elsewhere: white in the difference panel.
  const Color3f w = img.At(6 + 2 * (360 + 6) + 45, 6 + 45);
  EXPECT_NEAR(w.r, w.b, 1e-6);
  EXPECT_GT(w.g, 0.9f);
}

TEST(Chi2Report, FileStemKeepsOnlySafeCharacters) {
  EXPECT_EQ(Chi2FileStem("warp/cosine_hemisphere"), "warp_cosine_hemisphere");
  EXPECT_EQ(Chi2FileStem("bsdf/rough a=0.1"), "bsdf_rough_a_0.1");
  EXPECT_EQ(Chi2FileStem(""), "_");
}

TEST(Chi2Report, WritesPngAndCsv) {
  const std::string dir = ::testing::TempDir() + "/ptlab_chi2_report_test";
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(WriteChi2Report(dir, SmallResult()).ok());
  StatusOr<Image> png = ReadImage(dir + "/test_small_grid.png");
  ASSERT_TRUE(png.ok()) << png.status().message();
  EXPECT_EQ(png->width, 3 * 360 + 24);
  std::ifstream csv(dir + "/test_small_grid.csv");
  std::string header, first;
  std::getline(csv, header);
  std::getline(csv, first);
  EXPECT_EQ(header, "ix,iy,x0,x1,y0,y1,observed,expected");
  EXPECT_EQ(first, "0,0,0,0.25,0,0.5,10,10.000000");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ptlab
