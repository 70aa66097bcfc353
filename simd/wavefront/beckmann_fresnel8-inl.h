// The batch kernels of simd/wavefront/bsdf8.h's Beckmann and Fresnel entry points.
// Part of simd/wavefront/bsdf8-inl.h: included there, it uses that file's block driver and helpers.

#if defined(PTLAB_SIMD_BECKMANN_FRESNEL8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PTLAB_SIMD_BECKMANN_FRESNEL8_INL_H_
#undef PTLAB_SIMD_BECKMANN_FRESNEL8_INL_H_
#else
#define PTLAB_SIMD_BECKMANN_FRESNEL8_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace ptlab::simd {
namespace HWY_NAMESPACE {

inline void BeckmannEvalPdfKernel(const float* alpha, DirectionArrays wo, DirectionArrays wi,
                                  size_t n, float* d_out, float* pdf_out) {
  BlockIo<7, 2> io;
  io.in[0] = alpha;
  io.in[1] = wo.x, io.in[2] = wo.y, io.in[3] = wo.z;
  io.in[4] = wi.x, io.in[5] = wi.y, io.in[6] = wi.z;
  io.out[0] = d_out, io.out[1] = pdf_out;
  ForEachBlock(io, n, [](const BlockIo<7, 2>& b, size_t i) HWY_ATTR {
    const D8 d;
    const V8 alpha_v = ClampAlpha(d, Load(d, b.in[0], i));
    V8 pdf;
    const V8 dv =
        BeckmannEvalPdf(d, alpha_v, Load(d, b.in[1], i), Load(d, b.in[2], i), Load(d, b.in[3], i),
                        Load(d, b.in[4], i), Load(d, b.in[5], i), Load(d, b.in[6], i), &pdf);
    Store(d, dv, b.out[0], i);
    Store(d, pdf, b.out[1], i);
  });
}

inline void SampleBeckmannReflectionKernel(const float* alpha, DirectionArrays wo, const float* u_x,
                                           const float* u_y, size_t n, DirectionOutArrays wi,
                                           float* pdf_out) {
  BlockIo<6, 4> io;
  io.in[0] = alpha;
  io.in[1] = wo.x, io.in[2] = wo.y, io.in[3] = wo.z;
  io.in[4] = u_x, io.in[5] = u_y;
  io.out[0] = wi.x, io.out[1] = wi.y, io.out[2] = wi.z, io.out[3] = pdf_out;
  ForEachBlock(io, n, [](const BlockIo<6, 4>& b, size_t i) HWY_ATTR {
    const D8 d;
    const V8 alpha_v = ClampAlpha(d, Load(d, b.in[0], i));
    const V8 ox = Load(d, b.in[1], i), oy = Load(d, b.in[2], i), oz = Load(d, b.in[3], i);
    V8 hx, hy, hz, ix, iy, iz, pdf;
    SampleBeckmannNormal(d, alpha_v, Load(d, b.in[4], i), Load(d, b.in[5], i), &hx, &hy, &hz);
    Reflect(d, ox, oy, oz, hx, hy, hz, &ix, &iy, &iz);
    BeckmannEvalPdf(d, alpha_v, ox, oy, oz, ix, iy, iz, &pdf);
    const M8 ok = hn::Gt(pdf, hn::Zero(d));
    Store(d, hn::IfThenElseZero(ok, ix), b.out[0], i);
    Store(d, hn::IfThenElseZero(ok, iy), b.out[1], i);
    Store(d, hn::IfThenElseZero(ok, iz), b.out[2], i);
    Store(d, pdf, b.out[3], i);
  });
}

inline void ConductorFresnelKernel(const float* cos_i, const float* eta, const float* k, size_t n,
                                   float* f) {
  BlockIo<3, 1> io;
  io.in[0] = cos_i, io.in[1] = eta, io.in[2] = k;
  io.out[0] = f;
  ForEachBlock(io, n, [](const BlockIo<3, 1>& b, size_t i) HWY_ATTR {
    const D8 d;
    Store(d, FresnelConductor(d, Load(d, b.in[0], i), Load(d, b.in[1], i), Load(d, b.in[2], i)),
          b.out[0], i);
  });
}

inline void DielectricFresnelKernel(const float* cos_i, const float* eta, size_t n, float* f,
                                    float* cos_t) {
  BlockIo<2, 2> io;
  io.in[0] = cos_i, io.in[1] = eta;
  io.out[0] = f, io.out[1] = cos_t;
  ForEachBlock(io, n, [](const BlockIo<2, 2>& b, size_t i) HWY_ATTR {
    const D8 d;
    V8 ct;
    Store(d, FresnelDielectric(d, Load(d, b.in[0], i), Load(d, b.in[1], i), &ct), b.out[0], i);
    Store(d, ct, b.out[1], i);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace ptlab::simd
HWY_AFTER_NAMESPACE();

#endif  // PTLAB_SIMD_BECKMANN_FRESNEL8_INL_H_ toggle
