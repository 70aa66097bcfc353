// Atomic output files: the one way ptlab writes a result file (images, reports, tile times).
#pragma once

#include <string>
#include <string_view>

#include "engine/core/status.h"

namespace ptlab {

/// Replaces the file at `path` by `bytes` atomically: writes `<path>.tmp-<pid>` in the same
/// directory, then renames it over `path`. On any failure the temporary is removed and an error
/// naming the file is returned; an existing `path` is then left untouched, never half-written.
/// Not for concurrent writes of the same path from several threads of one process.
Status WriteFileAtomically(const std::string& path, std::string_view bytes);

/// Before a long computation whose result goes to `path` (through WriteFileAtomically):
/// removes the temporaries `<path>.tmp-<pid>` left by processes that no longer run (a render
/// killed with SIGKILL), then checks that `path` can be written by creating and removing this
/// process's temporary beside it. The error names `path` and says what is wrong.
Status PrepareOutputFile(const std::string& path);

}  // namespace ptlab
