#include "engine/wavefront/shadow_rows.h"

namespace ptlab {

size_t CompactShadowRows(size_t n, const ShadowRowInputs& in, const ShadowRowOutputs& out) {
  size_t m = 0;
  for (size_t c = 0; c < n; ++c) {
    if (!in.traced[c]) continue;
    out.request[m] = in.request[c];
    out.o_x[m] = in.o_x[c], out.o_y[m] = in.o_y[c], out.o_z[m] = in.o_z[c];
    out.d_x[m] = in.d_x[c], out.d_y[m] = in.d_y[c], out.d_z[m] = in.d_z[c];
    out.r[m] = in.r[c], out.g[m] = in.g[c], out.b[m] = in.b[c];
    ++m;
  }
  return m;
}

}  // namespace ptlab
