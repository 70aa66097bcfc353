// Error against time for `ptlab converge`: per-pass records, fits, time to quality, reports.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/image/image.h"

namespace ptlab {

/// One completed pass of one run (scene, variant, seed), measured against the reference.
struct ConvergencePoint {
  std::string scene, variant;
  uint64_t seed = 0;
  uint32_t pass = 0, spp = 0;  // spp: samples per pixel so far (the most any pixel took)
  double mean_spp = 0;          // samples taken / pixels (below spp with adaptive sampling)
  double seconds = 0;  // render time so far (measurement time excluded)
  double cpu_seconds = 0;  // CPU time of the render so far, all threads (RenderPass::cpu_seconds)
  double rel_mse = 0, rmse = 0, mae = 0;  // over the three channels (imgdiff's definitions)
  std::array<double, 3> bias{};           // (mean render - mean reference) / mean reference
  double parity_share = 0;                // docs/parity.md block share (32 px blocks within 5 %)
  /// Reference-free relMSE expected of this image, from its two halves (EstimateRelMseFrom-
  /// Halves); NaN on passes where the halves are unequal (odd pass counts).
  double estimated_rel_mse = 0;
};

/// relMSE expected of (a + b) / 2 from two independent half images a and b (the same
/// estimator with half the samples each): var of the mean = E[(a - b)^2] / 4 per pixel and
/// channel, divided by ((a + b)/2)^2 + kRelMseEpsilon as imgdiff's relMSE divides by the
/// reference's, with that denominator's second-order Jensen bias divided out (its relative
/// variance taken from the 3×3 neighbours). Precondition: same size.
double EstimateRelMseFromHalves(const Image& a, const Image& b);

/// Least-squares line through (log x, log y) over the points with x, y > 0 and finite.
struct LogLogFit {
  double slope = 0, intercept = 0;
  double slope_stderr = 0;  // standard error of the slope (0 with fewer than 3 points)
  int points = 0;
};
LogLogFit FitLogLog(const std::vector<double>& x, const std::vector<double>& y);

/// The seconds at which relMSE first reaches `target`, interpolated log-log between the passes
/// that straddle it (points in pass order); NaN when it is never reached.
double TimeToQuality(const std::vector<ConvergencePoint>& run, double target);

/// One line per variant of a scene: the mean over seeds of each pass, and the run's figures.
struct VariantSummary {
  std::string scene, variant;
  // Per pass, mean over seeds; spp is samples taken per pixel (mean_spp of the points).
  std::vector<double> spp, seconds, rel_mse, estimated_rel_mse;
  int seeds = 0;
  double final_rel_mse = 0, final_rel_mse_sd = 0;  // last pass: mean and spread over seeds
  double final_seconds = 0;
  double efficiency = 0;  // 1 / (relMSE · seconds) at the last pass
  LogLogFit slope_spp;    // relMSE against spp
  double seconds_to_1e2 = 0, seconds_to_1e3 = 0;  // NaN when not reached
  double estimate_ratio = 0;  // estimated / true relMSE at the last pass with an estimate
  /// Efficiency against the scene's first variant at matched time: relMSE_first(t) /
  /// relMSE(t) at t = the shorter of the two runs' last times (log-log interpolation of the
  /// mean curves); 1 for the first variant, NaN when the runs' times do not overlap.
  double matched_ratio = 0;
  double matched_seconds = 0;  // that t
};

/// relMSE of a summary's mean curve at `seconds`, interpolated log-log between the passes that
/// straddle it; NaN outside the curve's first and last times.
double RelMseAtSeconds(const VariantSummary& s, double seconds);

/// Groups points by (scene, variant) in first-seen order and summarises them.
std::vector<VariantSummary> Summarize(const std::vector<ConvergencePoint>& points);

/// converge.csv: one row per point, columns named in the header.
Status WriteConvergeCsv(const std::string& path, const std::vector<ConvergencePoint>& points);
/// converge.json: {"references": [...], "points": [...], "summary": [...]}.
Status WriteConvergeJson(const std::string& path, const std::vector<std::string>& references,
                         const std::vector<ConvergencePoint>& points,
                         const std::vector<VariantSummary>& summary);
/// A Markdown table of the summary (what `ptlab converge` prints and docs/converge.md shows).
std::string SummaryTable(const std::vector<VariantSummary>& summary);

/// Plots of one scene's variants through gnuplot: <stem>_seconds (relMSE vs seconds),
/// <stem>_spp (relMSE vs spp) and <stem>_efficiency, each as .svg and .png, log-log, with the
/// fitted slope in the legend. Writes the data and script beside them (<stem>.dat, <stem>.gp).
Status PlotConvergence(const std::string& dir, const std::string& stem,
                       const std::vector<VariantSummary>& scene_summary);

}  // namespace ptlab
