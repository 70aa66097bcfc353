// Render setup in one place: a scene's acceleration structures (BVH, then BVH8 and triangle
// rows) and the wavefront's kernel table that runs on them, the oracle's or simd/'s.
//
// Why here: the SIMD table needs simd/'s BVH8, triangle rows and kernels, and engine/ never
// includes simd/, so this cannot live in engine/render/. It is a plain C++ file of simd/ (it
// includes no hwy/ header and names no target) because simd/ is the lowest floor that sees both
// tables; the CLI (render, converge), the benchmarks and the tests all set up through it.
#pragma once

#include <cstdint>

#include "engine/bvh/bvh.h"
#include "engine/render/render.h"
#include "engine/wavefront/wavefront.h"
#include "simd/bvh8.h"
#include "simd/triangle_rows.h"

namespace ptlab {

/// Which kernel table a render runs: simd/'s 8-wide kernels (the default of `ptlab render`)
/// or the oracle's (`--scalar`, PTLAB_FORCE_SCALAR=1), which renders the same bits one ray at
/// a time.
enum class KernelChoice { kSimd, kOracle };

/// kOracle when `scalar` or ForceScalar(), else kSimd: the one switch of the tools.
KernelChoice ChooseKernels(bool scalar);

/// A scene's BVH, and for kSimd its BVH8 and triangle rows, with the kernel tables on them.
/// The tables point into the object, so it is neither copied nor moved (construct it where it
/// lives). It holds copies of the scene's geometry only: the scene itself is read at render
/// time (Render's `scene` must be the one set up, or one with the same triangles and spheres).
class RenderSetup {
 public:
  /// Builds the BVH (on `threads` threads: the same tree for any count); with kSimd, also the
  /// BVH8 collapsed from it and the triangle rows.
  RenderSetup(const Scene& scene, KernelChoice choice, int threads = 1);
  RenderSetup(const RenderSetup&) = delete;
  RenderSetup& operator=(const RenderSetup&) = delete;

  KernelChoice choice() const { return choice_; }
  bool packets() const { return choice_ == KernelChoice::kSimd; }
  /// The table chosen: simd/'s for kSimd, else the oracle's.
  const WavefrontKernels& kernels() const { return packets() ? simd_ : oracle_; }
  /// The oracle's table (always set up: it needs only the BVH).
  const WavefrontKernels& oracle_kernels() const { return oracle_; }
  /// simd/'s table; only with kSimd.
  const WavefrontKernels& simd_kernels() const;
  /// The table for a render that may ask for the oracle (`scalar`) per run, as converge's
  /// variants do: the oracle's when `scalar` or ForceScalar(), else kernels().
  const WavefrontKernels& KernelsFor(bool scalar) const;

  const Bvh& bvh() const { return bvh_; }
  /// Empty with kOracle.
  const simd::Bvh8& bvh8() const { return bvh8_; }
  const simd::TriangleRows& rows() const { return rows_; }

  /// "scalar" or "packet8 <Highway target>" (the EXR's ptlab:traversal).
  std::string TraversalName() const;

  /// Peak resident bytes of the process after each build step (getrusage's peak only grows).
  uint64_t peak_after_bvh() const { return peak_after_bvh_; }
  uint64_t peak_after_bvh8() const { return peak_after_bvh8_; }
  /// Wall seconds of the build steps: the BVH; the BVH8 and triangle rows (0 with kOracle).
  double bvh_seconds() const { return bvh_seconds_; }
  double bvh8_seconds() const { return bvh8_seconds_; }

 private:
  KernelChoice choice_;
  Bvh bvh_;
  simd::Bvh8 bvh8_;
  simd::TriangleRows rows_;
  WavefrontKernels oracle_, simd_;
  uint64_t peak_after_bvh_ = 0, peak_after_bvh8_ = 0;
  double bvh_seconds_ = 0, bvh8_seconds_ = 0;
};

/// Render(scene, setup.bvh(), options) with options.kernels = the setup's chosen table.
RenderResult Render(const Scene& scene, const RenderSetup& setup, RenderOptions options);

}  // namespace ptlab
