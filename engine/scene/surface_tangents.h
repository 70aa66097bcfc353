// normal: the uv tangents ∂p/∂u, ∂p/∂v of every triangle, which normal and bump maps read.
#pragma once

#include "engine/core/vec.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// ∂p/∂u and ∂p/∂v of the triangle (p0, p1, p2) with surface coordinates (uv0, uv1, uv2), as
/// Mitsuba 3's mesh computes them: with duv1 = uv1 − uv0, duv2 = uv2 − uv0 and
/// det = duv1.u duv2.v − duv1.v duv2.u, ∂p/∂u = (duv2.v (p1 − p0) − duv1.v (p2 − p0)) / det and
/// ∂p/∂v = (duv1.u (p2 − p0) − duv2.u (p1 − p0)) / det. Where det = 0 (a uv triangle of zero
/// area, e.g. at a sphere's pole) or a tangent is not finite, Mitsuba's fallback: the Duff et
/// al. basis around the unit geometric normal `ng` (s, t of Frame(ng)). Always finite.
void TriangleTangents(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, const Vec2f& uv0,
                      const Vec2f& uv1, const Vec2f& uv2, const Vec3f& ng, Vec3f* dp_du,
                      Vec3f* dp_dv);

/// Fills scene->materials.perturbation's tangent columns, one row per scene triangle (a mesh
/// without uvs has the barycentric parametrization, uv = (b1, b2): ∂p/∂u = p1 − p0, ∂p/∂v =
/// p2 − p0), when some material row is perturbed; nothing otherwise.
void BuildSurfaceTangents(Scene* scene);

}  // namespace ptlab
