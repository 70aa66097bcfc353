// Error against time for `ptlab converge`: fits, time to quality, CSV/JSON/Markdown, gnuplot.
#include "tools/converge/convergence.h"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include "engine/image/image_io.h"
#include "tools/common/json_line.h"
#include "tools/imgdiff/imgdiff.h"

namespace ptlab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string Num(double v) {
  if (!std::isfinite(v)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}


// A CSV field quoted as a JSON string (nlohmann/json escapes it).
std::string JsonString(const std::string& s) { return DumpJsonLine(Json(s)); }

double Mean(const std::vector<double>& v) {
  double s = 0;
  for (const double x : v) s += x;
  return v.empty() ? kNaN : s / double(v.size());
}

}  // namespace

double EstimateRelMseFromHalves(const Image& a, const Image& b) {
  // Per pixel and channel: d = (a − b)/2 has the variance of the merged mean m = (a + b)/2, and
  // relMSE = E[d²] / (μ² + ε). μ is unknown; the pixel's own m in its place makes the estimate
  // too high by Jensen's inequality, E[1/(m² + ε)] ≈ (1 + (4t − 1) r²) / (μ² + ε) to second
  // order, with r² = var(m) / (μ² + ε) and t = μ² / (μ² + ε). That factor is divided out, r²
  // taken from the eight neighbours' own d² / (m² + ε) (not the pixel's: its d² is the
  // numerator). A mean over a neighbourhood as the denominator instead would be biased at every
  // edge: −23 % on a direct-lit Cornell box (docs/converge.md).
  const int w = a.width, h = a.height;
  auto at = [w](int x, int y, int c) { return (size_t(y) * size_t(w) + size_t(x)) * 3 + size_t(c); };
  auto half_diff = [&](size_t i) { return 0.5 * (double(a.rgb[i]) - double(b.rgb[i])); };
  auto mean = [&](size_t i) { return 0.5 * (double(a.rgb[i]) + double(b.rgb[i])); };
  double sum = 0;
  int64_t n = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        const size_t i = at(x, y, c);
        const double d = half_diff(i), m = mean(i);
        if (!std::isfinite(d) || !std::isfinite(m)) continue;
        double r2 = 0;
        int taps = 0;
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if ((dx == 0 && dy == 0) || xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
            const size_t j = at(xx, yy, c);
            const double dj = half_diff(j), mj = mean(j);
            if (!std::isfinite(dj) || !std::isfinite(mj)) continue;
            r2 += dj * dj / (mj * mj + kRelMseEpsilon);
            ++taps;
          }
        }
        if (taps > 0) r2 /= double(taps);
        const double q = m * m + kRelMseEpsilon, t = m * m / q;
        // The factor is ≥ 1 − r² for any t; held ≥ ½ where a wild neighbourhood would turn it over.
        const double jensen = std::max(1.0 + (4.0 * t - 1.0) * r2, 0.5);
        sum += d * d / q / jensen;
        ++n;
      }
    }
  }
  return n > 0 ? sum / double(n) : kNaN;
}

LogLogFit FitLogLog(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> lx, ly;
  for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (!(x[i] > 0) || !(y[i] > 0) || !std::isfinite(x[i]) || !std::isfinite(y[i])) continue;
    lx.push_back(std::log(x[i]));
    ly.push_back(std::log(y[i]));
  }
  LogLogFit fit;
  fit.points = int(lx.size());
  if (fit.points < 2) {
    fit.slope = fit.intercept = kNaN;
    return fit;
  }
  const double mx = Mean(lx), my = Mean(ly);
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < lx.size(); ++i) {
    sxx += (lx[i] - mx) * (lx[i] - mx);
    sxy += (lx[i] - mx) * (ly[i] - my);
  }
  fit.slope = sxx > 0 ? sxy / sxx : kNaN;
  fit.intercept = my - fit.slope * mx;
  if (fit.points >= 3 && sxx > 0) {
    double rss = 0;
    for (size_t i = 0; i < lx.size(); ++i) {
      const double r = ly[i] - (fit.intercept + fit.slope * lx[i]);
      rss += r * r;
    }
    fit.slope_stderr = std::sqrt(rss / double(fit.points - 2) / sxx);
  }
  return fit;
}

double TimeToQuality(const std::vector<ConvergencePoint>& run, double target) {
  for (size_t i = 0; i < run.size(); ++i) {
    if (!(run[i].rel_mse <= target)) continue;
    if (i == 0 || !(run[i - 1].rel_mse > 0) || !(run[i - 1].seconds > 0) ||
        !(run[i].rel_mse > 0))
      return run[i].seconds;
    // Between the passes that straddle the target, relMSE is a power of time.
    const double l0 = std::log(run[i - 1].rel_mse), l1 = std::log(run[i].rel_mse);
    const double s0 = std::log(run[i - 1].seconds), s1 = std::log(run[i].seconds);
    const double f = l1 != l0 ? (std::log(target) - l0) / (l1 - l0) : 1.0;
    return std::exp(s0 + f * (s1 - s0));
  }
  return kNaN;
}

