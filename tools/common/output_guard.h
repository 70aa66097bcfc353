// The one output guard of ptlab's tools: before any work, every output path is resolved and
// checked against every input the run reads and every other output, and probed for creation,
// so no run overwrites its own scene, mesh, map, camera file or reference, writes two outputs
// into one file, or renders for minutes before finding its output folder missing.
#pragma once

#include <string>
#include <vector>

#include "engine/core/status.h"

namespace ptlab {

class OutputGuard {
 public:
  /// A file the run reads; `role` names it in messages ("scene", "-c camera file", ...).
  /// Empty paths are ignored.
  void AddInput(const std::string& path, const std::string& role);
  void AddInputs(const std::vector<std::string>& paths, const std::string& role);
  /// A file the run writes (through WriteFileAtomically or an image writer: a temporary
  /// `<path>.tmp-<pid>` beside it, then a rename). Empty paths are ignored.
  void AddOutput(const std::string& path, const std::string& role);

  /// Refusals that are bad usage (kExitUsage): an output whose name or temporary's name is longer
  /// than the system allows (NAME_MAX / PATH_MAX), an output that is a directory, and an output
  /// that is the same file as an input or as another output (same device and inode, or the same
  /// resolved path). The message names both paths and their roles.
  Status CheckPaths() const;

  /// Output failures (kExitRunFailed): an output folder that does not exist or cannot be written to;
  /// PrepareOutputFile creates and removes this process's temporary beside each output (and
  /// removes stale temporaries of dead processes).
  Status ProbeOutputs() const;

  /// CheckPaths, then ProbeOutputs: kExitOk when both pass, else the exit code of the first
  /// that fails (kExitUsage or kExitRunFailed), with its message in *error.
  int Check(std::string* error) const;

 private:
  struct Entry {
    std::string path, role;
  };
  std::vector<Entry> inputs_, outputs_;
};

/// The check of a folder that a run fills with files of its own naming (`ptlab converge -o`):
/// created if missing, then probed for a file. Returns kExitOk, or kExitUsage (a name past
/// PATH_MAX) or kExitRunFailed (cannot be created or written) with *error set.
int PrepareOutputFolder(const std::string& folder, std::string* error);

}  // namespace ptlab
