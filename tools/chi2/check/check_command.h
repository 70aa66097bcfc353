// `chi2 check`: the file-based route of the lab, for samplers written in any language.
#pragma once

namespace ptlab {

/// Runs `chi2 check ...` (argv[0] is "check"). Exit code: 0 the test passed, 1 it failed,
/// 2 bad input (usage, unreadable or malformed sample file, samples outside the domain, a pdf
/// program that failed, timed out or printed garbage, unwritable image directory).
int RunCheckCommand(int argc, char** argv);

}  // namespace ptlab