double RelMseAtSeconds(const VariantSummary& s, double seconds) {
  const size_t n = std::min(s.seconds.size(), s.rel_mse.size());
  if (n == 0 || !(seconds >= s.seconds[0]) || !(seconds <= s.seconds[n - 1])) return kNaN;
  for (size_t i = 0; i < n; ++i) {
    if (s.seconds[i] < seconds) continue;
    if (i == 0 || s.seconds[i] == seconds) return s.rel_mse[i];
    const double t0 = std::log(s.seconds[i - 1]), t1 = std::log(s.seconds[i]);
    const double f = t1 > t0 ? (std::log(seconds) - t0) / (t1 - t0) : 1.0;
    return std::exp(std::log(s.rel_mse[i - 1]) +
                    f * (std::log(s.rel_mse[i]) - std::log(s.rel_mse[i - 1])));
  }
  return kNaN;
}

std::vector<VariantSummary> Summarize(const std::vector<ConvergencePoint>& points) {
  // (scene, variant) -> seed -> points in pass order.
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, std::map<uint64_t, std::vector<ConvergencePoint>>>
      runs;
  for (const ConvergencePoint& p : points) {
    const auto key = std::make_pair(p.scene, p.variant);
    if (!runs.count(key)) order.push_back(key);
    runs[key][p.seed].push_back(p);
  }
  std::vector<VariantSummary> out;
  for (const auto& key : order) {
    const auto& by_seed = runs[key];
    VariantSummary s;
    s.scene = key.first;
    s.variant = key.second;
    s.seeds = int(by_seed.size());
    // Passes that every seed completed (a --time budget can end seeds at different passes).
    size_t passes = std::numeric_limits<size_t>::max();
    for (const auto& [seed, run] : by_seed) passes = std::min(passes, run.size());
    std::vector<double> ttq2, ttq3, finals;
    for (size_t k = 0; k < passes; ++k) {
      std::vector<double> spp, sec, rel, est;
      for (const auto& [seed, run] : by_seed) {
        spp.push_back(run[k].mean_spp), sec.push_back(run[k].seconds);
        rel.push_back(run[k].rel_mse), est.push_back(run[k].estimated_rel_mse);
      }
      s.spp.push_back(Mean(spp)), s.seconds.push_back(Mean(sec));
      s.rel_mse.push_back(Mean(rel)), s.estimated_rel_mse.push_back(Mean(est));
    }
    for (const auto& [seed, run] : by_seed) {
      ttq2.push_back(TimeToQuality(run, 1e-2));
      ttq3.push_back(TimeToQuality(run, 1e-3));
      if (passes > 0) finals.push_back(run[passes - 1].rel_mse);
    }
    // Reached by every seed, else not reached (NaN propagates through the mean).
    s.seconds_to_1e2 = Mean(ttq2);
    s.seconds_to_1e3 = Mean(ttq3);
    if (passes > 0) {
      s.final_rel_mse = s.rel_mse.back();
      s.final_seconds = s.seconds.back();
      double var = 0;
      for (const double f : finals) var += (f - s.final_rel_mse) * (f - s.final_rel_mse);
      s.final_rel_mse_sd = finals.size() > 1 ? std::sqrt(var / double(finals.size() - 1)) : 0;
      s.efficiency = 1.0 / (s.final_rel_mse * s.final_seconds);
      s.estimate_ratio = kNaN;
      for (size_t k = passes; k-- > 0;) {
        if (std::isfinite(s.estimated_rel_mse[k]) && s.rel_mse[k] > 0) {
          s.estimate_ratio = s.estimated_rel_mse[k] / s.rel_mse[k];
          break;
        }
      }
    }
    s.slope_spp = FitLogLog(s.spp, s.rel_mse);
    out.push_back(std::move(s));
  }
  // Against the scene's first variant, at the time both runs reached.
  for (VariantSummary& s : out) {
    const VariantSummary* first = nullptr;
    for (const VariantSummary& f : out)
      if (f.scene == s.scene) {
        first = &f;
        break;
      }
    s.matched_seconds = std::min(first->final_seconds, s.final_seconds);
    s.matched_ratio = &s == first ? 1.0
                                  : RelMseAtSeconds(*first, s.matched_seconds) /
                                        RelMseAtSeconds(s, s.matched_seconds);
  }
  return out;
}

