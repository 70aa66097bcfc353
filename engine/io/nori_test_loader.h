// Nori statistical test files (`<test type="ttest|chi2test">` roots) loaded into plain data.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/status.h"
#include "engine/scene/material_tables.h"
#include "engine/scene/scene.h"
#include "engine/io/xml_loader.h"

namespace ptlab {

/// Limits on a test file's counts: the automatic chi² sample count resolution x 2·resolution x
/// 5000 then fits an int, and the histograms and sample counts fit memory and time.
inline constexpr int kMaxNoriTestResolution = 256;
inline constexpr int kMaxNoriTestSampleCount = 1000000000;
inline constexpr int kMaxNoriTestCount = 10000;

enum class NoriTestType : uint8_t {
  kTTest,     // Nori `ttest`: Student t-tests of BSDF albedos or of 1-pixel scene radiance
  kChi2Test,  // Nori `chi2test`: χ² tests of BSDF sampling against the BSDF's pdf
};

/// The properties of a `<test>`, with Nori's defaults (src/ttest.cpp, src/chi2test.cpp).
struct NoriTestProperties {
  /// Family-wise significance: Šidák-corrected over all tests of the file.
  float significance_level = 0.01f;
  /// ttest: samples per test (100000). chi2test: samples per test; -1 = automatic,
  /// resolution × 2·resolution × 5000.
  int sample_count = 100000;
  /// ttest: incident angles in degrees (BSDF tests only) and one reference per test, in file
  /// order (BSDF-major: references[b · angles.size() + i] is BSDF b at angles[i]).
  std::vector<float> angles, references;
  /// chi2test: cells along cosθ (φ gets twice as many), minimum expected cell count (smaller
  /// cells are pooled), random incident directions per BSDF.
  int resolution = 10;
  int min_exp_frequency = 5;
  int test_count = 5;
};

/// A loaded test file: its type and properties, and either its scenes or its BSDFs.
struct NoriTestFile {
  std::string path;
  NoriTestType type = NoriTestType::kTTest;
  NoriTestProperties properties;
  std::vector<Scene> scenes;       // each parsed exactly like a scene file
  MaterialTables materials;        // rows of the BSDFs below
  std::vector<MaterialRef> bsdfs;  // the `<bsdf>` children, in file order
  std::vector<int> child_lines;    // line of each scene or BSDF, for reports
};

/// Loads a Nori test file. Relative file names inside its scenes resolve against the directory
/// of `path`. Format (Nori's, made strict):
/// - root `<test type="ttest">` with `<float name="significanceLevel">`, `<integer
///   name="sampleCount">`, `<string name="references">` (required) and `<string name="angles">`
///   (numbers separated by commas and/or whitespace), and either `<scene>` children (one
///   reference each; no angles) or `<bsdf>` children (references = angles × BSDFs);
/// - root `<test type="chi2test">` with `<float name="significanceLevel">` and `<integer
///   name="resolution|minExpFrequency|sampleCount|testCount">`, and `<bsdf>` children only.
/// Unknown or duplicate properties, wrong property types, malformed or out-of-range values,
/// count mismatches, other children and any error inside a scene or BSDF are errors naming
/// "file:line:col" and what was expected. Features a scene uses that the loader does not support
/// yet fail with the loader's message (which says "not supported yet").
StatusOr<NoriTestFile> LoadNoriTestFile(const std::string& path, const LoadOptions& options = {});

/// As LoadNoriTestFile, from XML text in memory: relative file names resolve against `base_dir`
/// and messages name `display_name`.
StatusOr<NoriTestFile> LoadNoriTestFileFromString(const std::string& xml,
                                                  const std::string& base_dir,
                                                  const std::string& display_name,
                                                  const LoadOptions& options = {});

}  // namespace ptlab
