// Closed-set references into component tables: a 4-bit tag and a 28-bit row index.
#pragma once

#include <cstdint>

namespace ptlab {

/// The closed set of BSDF models. A material is (tag, row in that model's table).
enum class MaterialTag : uint8_t {
  kDiffuse = 0,
  kMirror = 1,
  kDielectric = 2,
  kConductor = 3,
  kRoughPlastic = 4,
  // matA: Mitsuba's roughdielectric (6 is unused: `conductor` is a mirror row).
  kRoughDielectric = 5,
  // mask: Mitsuba's `mask` (a nested material with an opacity, else pass-through).
  kMask = 6,
  // matB: Mitsuba's coated plastics (plastic, roughplastic), thindielectric, blendbsdf.
  kPlastic = 7,
  kThinDielectric = 8,
  kBlend = 9,
  // principled: Mitsuba's principled and principledthin (engine/bsdf/principled*.h).
  kPrincipled = 10,
  kPrincipledThin = 11,
};
inline constexpr int kMaterialTagCount = 12;

/// The closed set of emitter kinds.
enum class EmitterTag : uint8_t {
  kArea = 0,
  kEnvironment = 1,
  kDistantDisk = 2,
  kPoint = 3,
  kDirectional = 4,
  kSpot = 5,
  kProjector = 6,
};

/// tag:4 | index:28, as in MaterialRef and EmitterRef.
template <typename Tag>
struct TaggedRef {
  uint32_t bits = 0xffffffffu;

  static constexpr TaggedRef Make(Tag tag, uint32_t index) {
    return TaggedRef{(static_cast<uint32_t>(tag) << 28) | (index & 0x0fffffffu)};
  }
  static constexpr TaggedRef None() { return TaggedRef{}; }
  constexpr bool valid() const { return bits != 0xffffffffu; }
  constexpr Tag tag() const { return static_cast<Tag>(bits >> 28); }
  constexpr uint32_t index() const { return bits & 0x0fffffffu; }
  constexpr bool operator==(const TaggedRef&) const = default;
};

using MaterialRef = TaggedRef<MaterialTag>;
using EmitterRef = TaggedRef<EmitterTag>;

}  // namespace ptlab
