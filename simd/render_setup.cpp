// RenderSetup: BVH -> BVH8 -> triangle rows -> kernel table, built once per scene.
#include "simd/render_setup.h"

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

RenderSetup::RenderSetup(const Scene& scene, KernelChoice choice) : choice_(choice) {
  bvh_ = BuildSceneBvh(scene);
  peak_after_bvh_ = PeakResidentBytes();
  oracle_ = OracleWavefrontKernels(bvh_);
  if (packets()) {
    bvh8_ = simd::BuildBvh8(bvh_);
    rows_ = simd::BuildTriangleRows(scene);
    simd_ = simd::SimdWavefrontKernels(bvh8_, rows_);
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
