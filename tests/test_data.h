// Third-party test data (Nori, CS184, Poly Haven and Mitsuba 3 scenes and references), which is
// never in the repository: one place that says where the tests find it. `./lab data` looks in
// the same place (tests/data/third_party.py) and downloads what is missing.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

namespace ptlab::test_data {

/// The data folder with a trailing '/': $PTLAB_DATA when set and not empty, else
/// ../shared/data beside the checkout.
inline std::string Dir() {
  const char* env = std::getenv("PTLAB_DATA");
  std::string dir = env != nullptr && *env != '\0' ? env : PTLAB_SOURCE_DIR "/../shared/data";
  if (dir.back() != '/') dir += '/';
  return dir;
}

/// A file or folder of the data, `rel` relative to Dir() ("nori/epfl/scenes/...").
inline std::string Path(std::string_view rel) { return Dir() + std::string(rel); }

/// True under CI=true: there a test that needs data fails instead of skipping.
inline bool Required() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string_view(ci) == "true";
}

}  // namespace ptlab::test_data

/// Skips the current test (or returns from the helper it is in) when `path` does not exist;
/// under CI=true fails it instead. `./lab test` counts the skips by the message's first words.
#define PTLAB_REQUIRE_DATA(path)                                                            \
  do {                                                                                      \
    const std::string ptlab_required_path_ = (path);                                        \
    if (!std::filesystem::exists(ptlab_required_path_)) {                                   \
      if (::ptlab::test_data::Required()) {                                                 \
        GTEST_FAIL() << "needs test data: " << ptlab_required_path_                         \
                     << " (CI=true: the data must be present; set PTLAB_DATA or run ./lab " \
                        "data)";                                                            \
      }                                                                                     \
      GTEST_SKIP() << "needs test data: " << ptlab_required_path_                           \
                   << " (set PTLAB_DATA or run ./lab data)";                                \
    }                                                                                       \
  } while (false)