Status WriteConvergeCsv(const std::string& path, const std::vector<ConvergencePoint>& points) {
  std::ostringstream o;
  o << "scene,variant,seed,pass,spp,mean_spp,seconds,rel_mse,rmse,mae,bias_r,bias_g,bias_b,parity_share,"
       "estimated_rel_mse,cpu_seconds\n";
  for (const ConvergencePoint& p : points) {
    // Variant specs hold commas: quote them (RFC 4180).
    o << JsonString(p.scene) << "," << JsonString(p.variant) << "," << p.seed << "," << p.pass
      << "," << p.spp << "," << Num(p.mean_spp) << "," << Num(p.seconds) << "," << Num(p.rel_mse) << "," << Num(p.rmse)
      << "," << Num(p.mae) << "," << Num(p.bias[0]) << "," << Num(p.bias[1]) << ","
      << Num(p.bias[2]) << "," << Num(p.parity_share) << "," << Num(p.estimated_rel_mse) << ","
      << Num(p.cpu_seconds) << "\n";
  }
  return WriteFileAtomically(path, o.str());
}

Status WriteConvergeJson(const std::string& path, const std::vector<std::string>& references,
                         const std::vector<ConvergencePoint>& points,
                         const std::vector<VariantSummary>& summary) {
  // One point or summary row per line, as before; every value through nlohmann/json.
  std::ostringstream o;
  o << "{\n  \"references\": " << DumpJsonLine(Json(references)) << ",\n  \"points\": [\n";
  for (size_t i = 0; i < points.size(); ++i) {
    const ConvergencePoint& p = points[i];
    Json j;
    j["scene"] = p.scene;
    j["variant"] = p.variant;
    j["seed"] = p.seed;
    j["pass"] = p.pass;
    j["spp"] = p.spp;
    j["mean_spp"] = JsonNumberOrNull(p.mean_spp);
    j["seconds"] = JsonNumberOrNull(p.seconds);
    j["rel_mse"] = JsonNumberOrNull(p.rel_mse);
    j["rmse"] = JsonNumberOrNull(p.rmse);
    j["mae"] = JsonNumberOrNull(p.mae);
    j["bias"] = Json::array({JsonNumberOrNull(p.bias[0]), JsonNumberOrNull(p.bias[1]),
                             JsonNumberOrNull(p.bias[2])});
    j["parity_share"] = JsonNumberOrNull(p.parity_share);
    j["estimated_rel_mse"] = JsonNumberOrNull(p.estimated_rel_mse);
    j["cpu_seconds"] = JsonNumberOrNull(p.cpu_seconds);
    o << "    " << DumpJsonLine(j) << (i + 1 < points.size() ? "," : "") << "\n";
  }
  o << "  ],\n  \"summary\": [\n";
  for (size_t i = 0; i < summary.size(); ++i) {
    const VariantSummary& s = summary[i];
    Json j;
    j["scene"] = s.scene;
    j["variant"] = s.variant;
    j["seeds"] = s.seeds;
    j["final_rel_mse"] = JsonNumberOrNull(s.final_rel_mse);
    j["final_rel_mse_sd"] = JsonNumberOrNull(s.final_rel_mse_sd);
    j["final_seconds"] = JsonNumberOrNull(s.final_seconds);
    j["efficiency"] = JsonNumberOrNull(s.efficiency);
    j["slope_spp"] = JsonNumberOrNull(s.slope_spp.slope);
    j["slope_spp_stderr"] = JsonNumberOrNull(s.slope_spp.slope_stderr);
    j["seconds_to_rel_mse_1e-2"] = JsonNumberOrNull(s.seconds_to_1e2);
    j["seconds_to_rel_mse_1e-3"] = JsonNumberOrNull(s.seconds_to_1e3);
    j["estimate_over_true"] = JsonNumberOrNull(s.estimate_ratio);
    j["efficiency_over_first_at_matched_time"] = JsonNumberOrNull(s.matched_ratio);
    j["matched_seconds"] = JsonNumberOrNull(s.matched_seconds);
    o << "    " << DumpJsonLine(j) << (i + 1 < summary.size() ? "," : "") << "\n";
  }
  o << "  ]\n}\n";
  return WriteFileAtomically(path, o.str());
}

