// 8-wide ray and hit packets: plain aligned SoA arrays (no Highway types), like Embree's RTCRay8.
#pragma once

// The types live in engine/core/packet8.h so that the scalar render driver can fill and read
// packets without including anything from simd/; they are the same types here.
#include "engine/core/packet8.h"

namespace ptlab::simd {

using ::ptlab::HitPacket8;
using ::ptlab::kAllLanes;
using ::ptlab::kPacketWidth;
using ::ptlab::Mask8;
using ::ptlab::RayPacket8;

}  // namespace ptlab::simd
