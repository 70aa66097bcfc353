// Splat stage, the scalar oracle (engine/wavefront/splat.h).
#include "engine/wavefront/splat.h"

namespace ptlab {

void SplatSamples(const PixelFilter& filter, const FilmSamples& samples, FilmBlock* block) {
  for (size_t k = 0; k < samples.n; ++k) {
    block->Splat(filter, samples.sx[k], samples.sy[k],
                 Color3f{samples.r[k], samples.g[k], samples.b[k]});
  }
}

}  // namespace ptlab
