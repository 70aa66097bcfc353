// Nori test runner: BSDF-albedo and scene t-tests, BSDF χ² tests through the chi2 library.
#include "tools/chi2/nori_tests.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <vector>

#include "engine/bsdf/bsdf.h"
#include "engine/bvh/bvh.h"
#include "engine/core/rng.h"
#include "engine/render/bdpt.h"
#include "engine/render/camera.h"
#include "engine/render/integrator.h"
#include "tools/chi2/chi2.h"
#include "tools/chi2/report.h"
#include "tools/chi2/stats_math.h"
#include "tools/common/exit_codes.h"

namespace ptlab {
namespace {

// Scene samples are accumulated in chunks of this many (one RunningMoments each), merged in
// chunk order: the result is the same for any number of threads.
constexpr int64_t kSceneChunk = 4096;

// Absolute tolerance of each cell's pdf integral in Nori χ² tests (see RunChi2Tests).
constexpr double kChi2CellAbsTol = 1e-12;

// Stream salts, so BSDF t-tests, scene t-tests and χ² directions never share a PCG32 stream.
constexpr uint64_t kBsdfTTestSalt = 0x62736466ULL, kSceneTTestSalt = 0x7363656eULL,
                   kChi2DirectionSalt = 0x63686932ULL;

const char* MaterialName(MaterialTag tag) {
  switch (tag) {
    case MaterialTag::kDiffuse:
      return "diffuse";
    case MaterialTag::kMirror:
      return "mirror";
    case MaterialTag::kDielectric:
      return "dielectric";
    case MaterialTag::kConductor:
      return "roughconductor";
    case MaterialTag::kRoughPlastic:
      return "microfacet";
    case MaterialTag::kRoughDielectric:  // matA
      return "roughdielectric";
    // matB
    case MaterialTag::kPlastic:
      return "plastic";
    case MaterialTag::kThinDielectric:
      return "thindielectric";
    case MaterialTag::kBlend:
      return "blendbsdf";
    case MaterialTag::kPrincipled:  // principled
      return "principled";
    case MaterialTag::kPrincipledThin:
      return "principledthin";
    case MaterialTag::kMask:  // mask
      return "mask";
  }
  return "?";
}

std::string Printf(const char* fmt, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), fmt, a, b, c);
  return buf;
}

std::string BsdfName(const NoriTestFile& file, size_t b) {
  const size_t line_index = file.scenes.size() + b;
  const int line = line_index < file.child_lines.size() ? file.child_lines[line_index] : 0;
  return "bsdf " + std::to_string(b + 1) + " " + MaterialName(file.bsdfs[b].tag()) + " (line " +
         std::to_string(line) + ")";
}

void FinishTTest(const RunningMoments& m, double reference, double alpha, int test_count,
                 NoriTestCase* c) {
  c->samples = m.n;
  c->estimate = m.mean;
  c->reference = reference;
  c->variance = m.Variance();
  const TTestResult t = OneSampleTTest(m.mean, c->variance, m.n, reference, alpha, test_count);
  c->statistic = t.t;
  c->dof = t.dof;
  c->p_value = t.p_value;
  c->alpha = t.alpha;
  if (!t.pass) {
    c->details.push_back(
        Printf("the t-test rejects the reference: p = %.4g < alpha' = %.4g", t.p_value, t.alpha));
  }
  c->verdict = t.pass && c->details.empty() ? NoriVerdict::kPass : NoriVerdict::kFail;
}

// Whether the next case of the file (*case_index, then advanced) is run (NoriTestOptions::runs_case).
bool RunsNextCase(const NoriTestOptions& options, size_t* case_index) {
  const size_t i = (*case_index)++;
  return !options.runs_case || options.runs_case(i);
}

