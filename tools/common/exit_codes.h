// The exit codes of every ptlab tool (ptlab render/converge/test/envmap-pdf, imgdiff, chi2,
// chi2 check): one table, documented in docs/robustness.md. main() functions return these
// names, never bare numbers.
#pragma once

namespace ptlab {

/// Success: the render was written, the comparison or the test passed.
inline constexpr int kExitOk = 0;
/// The verdict is negative: a statistical test rejected, an image is over a threshold, fails
/// parity or has another size than the reference.
inline constexpr int kExitFailed = 1;
/// Bad usage or bad input: a flag, a file that cannot be read or used (scene, mesh, image,
/// sample file, pdf program), an output that would overwrite an input or another output.
/// Nothing was written.
inline constexpr int kExitUsage = 2;
/// The run could not complete: an output folder that is missing or read-only, a write that
/// failed, a worker thread that cannot start, a render error.
inline constexpr int kExitRunFailed = 3;
/// Skipped: `ptlab test` on a file that needs a feature ptlab does not support yet.
inline constexpr int kExitSkipped = 4;
/// Stopped by SIGINT (Ctrl-C) or SIGTERM after writing what was complete (128 + signal).
inline constexpr int kExitInterrupted = 130;
inline constexpr int kExitTerminated = 143;

}  // namespace ptlab
