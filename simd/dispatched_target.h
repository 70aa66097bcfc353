// Which Highway target the simd/ kernels dispatch to now: one name for logs, tests and benchmarks.
#pragma once

namespace ptlab::simd {

/// Name of the Highway target HWY_DYNAMIC_DISPATCH picks now (e.g. "AVX3", "AVX2", "SSE4").
/// Every simd/*.cpp compiles its kernels for the same targets (simd/targets.h, its first
/// include) and dispatches with the same chosen-target state, so this is the target of every
/// simd/ kernel, including under hwy::SetSupportedTargetsForTest.
const char* DispatchedTargetName();

}  // namespace ptlab::simd
