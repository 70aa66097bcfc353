// imgdiff CLI: compares test image A with reference B (or runs Mitsuba 3's Z test); exit = verdict.
#include <CLI/CLI.hpp>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "engine/image/image_io.h"
#include "tools/cli_checks.h"
#include "tools/common/exit_codes.h"
#include "tools/common/output_guard.h"
#include "tools/imgdiff/imgdiff.h"
#include "tools/imgdiff/ztest.h"

namespace {

using ptlab::kExitFailed;
using ptlab::kExitOk;
using ptlab::kExitRunFailed;
using ptlab::kExitUsage;

constexpr const char* kFooter = R"(Metrics (A = test, B = reference; pixels with a NaN/Inf channel
in A or B are skipped):
  MAE, MSE, RMSE per channel and over all channels; relMSE = mean((a-b)^2 / (b^2 + eps)),
  eps = 1e-2; PSNR = 10 log10(peak^2 / MSE) with peak = 1 if B is a PNG (LDR), else the
  maximum finite value of B; max abs error with its pixel (x, y from the top-left) and channel;
  NaN/Inf pixel counts of each image; channel means of each image (over its finite pixels) and
  their relative difference (meanA - meanB) / meanB.
Blocks: N x N tiles from the top-left; partial edge blocks are INCLUDED (mean over the pixels
  they cover); a block's mean is over its pixels and the three channels. Among blocks whose mean
  in B is >= --block-min, the share whose mean in A is within --tol of B's:
  |meanA - meanB| < tol * meanB.
--parity F: PARITY.md's P(F): every channel mean of A within 1 % of B's (strictly), no NaN/Inf
  in A, and the share of 32x32 blocks (B mean >= 0.01) within 5 % is >= F. --flip-x applies.
--heatmap: per-pixel signed relative error of the channel mean, (a-b)/sqrt(b^2 + 1e-2), in a
  blue-white-red map: -scale blue, 0 white, +scale red; NaN/Inf pixels green. Written as PNG
  (or EXR/PFM by the extension).
With any --fail-* threshold, NaN/Inf pixels in A also fail.
--ztest REF VAR IMAGE --spp N: Mitsuba 3's render test instead of A/B (docs/mitsuba-tests.md):
  REF, VAR and IMAGE converted from RGB to XYZ (VAR is a per-sample variance stored as Mitsuba's
  _var.exr: Mitsuba's reference variance, or `ptlab render --moments`'s NAME_var.exr for the
  test with ptlab's own variance); per pixel channel z = |IMAGE - REF| sqrt(N / max(VAR, 1e-4)),
  p = 2 (1 - Phi(z)); pass when >= 99.75 % of the pixel channels have p > 1 - 0.99^(1/pixels).
  On failure writes PREFIX_pvalue.exr (p of X, Y, Z) and PREFIX_failed.exr (0.02 IMAGE, failed
  channels 1); PREFIX is --ztest-out, else IMAGE without its extension.
Exit codes (tools/common/exit_codes.h, shared with ptlab and chi2): 0 pass; 1 fail: over a
  threshold, parity failed, or A and B of different sizes; 2 bad usage, an unreadable image,
  or a heat map that would overwrite A or B; 3 the heat map could not be written.)";

bool IsLdrPng(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[16] = {};
  in.read(reinterpret_cast<char*>(magic), sizeof(magic));
  return ptlab::DetectImageFormat(magic, size_t(in.gcount())) == ptlab::ImageFormat::kPng;
}

std::string WithoutExtension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return path;
  return path.substr(0, dot);
}