// Nori's BSDF t-test: the mean luminance of sample weights is the directional albedo.
void RunBsdfTTests(const NoriTestFile& file, const NoriTestOptions& options, int64_t samples,
                   size_t* case_index, NoriTestReport* report) {
  MaterialTables materials = file.materials;
  if (options.dielectric_scale_radiance) {
    DielectricTable& d = materials.dielectric;
    d.flags.resize(d.size(), uint8_t{0});
    for (uint8_t& f : d.flags) f |= kDielectricScaleRadiance;
  }
  const NoriTestProperties& p = file.properties;
  size_t index = 0;
  for (size_t b = 0; b < file.bsdfs.size(); ++b) {
    const MaterialRef ref = file.bsdfs[b];
    for (size_t i = 0; i < p.angles.size(); ++i, ++index) {
      if (!RunsNextCase(options, case_index)) continue;
      NoriTestCase c;
      c.name = BsdfName(file, b) + " at " + Printf("%g", p.angles[i]) + " deg";
      // Nori: wi = sphericalDirection(θ, 0); its wi is our wo (towards the viewer).
      const float theta = p.angles[i] * (kPi / 180.0f);
      const Vec3f wo{std::sin(theta), 0.0f, std::cos(theta)};
      Pcg32 rng(MixBits(options.seed ^ kBsdfTTestSalt), index);
      RunningMoments m;
      for (int64_t k = 0; k < samples; ++k) {
        const float u1 = rng.NextFloat();
        const Vec2f u2{rng.NextFloat(), rng.NextFloat()};
        BsdfSample s;
        const bool ok = BsdfSampleDirection(materials, ref, wo, u1, u2, &s);
        m.Add(ok ? double(Luminance(s.weight)) : 0.0);
      }
      FinishTTest(m, p.references[index], p.significance_level, report->test_count, &c);
      report->cases.push_back(c);
      if (options.on_case) options.on_case(report->cases.back());
    }
  }
}

// Nori's scene t-test: the mean luminance of Li over uniformly jittered camera rays.
void RunSceneTTests(const NoriTestFile& file, const NoriTestOptions& options, int64_t samples,
                    size_t* case_index, NoriTestReport* report) {
  for (size_t s = 0; s < file.scenes.size(); ++s) {
    if (!RunsNextCase(options, case_index)) continue;
    const Scene& scene = file.scenes[s];
    NoriTestCase c;
    c.name = "scene " + std::to_string(s + 1) + " " + IntegratorTypeName(scene.integrator.type) +
             " (line " + std::to_string(s < file.child_lines.size() ? file.child_lines[s] : 0) +
             ")";
    const std::string unsupported = UnsupportedFeature(scene);
    if (!unsupported.empty()) {
      c.details.push_back(unsupported);
      c.verdict = NoriVerdict::kSkip;
    } else {
      const Bvh bvh = BuildBvh(scene.triangles, scene.spheres);
      const Camera camera(scene.camera);
      const RenderContext ctx{scene, bvh};
      const BidirectionalSetup bidirectional(scene);
      const uint64_t seed = MixBits(MixBits(options.seed ^ kSceneTTestSalt) + s);
      const float w = float(camera.width()), h = float(camera.height());
      const int64_t chunks = (samples + kSceneChunk - 1) / kSceneChunk;
      std::vector<RunningMoments> moments(static_cast<size_t>(chunks));
      std::vector<int64_t> nonfinite(size_t(chunks), 0);
      std::atomic<int64_t> next{0};
      auto worker = [&] {
        RayCounters counters;
        std::vector<LightSplat> splats;
        for (int64_t chunk; (chunk = next.fetch_add(1)) < chunks;) {
          const int64_t end = std::min(samples, (chunk + 1) * kSceneChunk);
          for (int64_t k = chunk * kSceneChunk; k < end; ++k) {
            // Independent samples whatever the scene's sampler: the t-test's variance estimate
            // assumes i.i.d. samples (a stratified set would make it conservative).
            PathSampler sampler(SamplerType::kIndependent, seed, uint32_t(k));
            const Vec2f pixel = sampler.Get2D(kDimensionPixel);
            const float px = std::min(pixel.x * w, std::nextafter(w, 0.0f));
            const float py = std::min(pixel.y * h, std::nextafter(h, 0.0f));
            const Vec2f lens = sampler.Get2D(kDimensionLens);
            const Ray ray = camera.GenerateRay(px, py, lens);
            Color3f L;
            if (IsBidirectional(scene.integrator.type)) {
              // The image's mean: the camera strategies plus every light-tracing contribution
              // (each splat's value is its share of the film's mean, CameraImportance).
              splats.clear();
              L = LiBidirectional(ctx, bidirectional, ray, sampler, &counters, &splats);
              for (const LightSplat& s : splats) L += s.value;
            } else {
              L = Li(ctx, ray, sampler, &counters);
            }
            if (!IsFinite(L)) {
              ++nonfinite[size_t(chunk)];
              continue;
            }
            moments[size_t(chunk)].Add(double(Luminance(L)));
          }
        }
      };
      const int threads = int(std::clamp<int64_t>(options.threads, 1, chunks));
      std::vector<std::thread> pool;
      for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
      worker();
      for (std::thread& t : pool) t.join();
      RunningMoments m;
      int64_t bad = 0;
      for (int64_t i = 0; i < chunks; ++i) {
        m.Merge(moments[size_t(i)]);
        bad += nonfinite[size_t(i)];
      }
      if (bad > 0) {
        c.details.push_back(Printf("%.0f of %.0f radiance samples were NaN or Inf (left out)",
                                   double(bad), double(samples)));
      }
      if (m.n >= 2) {
        FinishTTest(m, file.properties.references[s], file.properties.significance_level,
                    report->test_count, &c);
      } else {
        c.verdict = NoriVerdict::kFail;
      }
    }
    report->cases.push_back(c);
    if (options.on_case) options.on_case(report->cases.back());
  }
}

