// Distant disk emitter (Nori ETH `distantdisk`): constant radiance in a cone of directions.
#pragma once

#include <cstdint>
#include <string>

#include "engine/core/frame.h"
#include "engine/core/status.h"
#include "engine/core/vec.h"
#include "engine/light/environment_sample.h"
#include "engine/scene/emitter_tables.h"

namespace ptlab {

/// Appends a distant disk: radiance L (components finite, >= 0) for every world direction ω
/// with angle(ω, to_world.n) <= theta_a_deg, 0 elsewhere. to_world is a rotation; its n axis is
/// the cone axis (the local +z of Nori's toWorld). theta_a_deg ∈ (0, 180]; 180 = a constant
/// environment. Errors (naming `name`) for values out of range; nothing is appended then.
StatusOr<uint32_t> AddDistantDisk(const Color3f& radiance, float theta_a_deg, const Frame& to_world,
                                  const std::string& name, DistantDiskTable* table);

/// Radiance arriving from world direction w (unit, pointing away from the scene).
Color3f DistantDiskRadiance(const DistantDiskTable& table, uint32_t row, const Vec3f& w_world);

/// Samples a direction uniformly over the cone's solid angle (pdf 1/(2π(1 - cos thetaA))).
/// Returns false (out untouched) when the radiance is black.
bool SampleDistantDisk(const DistantDiskTable& table, uint32_t row, const Vec2f& u,
                       EnvironmentSample* out);

/// Solid-angle density of SampleDistantDisk at world direction w (unit): 1/(2π(1 - cos thetaA))
/// inside the cone, 0 outside and for a black disk.
float DistantDiskPdf(const DistantDiskTable& table, uint32_t row, const Vec3f& w_world);

}  // namespace ptlab
