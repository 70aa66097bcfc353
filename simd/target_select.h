// Pinning the SIMD dispatch to one compiled Highway target at run time (the PTLAB_TARGET
// environment variable), to measure a target the CPU would not pick: AVX2 on an AVX-512 machine.
#pragma once

#include <string>

#include "engine/core/status.h"

namespace ptlab::simd {

/// The compiled targets this CPU can run, best first, by Highway's names ("AVX3 AVX2 SSE4").
std::string AvailableTargetNames();

/// When PTLAB_TARGET names one of AvailableTargetNames() (any case), every dispatch from now on
/// goes to that target; unset or empty: Highway's own choice, the best one. Any other value is
/// an error that names the accepted ones (the caller exits 2).
Status SelectTargetFromEnvironment();

}  // namespace ptlab::simd