// Nori's chi2test, run through our χ² library (RunChi2Test) with Nori's parameters.
void RunChi2Tests(const NoriTestFile& file, const NoriTestOptions& options, int64_t samples,
                  size_t* case_index, NoriTestReport* report) {
  const NoriTestProperties& p = file.properties;
  Pcg32 directions(MixBits(options.seed ^ kChi2DirectionSalt), 0);
  const std::string stem = std::filesystem::path(file.path).filename().string();
  for (size_t b = 0; b < file.bsdfs.size(); ++b) {
    const MaterialRef ref = file.bsdfs[b];
    for (int l = 0; l < p.test_count; ++l) {
      // Nori: cos θ and φ / 2π uniform, so wo covers the upper hemisphere.
      const float cos_theta = directions.NextFloat();
      const float phi = 2.0f * kPi * directions.NextFloat();
      const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
      const Vec3f wo{sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
      if (!RunsNextCase(options, case_index)) continue;  // after the draws: wo stays the same
      NoriTestCase c;
      c.name = BsdfName(file, b) + " test " + std::to_string(l + 1) +
               Printf(" wo=(%.3f, %.3f, %.3f)", wo.x, wo.y, wo.z);
      if (IsDeltaMaterial(ref.tag())) {
        c.details.push_back(std::string("bsdf '") + MaterialName(ref.tag()) +
                            "' is a delta BSDF: it has no density for a chi-square test");
        c.verdict = NoriVerdict::kSkip;
      } else {
        const MaterialTables& m = file.materials;
        Chi2Subject subject;
        subject.name =
            "nori/" + stem + "/bsdf" + std::to_string(b + 1) + "/test" + std::to_string(l + 1);
        subject.params = c.name;
        subject.domain = Chi2Domain::Sphere();
        subject.uniform_dims = 3;
        subject.albedo = kChi2UnknownAlbedo;
        subject.sample = [&m, ref, wo](float u1, const Vec2f& u2, Chi2Point* point) {
          BsdfSample s;
          if (!BsdfSampleDirection(m, ref, wo, u1, u2, &s)) return false;
          *point = s.wi;
          return true;
        };
        subject.pdf = [&m, ref, wo](const Chi2Point& wi) {
          return double(BsdfPdf(m, ref, wo, wi));
        };
        Chi2Options o;
        o.samples = samples;
        o.res = p.resolution;
        o.seed = options.seed;
        o.alpha = p.significance_level;
        o.test_count = report->test_count;
        o.min_expected = p.min_exp_frequency;
        // Nori's test as written: its grid is coarse already (10 × 20 cells by default), and
        // its significance level is the file's, not split with a second grid.
        o.coarse_blocks = 0;
        // Nori's cells are large (18° × 0.2 in cos θ), and in their far tails a peaked lobe's
        // pdf underflows float, where a purely relative tolerance can never be met: without an
        // absolute floor those cells exhaust the evaluation budget and the cells next to them
        // come out inaccurate (measured: 2 % low at the horizon). A cell whose integral is
        // settled to 1e-12 holds < 1e-5 expected samples at 10^7 samples.
        o.simpson.outer.abs_tol = kChi2CellAbsTol;
        o.simpson.inner.abs_tol = kChi2CellAbsTol;
        const Chi2Result r = RunChi2Test(subject, o);
        c.samples = r.samples;
        c.statistic = r.chi2;
        c.dof = r.dof;
        c.p_value = r.p_value;
        c.alpha = r.alpha;
        c.details = r.failures;
        c.details.insert(c.details.end(), r.notes.begin(), r.notes.end());
        c.verdict = r.pass ? NoriVerdict::kPass : NoriVerdict::kFail;
        if (!r.pass && !options.chi2_report_dir.empty()) {
          const Status written = WriteChi2Report(options.chi2_report_dir, r);
          c.details.push_back(written.ok() ? "report: " + options.chi2_report_dir + "/" +
                                                 Chi2FileStem(r.name) + ".png"
                                           : "report not written: " + written.message());
        }
      }
      report->cases.push_back(c);
      if (options.on_case) options.on_case(report->cases.back());
    }
  }
}

}  // namespace

