// Heap bytes of the scene's component tables, column by column.
#include "engine/scene/scene_bytes.h"

#include <vector>

#include "engine/core/memory.h"

namespace ptlab {
namespace {

// Every table is a set of vectors; a column added to a table must be counted below, which these
// sizes remind whoever adds one of.
constexpr size_t kColumn = sizeof(std::vector<float>);
static_assert(sizeof(TriangleTable) == 9 * kColumn);
static_assert(sizeof(SphereTable) == 6 * kColumn);
static_assert(sizeof(TriangleShadingTable) == 5 * kColumn);
static_assert(sizeof(VertexTable) == 5 * kColumn);
static_assert(sizeof(MeshTable) == 7 * kColumn);
static_assert(sizeof(MaterialTables) ==
              (4 + 3 + 9 + 7 + 6 + /* matA */ 6 + 5 + 13 + /* matB */ 11 + 7 + 3 +
               kMaterialTagCount + /* normal */ 9 + kMaterialTagCount +
               /* principled */ 2 * (3 + 1 + 2 * kPrincipledParamCount) + /* mask */ 3 + 1 + 2) *
              kColumn);
static_assert(sizeof(TextureTable) == 13 * kColumn);
static_assert(sizeof(AreaLightTable) == 8 * kColumn);
static_assert(sizeof(EnvironmentMapTable) == 14 * kColumn);
static_assert(sizeof(DistantDiskTable) == 4 * kColumn);
static_assert(sizeof(PointLightTable) == 2 * kColumn);
static_assert(sizeof(DirectionalLightTable) == 2 * kColumn);
static_assert(sizeof(SpotLightTable) == 10 * kColumn);
static_assert(sizeof(ProjectorTable) == 7 * kColumn);
static_assert(sizeof(EmitterSelectionTable) == 11 * kColumn);
static_assert(sizeof(InstanceTable) == 5 * kColumn);  // counted with the meshes

size_t TableBytes(const TriangleShadingTable& t) {
  return VectorsBytes(t.mesh, t.material, t.vertex0, t.vertex1, t.vertex2);
}

size_t TableBytes(const VertexTable& t) { return VectorsBytes(t.n_x, t.n_y, t.n_z, t.u, t.v); }

size_t TableBytes(const MeshTable& t) {
  return VectorsBytes(t.first_triangle, t.triangle_count, t.material, t.emitter, t.has_normals,
                      t.has_uvs) +
         StringsBytes(t.name);
}

// matB: the coated plastics, the thin dielectric, the blend and the two-sided flags.
size_t MatBTablesBytes(const MaterialTables& m) {
  const PlasticTable& p = m.plastic;
  const ThinDielectricTable& t = m.thin_dielectric;
  size_t bytes = VectorsBytes(p.distribution, p.alpha, p.eta, p.base_r, p.base_g, p.base_b,
                              p.specular_r, p.specular_g, p.specular_b,
                              p.specular_sampling_weight, p.transmittance) +
                 VectorsBytes(t.eta, t.reflectance_r, t.reflectance_g, t.reflectance_b,
                              t.transmittance_r, t.transmittance_g, t.transmittance_b) +
                 VectorsBytes(m.blend.weight, m.blend.first, m.blend.second);
  for (const auto& c : m.two_sided.by_tag) bytes += VectorBytes(c);
  return bytes;
}

// normal: the normal / bump map rows and the triangles' uv tangents.
size_t PerturbationBytes(const ShadingPerturbations& p) {
  size_t bytes = VectorsBytes(p.kind, p.texture, p.scale, p.dp_du_x, p.dp_du_y, p.dp_du_z,
                              p.dp_dv_x, p.dp_dv_y, p.dp_dv_z);
  for (const auto& c : p.by_tag) bytes += VectorBytes(c);
  return bytes;
}

// principled: the principled and principledthin tables.
size_t PrincipledTablesBytes(const MaterialTables& m) {
  size_t bytes = 0;
  for (const PrincipledTable* t : {&m.principled, &m.principled_thin}) {
    bytes += VectorsBytes(t->base_r, t->base_g, t->base_b, t->base_color_texture);
    for (int p = 0; p < kPrincipledParamCount; ++p)
      bytes += VectorBytes(t->value[p]) + VectorBytes(t->texture[p]);
  }
  return bytes;
}

// matA: the smooth conductor's and rough conductor's optional columns, the rough dielectric.
size_t MatABytes(const MaterialTables& m) {
  const MirrorTable& mi = m.mirror;
  const ConductorTable& c = m.conductor;
  const RoughDielectricTable& rd = m.rough_dielectric;
  return VectorsBytes(mi.eta_r, mi.eta_g, mi.eta_b, mi.k_r, mi.k_g, mi.k_b) +
         VectorsBytes(c.alpha_v, c.specular_r, c.specular_g, c.specular_b, c.flags) +
         VectorsBytes(rd.alpha_u, rd.alpha_v, rd.int_ior, rd.ext_ior, rd.flags, rd.reflectance_r,
                      rd.reflectance_g, rd.reflectance_b, rd.transmittance_r, rd.transmittance_g,
                      rd.transmittance_b, rd.alpha_texture, rd.alpha_v_texture);
}

// mask: the mask table and the textured-parameter columns of the blend and the conductor.
size_t MaskBytes(const MaterialTables& m) {
  return VectorsBytes(m.mask.opacity, m.mask.opacity_texture, m.mask.nested,
                      m.blend.weight_texture, m.conductor.alpha_texture,
                      m.conductor.alpha_v_texture);
}

size_t TableBytes(const MaterialTables& m) {
  const DielectricTable& d = m.dielectric;
  return VectorsBytes(m.diffuse.albedo_r, m.diffuse.albedo_g, m.diffuse.albedo_b,
                      m.diffuse.albedo_texture) +
         VectorsBytes(m.mirror.reflectance_r, m.mirror.reflectance_g, m.mirror.reflectance_b) +
         VectorsBytes(d.int_ior, d.ext_ior, d.flags, d.reflectance_r, d.reflectance_g,
                      d.reflectance_b, d.transmittance_r, d.transmittance_g, d.transmittance_b) +
         VectorsBytes(m.conductor.alpha, m.conductor.eta_r, m.conductor.eta_g, m.conductor.eta_b,
                      m.conductor.k_r, m.conductor.k_g, m.conductor.k_b) +
         VectorsBytes(m.rough_plastic.alpha, m.rough_plastic.int_ior, m.rough_plastic.ext_ior,
                      m.rough_plastic.kd_r, m.rough_plastic.kd_g, m.rough_plastic.kd_b) +
         MatBTablesBytes(m) + MatABytes(m) + PrincipledTablesBytes(m) + MaskBytes(m) +
         PerturbationBytes(m.perturbation);  // normal
}

size_t EmitterTablesBytes(const Scene& s) {
  const AreaLightTable& a = s.area_lights;
  const EnvironmentMapTable& e = s.environment_maps;
  const EmitterSelectionTable& sel = s.emitter_selection;
  return VectorsBytes(a.radiance, a.mesh, a.area, a.cdf_offset, a.triangle_cdf, a.guide_offset,
                      a.triangle_guide, a.texture) +
         VectorsBytes(e.width, e.height, e.pixel_offset, e.marginal_offset, e.conditional_offset,
                      e.sampling, e.rows, e.to_world, e.luminance_integral, e.texels, e.marginal_cdf,
                      e.conditional_cdf, e.marginal_guide, e.conditional_guide) +
         VectorsBytes(s.distant_disks.radiance, s.distant_disks.max_chord2,
                      s.distant_disks.solid_angle, s.distant_disks.to_world) +
         VectorsBytes(s.point_lights.position, s.point_lights.power) +
         VectorsBytes(s.directional_lights.direction, s.directional_lights.radiance) +
         VectorsBytes(s.spot_lights.position, s.spot_lights.axis, s.spot_lights.intensity,
                      s.spot_lights.cos_half_angle, s.spot_lights.exponent) +
         VectorsBytes(s.spot_lights.cos_beam, s.spot_lights.cutoff, s.spot_lights.inv_transition,
                      s.spot_lights.texture, s.spot_lights.texture_frame) +
         VectorsBytes(s.emitters, sel.power, sel.pmf, sel.cdf, sel.guide, sel.slot_area,
                      sel.slot_environment, sel.slot_disk, sel.slot_point, sel.slot_directional,
                      sel.slot_spot, sel.slot_projector) +
         VectorsBytes(s.projectors.position, s.projectors.to_world, s.projectors.tan_half_x,
                      s.projectors.tan_half_y, s.projectors.scale, s.projectors.irradiance,
                      s.projectors.texture);
}

}  // namespace

size_t TableBytes(const SdfGridTable& t) {
  static_assert(sizeof(SdfGridTable) == 8 * kColumn);
  return VectorsBytes(t.nx, t.ny, t.nz, t.offset, t.to_world, t.material, t.normals, t.values);
}

size_t TableBytes(const TriangleTable& t) {
  return VectorsBytes(t.v0_x, t.v0_y, t.v0_z, t.v1_x, t.v1_y, t.v1_z, t.v2_x, t.v2_y, t.v2_z);
}

size_t TableBytes(const SphereTable& t) {
  return VectorsBytes(t.center_x, t.center_y, t.center_z, t.radius, t.material, t.uv_frame);
}

SceneBytes SceneTableBytes(const Scene& scene) {
  SceneBytes b;
  b.triangles = TableBytes(scene.triangles);
  b.spheres = TableBytes(scene.spheres) + TableBytes(scene.sdf_grids);
  b.shading = TableBytes(scene.shading);
  b.vertices = TableBytes(scene.vertices);
  // Textures count with the materials they drive.
  const TextureTable& t = scene.textures;
  b.materials = TableBytes(scene.materials) +
                VectorsBytes(t.kind, t.filter, t.wrap, t.m00, t.m01, t.m02, t.m10, t.m11, t.m12,
                             t.width, t.height, t.offset, t.data);
  b.emitters = EmitterTablesBytes(scene);
  b.meshes = TableBytes(scene.meshes);
  const InstanceTable& in = scene.instances;
  b.meshes += VectorsBytes(in.group_first_row, in.group_row_count, in.group, in.to_world,
                           in.first_prim);
  return b;
}

}  // namespace ptlab
