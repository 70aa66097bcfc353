// RenderSetup: BVH -> BVH8 -> triangle rows -> kernel table, built once per scene.
#include "simd/render_setup.h"

#include <chrono>

#include "engine/bvh/scene_bvh.h"
#include "engine/core/check.h"
#include "engine/core/memory.h"
#include "simd/dispatched_target.h"
#include "simd/traverse8.h"
#include "simd/wavefront/kernels8.h"

namespace ptlab {

KernelChoice ChooseKernels(bool scalar) {
  return scalar || ForceScalar() ? KernelChoice::kOracle : KernelChoice::kSimd;
}

RenderSetup::RenderSetup(const Scene& scene, KernelChoice choice, int threads)
    : choice_(choice) {
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  auto start = Clock::now();
  bvh_ = BuildSceneBvh(scene, threads);
  bvh_seconds_ = seconds_since(start);
  peak_after_bvh_ = PeakResidentBytes();
  oracle_ = OracleWavefrontKernels(bvh_);
  if (packets()) {
    start = Clock::now();
    bvh8_ = simd::BuildBvh8(bvh_);
    rows_ = simd::BuildTriangleRows(scene);
    simd_ = simd::SimdWavefrontKernels(bvh8_, rows_);
    bvh8_seconds_ = seconds_since(start);
  }
  peak_after_bvh8_ = PeakResidentBytes();
}

const WavefrontKernels& RenderSetup::simd_kernels() const {
  PTLAB_CHECK(packets());
  return simd_;
}

const WavefrontKernels& RenderSetup::KernelsFor(bool scalar) const {
  return scalar || ForceScalar() ? oracle_ : kernels();
}

std::string RenderSetup::TraversalName() const {
  return packets() ? std::string("packet8 ") + simd::DispatchedTargetName() : std::string("scalar");
}

RenderResult Render(const Scene& scene, const RenderSetup& setup, RenderOptions options) {
  options.kernels = &setup.kernels();
  return Render(scene, setup.bvh(), options);
}

}  // namespace ptlab
