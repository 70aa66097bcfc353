// normal: Mitsuba's `normalmap` and `bumpmap` as a component of material rows: a row whose
// shading frame a texture perturbs before its own BSDF is evaluated (the row keeps its tag).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/scene/refs.h"

namespace ptlab {

enum class PerturbationKind : uint8_t {
  kNormalMap,  // the texture's RGB c is the normal 2c − 1 in the shading frame (tangent space)
  kBumpMap,    // scale × the texture's luminance is a height along the shading normal
};

/// The perturbed rows of every tag and, per perturbation, its kind, texture and scale; plus the
/// uv tangents ∂p/∂u, ∂p/∂v of every scene triangle (world space, BuildSurfaceTangents), which
/// the perturbed frames read. Like TwoSidedFlags, one column per tag, empty until a row of the
/// tag is perturbed: a scene without normal or bump maps holds nothing and pays one empty()
/// test per BSDF call (engine/bsdf/perturbed_frame.h).
struct ShadingPerturbations {
  /// by_tag[tag][row] = perturbation id + 1 (0: the row is not perturbed); rows past the end
  /// are not perturbed.
  AlignedVector<uint32_t> by_tag[kMaterialTagCount];
  AlignedVector<uint8_t> kind;     // PerturbationKind
  AlignedVector<uint32_t> texture; // a TextureTable row
  AlignedVector<float> scale;      // bump maps: the height's scale (normal maps: 1)
  /// Per scene triangle (TriangleTable row): ∂p/∂u and ∂p/∂v, empty without perturbations.
  AlignedVector<float> dp_du_x, dp_du_y, dp_du_z, dp_dv_x, dp_dv_y, dp_dv_z;

  bool empty() const { return kind.empty(); }
  size_t size() const { return kind.size(); }
  /// Perturbs row `ref`; false when it is already perturbed (one perturbation per row).
  bool Add(MaterialRef ref, PerturbationKind k, uint32_t texture_id, float s) {
    AlignedVector<uint32_t>& c = by_tag[static_cast<int>(ref.tag())];
    if (c.size() <= ref.index()) c.resize(ref.index() + 1, 0u);
    if (c[ref.index()] != 0) return false;
    kind.push_back(uint8_t(k)), texture.push_back(texture_id), scale.push_back(s);
    c[ref.index()] = uint32_t(kind.size());
    return true;
  }
  /// Replaces the perturbation of a perturbed row `ref` (its id stays).
  void Replace(MaterialRef ref, PerturbationKind k, uint32_t texture_id, float s) {
    const int64_t id = Of(ref);
    kind[size_t(id)] = uint8_t(k), texture[size_t(id)] = texture_id, scale[size_t(id)] = s;
  }
  /// The perturbation id of `ref`, or -1.
  int64_t Of(MaterialRef ref) const {
    const int t = static_cast<int>(ref.tag());
    if (t >= kMaterialTagCount) return -1;
    const AlignedVector<uint32_t>& c = by_tag[t];
    return ref.index() < c.size() ? int64_t(c[ref.index()]) - 1 : -1;
  }
  /// True when some row of `tag` is perturbed.
  bool Any(MaterialTag tag) const { return !by_tag[static_cast<int>(tag)].empty(); }
};

}  // namespace ptlab