const char* NoriVerdictName(NoriVerdict verdict) {
  switch (verdict) {
    case NoriVerdict::kPass:
      return "PASS";
    case NoriVerdict::kFail:
      return "FAIL";
    case NoriVerdict::kSkip:
      return "SKIP";
  }
  return "?";
}

int NoriTestReport::Count(NoriVerdict v) const {
  return int(std::count_if(cases.begin(), cases.end(),
                           [v](const NoriTestCase& c) { return c.verdict == v; }));
}

NoriVerdict NoriTestReport::Verdict() const {
  if (Count(NoriVerdict::kFail) > 0) return NoriVerdict::kFail;
  if (!skip_reason.empty() || Count(NoriVerdict::kSkip) > 0) return NoriVerdict::kSkip;
  return NoriVerdict::kPass;
}

NoriTestReport RunNoriTestFile(const NoriTestFile& file, const NoriTestOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  NoriTestReport report;
  report.path = file.path;
  report.type = file.type;
  report.properties = file.properties;
  const int64_t samples = options.sample_count_override > 0 ? options.sample_count_override
                                                            : file.properties.sample_count;
  report.properties.sample_count = int(samples);
  size_t case_index = 0;
  if (file.type == NoriTestType::kChi2Test) {
    report.test_count = file.properties.test_count * int(file.bsdfs.size());
    RunChi2Tests(file, options, samples, &case_index, &report);
  } else {
    report.test_count = int(file.properties.references.size());
    if (!file.bsdfs.empty()) RunBsdfTTests(file, options, samples, &case_index, &report);
    RunSceneTTests(file, options, samples, &case_index, &report);
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

StatusOr<NoriTestReport> RunNoriTest(const std::string& path, const NoriTestOptions& options) {
  StatusOr<NoriTestFile> file = LoadNoriTestFile(path);
  if (!file.ok()) {
    if (!IsUnsupportedFeatureMessage(file.status().message())) return file.status();
    NoriTestReport report;
    report.path = path;
    report.skip_reason = file.status().message();
    return report;
  }
  return RunNoriTestFile(*file, options);
}

std::string FormatNoriTestCase(const NoriTestCase& c, bool details) {
  char buf[512];
  std::string s = std::string(NoriVerdictName(c.verdict)) + "  " + c.name;
  if (!std::isnan(c.reference)) {
    std::snprintf(buf, sizeof(buf),
                  ": estimate %.6g vs reference %.6g  t=%+.3f p=%.4g alpha'=%.3g n=%lld",
                  c.estimate, c.reference, c.statistic, c.p_value, c.alpha,
                  static_cast<long long>(c.samples));
    s += buf;
    if (details) s += Printf("  (variance %.4g)", c.variance);
  } else if (!std::isnan(c.statistic)) {
    std::snprintf(buf, sizeof(buf), ": chi2=%.1f dof=%.0f p=%.4g alpha'=%.3g n=%lld", c.statistic,
                  c.dof, c.p_value, c.alpha, static_cast<long long>(c.samples));
    s += buf;
  }
  if (details || c.verdict != NoriVerdict::kPass)
    for (const std::string& d : c.details) s += "\n      - " + d;
  return s;
}

bool IsUnsupportedFeatureMessage(const std::string& message) {
  return message.find("not supported yet") != std::string::npos;
}

std::string FormatNoriTestHeader(const NoriTestFile& file) {
  const NoriTestProperties& p = file.properties;
  const bool ttest = file.type == NoriTestType::kTTest;
  const int tests = ttest ? int(p.references.size()) : p.test_count * int(file.bsdfs.size());
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "%s: %s, %d tests, %d samples each, significance %g (Sidak: alpha' = %.4g per "
                "test)",
                file.path.c_str(), ttest ? "ttest" : "chi2test", tests, p.sample_count,
                double(p.significance_level), SidakAlpha(p.significance_level, tests));
  return buf;
}

std::string FormatNoriTestSummary(const NoriTestReport& report) {
  const int passed = report.Count(NoriVerdict::kPass), failed = report.Count(NoriVerdict::kFail),
            skipped = report.Count(NoriVerdict::kSkip);
  char buf[1024];
  std::snprintf(buf, sizeof buf, "%s: %s: passed %d/%d, failed %d, skipped %d (%.1f s)",
                report.path.c_str(), NoriVerdictName(report.Verdict()), passed,
                int(report.cases.size()), failed, skipped, report.seconds);
  return buf;
}

int NoriTestExitCode(const NoriTestReport& report) {
  switch (report.Verdict()) {
    case NoriVerdict::kPass:
      return kExitOk;
    case NoriVerdict::kFail:
      return kExitFailed;
    case NoriVerdict::kSkip:
      return kExitSkipped;
  }
  return kExitFailed;
}

int RunNoriTestCommand(const std::string& path, bool verbose) {
  StatusOr<NoriTestFile> file = LoadNoriTestFile(path);
  if (!file.ok()) {
    if (IsUnsupportedFeatureMessage(file.status().message())) {
      std::printf("SKIP  %s\n      - %s\n", path.c_str(), file.status().message().c_str());
      std::printf("%s: skipped (a feature it needs is not supported yet)\n", path.c_str());
      return kExitSkipped;
    }
    std::fprintf(stderr, "error: %s\n", file.status().message().c_str());
    return kExitUsage;
  }
  std::printf("%s\n", FormatNoriTestHeader(*file).c_str());
  std::fflush(stdout);
  NoriTestOptions options;
  options.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  options.on_case = [verbose](const NoriTestCase& c) {
    std::printf("%s\n", FormatNoriTestCase(c, verbose).c_str());
    std::fflush(stdout);
  };
  const NoriTestReport report = RunNoriTestFile(*file, options);
  std::printf("%s\n", FormatNoriTestSummary(report).c_str());
  return NoriTestExitCode(report);
}

}  // namespace ptlab
