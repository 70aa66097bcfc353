// Peer renderers in `ptlab converge`: another renderer (Mitsuba 3, through its Python API)
// rendering the same scene in passes, measured against the same reference as ptlab's variants.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "engine/core/status.h"
#include "engine/image/image.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// "renderer=mitsuba3[,variant=llvm_ad_rgb|scalar_rgb][,sampler=independent|multijitter|
/// stratified|ldsampler|orthogonal][,max_depth=N][,rr_depth=N]" (Mitsuba's path integrator;
/// max_depth -1 is unbounded; without max_depth=, the scene's own depth as ptlab read it, in
/// Mitsuba's count (ptlab's bounces + 1), so that both renderers render the same image;
/// rr_depth >= 1, default 5).
struct PeerVariant {
  std::string renderer = "mitsuba3";
  std::string mitsuba_variant = "llvm_ad_rgb";
  std::string sampler = "independent";
  int max_depth = -1;
  bool max_depth_given = false;
  int rr_depth = 5;
};

/// Whether a variant spec names a peer renderer (it has a `renderer=` item).
bool IsPeerSpec(const std::string& spec);

/// Parses a peer spec; an unknown key or value is an error naming it and what is accepted.
StatusOr<PeerVariant> ParsePeerVariant(const std::string& spec);

/// The Python interpreter with Mitsuba 3: $PTLAB_MITSUBA_PYTHON, else the virtual environment
/// that `./lab peer-install` makes, ${XDG_CACHE_HOME:-$HOME/.cache}/ptlab/mitsuba-venv.
std::string PeerPython();

/// What a peer run renders: ptlab's loaded scene gives the film, filter and camera, so that
/// both renderers image the same thing; the scene file gives the shapes and materials.
struct PeerRunOptions {
  std::string scene_path;
  const Scene* scene = nullptr;  // camera and filter (after --width)
  std::string lookat = "nori";
  uint32_t spp = 0;     // total, in passes of pass_spp; or
  double time = 0;      // > 0: render seconds (whole passes)
  uint32_t pass_spp = 16;
  uint64_t seed = 1;
  int threads = 0;
  std::string work_dir;  // pass files go here (deleted as they are read)
  const std::atomic<bool>* cancel = nullptr;
};

/// One pass as ptlab measures it: the pass's own filter-weighted sums (R, G, B, weight per
/// pixel, row-major), and the cumulative render times of the passes so far.
struct PeerPass {
  uint32_t index = 0, spp_done = 0;
  double seconds = 0, cpu_seconds = 0;
  int width = 0, height = 0;
  const std::vector<float>* rgbw = nullptr;
};

/// What the peer reported about itself; load and warm-up times are excluded from the passes.
struct PeerSetup {
  std::string version;  // e.g. "Mitsuba 3.9.1 (llvm_ad_rgb)"
  double load_seconds = 0, warmup_seconds = 0;
};

/// Runs the peer; on_pass runs after every pass while the peer waits (not timed). Fails with
/// the peer's reason when Mitsuba is missing or cannot read the scene. *interrupted is set
/// when the run ended because of options.cancel or a signal.
Status RunPeer(const PeerVariant& variant, const PeerRunOptions& options,
               const std::function<void(const PeerPass&)>& on_pass, PeerSetup* setup,
               bool* interrupted);

/// Accumulates passes' weighted sums: the whole image and the even/odd halves.
class PeerFilm {
 public:
  PeerFilm(int width, int height);
  void Add(const PeerPass& pass);
  Image Resolve() const { return Resolve(total_); }
  Image ResolveHalf(int h) const { return Resolve(half_[h]); }

 private:
  Image Resolve(const std::vector<double>& sums) const;
  int width_, height_;
  std::vector<double> total_, half_[2];
};

}  // namespace ptlab