// --ztest REF VAR IMAGE: Mitsuba 3's Z test; writes the p-value and failed-pixel images on failure.
int RunZTest(const std::vector<std::string>& paths, uint32_t spp, const std::string& out_prefix,
             bool json) {
  {  // before any work: the p-value and failed-pixel images may not replace an input
    const std::string prefix = out_prefix.empty() ? WithoutExtension(paths[2]) : out_prefix;
    ptlab::OutputGuard guard;
    guard.AddInput(paths[0], "REF");
    guard.AddInput(paths[1], "VAR");
    guard.AddInput(paths[2], "IMAGE");
    guard.AddOutput(prefix + "_pvalue.exr", "the p-value image");
    guard.AddOutput(prefix + "_failed.exr", "the failed-pixel image");
    std::string error;
    if (const int code = guard.Check(&error); code != kExitOk) {
      std::fprintf(stderr, "imgdiff: %s\n", error.c_str());
      return code;
    }
  }
  ptlab::Image images[3];
  for (int k = 0; k < 3; ++k) {
    ptlab::StatusOr<ptlab::Image> img = ptlab::ReadImage(paths[size_t(k)]);
    if (!img.ok()) {
      std::fprintf(stderr, "imgdiff: %s\n", img.status().message().c_str());
      return kExitUsage;
    }
    images[k] = std::move(*img);
  }
  for (int k = 1; k < 3; ++k) {
    if (!ptlab::SameSize(images[0], images[k])) {
      std::fprintf(stderr, "imgdiff: size mismatch: REF %s is %dx%d, %s %s is %dx%d\n",
                   paths[0].c_str(), images[0].width, images[0].height, k == 1 ? "VAR" : "IMAGE",
                   paths[size_t(k)].c_str(), images[k].width, images[k].height);
      return kExitFailed;  // not the same image
    }
  }
  ptlab::ZTestOptions options;
  options.spp = spp;
  const ptlab::ZTestResult r = ptlab::ZTest(images[2], images[0], images[1], options);
  if (!r.pass) {
    const std::string prefix = out_prefix.empty() ? WithoutExtension(paths[2]) : out_prefix;
    for (const auto& [suffix, image] :
         {std::pair{"_pvalue.exr", &r.p_value}, std::pair{"_failed.exr", &r.failed_pixels}}) {
      const ptlab::Status s = ptlab::WriteExr(prefix + suffix, *image);
      if (!s.ok()) {
        std::fprintf(stderr, "imgdiff: %s\n", s.message().c_str());
        return kExitRunFailed;
      }
      if (!json) std::printf("wrote %s%s\n", prefix.c_str(), suffix);
    }
  }
  if (json) {
    std::printf("%s\n", ptlab::FormatZTestJson(paths[0], paths[1], paths[2], r).c_str());
  } else {
    std::printf("REF: %s\nVAR: %s\nIMAGE: %s\n%sresult: %s\n", paths[0].c_str(), paths[1].c_str(),
                paths[2].c_str(), ptlab::FormatZTestTable(r).c_str(), r.pass ? "PASS" : "FAIL");
  }
  return r.pass ? kExitOk : kExitFailed;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "imgdiff: compare image A (test) with image B (reference). Reads EXR, PNG, "
      "Radiance HDR and PFM."};
  app.footer(kFooter);
  std::string path_a, path_b, heatmap_path;
  bool json = false, flip_x = false;
  ptlab::ImageDiffOptions options;
  double heatmap_scale = 0.5;
  double fail_rmse = 0, fail_relmse = 0, fail_mean_rel = 0, fail_block_share = 0, parity = 0;
  std::vector<std::string> ztest_paths;
  std::string ztest_out;
  uint32_t ztest_spp = 0;
  CLI::Option* o_a = app.add_option("A", path_a, "test image (required unless --ztest)");
  CLI::Option* o_b = app.add_option("B", path_b, "reference image (required unless --ztest)");
  CLI::Option* o_ztest =
      app.add_option("--ztest", ztest_paths,
                     "REF VAR IMAGE: Mitsuba 3's Z test of IMAGE (see below) instead of A/B")
          ->expected(3);
  CLI::Option* o_spp = app.add_option("--spp", ztest_spp, "--ztest: samples per pixel of IMAGE")
                           ->check(CLI::Range(1u, 0xffffffffu));
  app.add_option("--ztest-out", ztest_out,
                 "--ztest: prefix of the p-value and failed-pixel images (default: IMAGE's)");
  app.add_flag("--json", json, "print one JSON object instead of the table");
  app.add_flag("--flip-x", flip_x, "mirror A left-right before comparing (eth2015 references)");
  app.add_option("--block", options.block_size, "block edge N in pixels")
      ->check(ptlab::IntegerRange(1, 65536))
      ->capture_default_str();
  app.add_option("--tol", options.block_tol, "block relative tolerance T")
      ->check(ptlab::FinitePositive())
      ->capture_default_str();
  app.add_option("--block-min", options.block_min, "floor on B's block mean for eligibility")
      ->check(ptlab::FiniteRange(0, HUGE_VAL))
      ->capture_default_str();
  app.add_option("--heatmap", heatmap_path, "write the relative-error heat map here");
  app.add_option("--heatmap-scale", heatmap_scale, "relative error shown at full colour")
      ->check(ptlab::FinitePositive())
      ->capture_default_str();
  CLI::Option* o_rmse = app.add_option("--fail-rmse", fail_rmse, "fail if RMSE (all) > X")
                            ->check(ptlab::FiniteRange(0, HUGE_VAL));
  CLI::Option* o_relmse = app.add_option("--fail-relmse", fail_relmse, "fail if relMSE (all) > X")
                              ->check(ptlab::FiniteRange(0, HUGE_VAL));
  CLI::Option* o_mean = app.add_option("--fail-mean-rel", fail_mean_rel,
                                       "fail if max over channels |meanA-meanB|/meanB > X")
                            ->check(ptlab::FiniteRange(0, HUGE_VAL));
  CLI::Option* o_share = app.add_option("--fail-block-share", fail_block_share,
                                        "fail if the share of blocks within --tol is < F")
                             ->check(ptlab::FiniteRange(0.0, 1.0));
  CLI::Option* o_parity =
      app.add_option("--parity", parity, "fail unless PARITY.md's criterion P(F) holds")
          ->check(ptlab::FiniteRange(0.0, 1.0));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  if (o_ztest->count()) {
    if (o_a->count() || o_b->count() || !o_spp->count()) {
      std::fprintf(stderr, "imgdiff: --ztest REF VAR IMAGE takes --spp N and no A/B images\n");
      return kExitUsage;
    }
    return RunZTest(ztest_paths, ztest_spp, ztest_out, json);
  }
  if (!o_a->count() || !o_b->count()) {
    std::fprintf(stderr, "imgdiff: images A and B are required (or --ztest REF VAR IMAGE)\n");
    return kExitUsage;
  }
  options.flip_x = flip_x;
  if (!heatmap_path.empty()) {  // before any work: the heat map may not replace A or B
    ptlab::OutputGuard guard;
    guard.AddInput(path_a, "A");
    guard.AddInput(path_b, "B");
    guard.AddOutput(heatmap_path, "--heatmap");
    std::string error;
    if (const int code = guard.Check(&error); code != kExitOk) {
      std::fprintf(stderr, "imgdiff: %s\n", error.c_str());
      return code;
    }
  }

  ptlab::StatusOr<ptlab::Image> a = ptlab::ReadImage(path_a);
  if (!a.ok()) {
    std::fprintf(stderr, "imgdiff: %s\n", a.status().message().c_str());
    return kExitUsage;
  }
  ptlab::StatusOr<ptlab::Image> b = ptlab::ReadImage(path_b);
  if (!b.ok()) {
    std::fprintf(stderr, "imgdiff: %s\n", b.status().message().c_str());
    return kExitUsage;
  }
  if (!ptlab::SameSize(*a, *b)) {
    std::fprintf(stderr, "imgdiff: size mismatch: A %s is %dx%d, B %s is %dx%d\n", path_a.c_str(),
                 a->width, a->height, path_b.c_str(), b->width, b->height);
    return kExitFailed;  // not the same image
  }
  if (IsLdrPng(path_b)) options.psnr_peak = 1.0;

  const ptlab::ImageDiff diff = ptlab::CompareImages(*a, *b, options);
  ptlab::DiffThresholds thresholds;
  if (o_rmse->count()) thresholds.rmse = fail_rmse;
  if (o_relmse->count()) thresholds.rel_mse = fail_relmse;
  if (o_mean->count()) thresholds.mean_rel = fail_mean_rel;
  if (o_share->count()) thresholds.block_share = fail_block_share;
  std::vector<std::string> failures = ptlab::CheckThresholds(diff, thresholds);
  ptlab::ParityResult parity_result;
  const bool has_parity = o_parity->count() > 0;
  if (has_parity) {
    parity_result = ptlab::CheckParity(*a, *b, parity, flip_x);
    if (!parity_result.pass) failures.push_back("parity " + parity_result.summary);
  }

  if (!heatmap_path.empty()) {
    const ptlab::Image heat =
        ptlab::RelativeErrorHeatmap(flip_x ? ptlab::FlipX(*a) : *a, *b, heatmap_scale);
    const std::string lower = [&] {
      std::string s = heatmap_path;
      for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
      return s;
    }();
    const bool by_extension = lower.ends_with(".exr") || lower.ends_with(".pfm");
    const ptlab::Status s =
        by_extension ? ptlab::WriteImage(heatmap_path, heat) : ptlab::WritePng(heatmap_path, heat);
    if (!s.ok()) {
      std::fprintf(stderr, "imgdiff: heat map: %s\n", s.message().c_str());
      return kExitRunFailed;
    }
  }

  if (json) {
    std::printf("%s\n", ptlab::FormatDiffJson(path_a, path_b, diff,
                                              has_parity ? &parity_result : nullptr, failures)
                            .c_str());
  } else {
    std::printf("A: %s\nB: %s\n%s", path_a.c_str(), path_b.c_str(),
                ptlab::FormatDiffTable(diff, has_parity ? &parity_result : nullptr).c_str());
    if (failures.empty()) {
      std::printf("result: PASS\n");
    } else {
      std::printf("result: FAIL\n");
      for (const std::string& f : failures) std::printf("  - %s\n", f.c_str());
    }
  }
  return failures.empty() ? kExitOk : kExitFailed;
}
