// Helpers of the tests that run the built tools as a user would: scratch folders, files, shells.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ptlab::test_util {

/// An empty folder build/test-output/<name> (removed and made anew).
inline std::filesystem::path TempDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(PTLAB_BINARY_DIR) / "test-output" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// The whole file as text ("" when it cannot be read).
inline std::string ReadFile(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Exit status of a bash command line, its stdout and stderr to `log` (-1: ended by a signal).
inline int RunShell(const std::string& command, const std::filesystem::path& log) {
  const std::string line = "bash -c '" + command + "' > " + log.string() + " 2>&1";
  const int rc = std::system(line.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

}  // namespace ptlab::test_util