std::string SummaryTable(const std::vector<VariantSummary>& summary) {
  std::ostringstream o;
  o << "| scene | variant | seeds | spp | seconds | relMSE (± sd) | efficiency 1/(relMSE·s) | "
       "slope vs spp | s to 1e-2 | s to 1e-3 | estimate / true | efficiency / first's at "
       "matched s |\n"
    << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  auto secs = [](double v) { return std::isfinite(v) ? Num(v) : std::string("not reached"); };
  for (const VariantSummary& s : summary) {
    char rel[96];
    std::snprintf(rel, sizeof rel, "%.4g ± %.2g", s.final_rel_mse, s.final_rel_mse_sd);
    char slope[64];
    std::snprintf(slope, sizeof slope, "%.3f ± %.3f", s.slope_spp.slope,
                  s.slope_spp.slope_stderr);
    o << "| " << s.scene << " | " << s.variant << " | " << s.seeds << " | "
      << (s.spp.empty() ? 0.0 : s.spp.back()) << " | " << Num(s.final_seconds) << " | " << rel
      << " | " << Num(s.efficiency) << " | " << slope << " | " << secs(s.seconds_to_1e2)
      << " | " << secs(s.seconds_to_1e3) << " | " << Num(s.estimate_ratio) << " | "
      << Num(s.matched_ratio) << " (at " << Num(s.matched_seconds) << " s) |\n";
  }
  return o.str();
}

Status PlotConvergence(const std::string& dir, const std::string& stem,
                       const std::vector<VariantSummary>& scene_summary) {
  namespace fs = std::filesystem;
  const std::string base = (fs::path(dir) / stem).string();
  // Data: one gnuplot index block per variant (spp, seconds, relMSE, efficiency).
  std::ostringstream data;
  for (const VariantSummary& s : scene_summary) {
    data << "# " << s.variant << "\n";
    for (size_t k = 0; k < s.spp.size(); ++k)
      data << Num(s.spp[k]) << " " << Num(s.seconds[k]) << " " << Num(s.rel_mse[k]) << " "
           << Num(1.0 / (s.rel_mse[k] * s.seconds[k])) << "\n";
    data << "\n\n";
  }
  PTLAB_RETURN_IF_ERROR(WriteFileAtomically(base + ".dat", data.str()));
  std::ostringstream gp;
  gp << "# gnuplot script written by ptlab converge\n"
     << "set logscale xy\nset grid\nset key below\nset datafile missing 'nan'\n";
  struct Plot {
    const char* suffix;
    const char* xlabel;
    const char* ylabel;
    int x, y;
    bool targets;
  };
  const Plot plots[] = {
      {"_seconds", "render time (s)", "relMSE", 2, 3, true},
      {"_spp", "samples per pixel", "relMSE", 1, 3, true},
      {"_efficiency", "render time (s)", "efficiency 1/(relMSE s)", 2, 4, false},
  };
  for (const char* term : {"svg size 900,560 dynamic font 'sans,12'",
                           "pngcairo size 900,560 font 'sans,11'"}) {
    const std::string ext = std::string(term).rfind("svg", 0) == 0 ? ".svg" : ".png";
    for (const Plot& p : plots) {
      gp << "set terminal " << term << "\nset output '" << base << p.suffix << ext << "'\n"
         << "set title '" << stem << "'\nset xlabel '" << p.xlabel << "'\nset ylabel '"
         << p.ylabel << "'\nplot ";
      for (size_t i = 0; i < scene_summary.size(); ++i) {
        const VariantSummary& s = scene_summary[i];
        std::string title = s.variant;
        for (char& c : title)
          if (c == '\'' || c == '_') c = c == '_' ? ' ' : '"';
        if (p.targets && std::string(p.suffix) == "_spp") {
          char buf[48];
          std::snprintf(buf, sizeof buf, " (slope %.2f)", s.slope_spp.slope);
          title += buf;
        }
        gp << (i ? ", " : "") << "'" << base << ".dat' index " << i << " using " << p.x << ":"
           << p.y << " with linespoints title '" << title << "'";
      }
      if (p.targets)
        gp << ", 1e-2 with lines dashtype 2 lc 'gray' title 'relMSE 1e-2', 1e-3 with lines "
              "dashtype 3 lc 'gray' title 'relMSE 1e-3'";
      gp << "\nunset output\n";
    }
  }
  PTLAB_RETURN_IF_ERROR(WriteFileAtomically(base + ".gp", gp.str()));
  const std::string command = "gnuplot '" + base + ".gp' 2> '" + base + ".gnuplot.log'";
  const int rc = std::system(command.c_str());
  if (rc != 0 || !WIFEXITED(rc) || WEXITSTATUS(rc) != 0)
    return Status::Error("gnuplot failed on " + base + ".gp (is gnuplot installed? ./lab "
                         "installs gnuplot-nox); see " + base + ".gnuplot.log");
  std::error_code ec;
  fs::remove(base + ".gnuplot.log", ec);
  return Status::Ok();
}

}  // namespace ptlab
