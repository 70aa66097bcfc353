// Material components: one SoA table per BSDF model; MaterialRef = (tag, row).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/core/aligned.h"
#include "engine/core/vec.h"
#include "engine/scene/refs.h"
#include "engine/scene/texture_tables.h"
// matB: coated plastics, thin dielectric, blend, two-sided flags.
#include "engine/scene/blend_table.h"
#include "engine/scene/mask_table.h"  // mask
#include "engine/scene/plastic_table.h"
#include "engine/scene/thin_dielectric_table.h"
#include "engine/scene/two_sided.h"
#include "engine/scene/shading_perturbation.h"  // normal
// principled: Mitsuba's principled and principledthin.
#include "engine/scene/principled_table.h"

namespace ptlab {

/// Lambertian: albedo (Nori default 0.5). `albedo_texture` (a textured parameter, engine/
/// texture/texture_site.h) stays empty until a row's albedo is a texture; then it holds one
/// texture id per row (kNoTexture: the row's constant albedo).
struct DiffuseTable {
  AlignedVector<float> albedo_r, albedo_g, albedo_b;
  AlignedVector<uint32_t> albedo_texture;
  size_t size() const { return albedo_r.size(); }
  bool textured() const { return !albedo_texture.empty(); }
  Color3f Albedo(size_t i) const { return {albedo_r[i], albedo_g[i], albedo_b[i]}; }
};

/// Specular mirror: the reflected sample's weight per RGB channel (1 1 1 for Nori's mirror; a
/// CS184 CGL <mirror> tints it with its reflectance). Mitsuba's smooth `conductor` is a mirror
/// whose weight is also multiplied by the conductor Fresnel term of its complex IOR η + iκ:
/// `eta_*` and `k_*` stay empty until a row has one (η = κ = 0 gives F = 1 exactly).
struct MirrorTable {
  AlignedVector<float> reflectance_r, reflectance_g, reflectance_b;
  AlignedVector<float> eta_r, eta_g, eta_b, k_r, k_g, k_b;
  size_t size() const { return reflectance_r.size(); }
  Color3f Reflectance(size_t i) const {
    return {reflectance_r[i], reflectance_g[i], reflectance_b[i]};
  }
  bool fresnel() const { return !eta_r.empty(); }
  Color3f Eta(size_t i) const { return fresnel() ? Color3f{eta_r[i], eta_g[i], eta_b[i]} : Color3f{}; }
  Color3f K(size_t i) const { return fresnel() ? Color3f{k_r[i], k_g[i], k_b[i]} : Color3f{}; }
};

/// Options of a dielectric row (bit flags; see engine/bsdf/dielectric.h).
enum DielectricFlags : uint8_t {
  kDielectricSchlick = 1u << 0,        // Schlick's Fresnel approximation (CS184 scenes)
  kDielectricScaleRadiance = 1u << 1,  // scale radiance by (η_o/η_i)² on refraction
  kDielectricRefractOnly = 1u << 2,    // always refract, never reflect (CS184 RefractionBSDF)
};

/// Smooth dielectric interface (Nori defaults intIOR 1.5046, extIOR 1.000277). `flags` stays
/// empty until some row has a non-zero DielectricFlags value (then it holds one per row).
/// `reflectance_*` and `transmittance_*` (CS184 GlassBSDF's colors, multiplying the weight of
/// the reflected and the refracted sample) likewise stay empty until a row is tinted.
struct DielectricTable {
  AlignedVector<float> int_ior, ext_ior;
  AlignedVector<uint8_t> flags;
  AlignedVector<float> reflectance_r, reflectance_g, reflectance_b;
  AlignedVector<float> transmittance_r, transmittance_g, transmittance_b;
  size_t size() const { return int_ior.size(); }
  uint8_t Flags(size_t i) const { return i < flags.size() ? flags[i] : uint8_t{0}; }
  bool tinted() const { return !reflectance_r.empty(); }
  Color3f Reflectance(size_t i) const {
    return tinted() ? Color3f{reflectance_r[i], reflectance_g[i], reflectance_b[i]}
                    : Color3f{1, 1, 1};
  }
  Color3f Transmittance(size_t i) const {
    return tinted() ? Color3f{transmittance_r[i], transmittance_g[i], transmittance_b[i]}
                    : Color3f{1, 1, 1};
  }
};

/// Options of a conductor or rough dielectric row in its Mitsuba form (bit flags).
enum MicrofacetFlags : uint8_t {
  kMicrofacetGgx = 1u << 0,            // GGX; else Beckmann
  kMicrofacetSampleVisible = 1u << 1,  // visible-normal sampling
};

/// Rough conductor (Mitsuba `roughconductor`): per-RGB eta and k. Rows added by AddConductor
/// are Nori's form: isotropic Beckmann with Walter's rational G1 and D cos θ sampling
/// (engine/bsdf/conductor.h). The Mitsuba form (engine/bsdf/rough_conductor.h: Beckmann or GGX,
/// alpha = αu and alpha_v, visible normals, specular reflectance) needs the columns
/// `alpha_v`, `flags` (MicrofacetFlags) and `specular_*`, which stay empty until
/// AddRoughConductor adds a row; from then on every row is evaluated in the Mitsuba form
/// (earlier rows get αv = α, Beckmann, D cos θ sampling, specular 1).
struct ConductorTable {
  AlignedVector<float> alpha, eta_r, eta_g, eta_b, k_r, k_g, k_b;
  AlignedVector<float> alpha_v, specular_r, specular_g, specular_b;
  AlignedVector<uint8_t> flags;
  // mask: textured αu (`alpha`) and αv of Mitsuba-form rows, one texture-id column each (docs/
  // materials.md "Textured parameters"); empty while no row's roughness is a texture.
  AlignedVector<uint32_t> alpha_texture, alpha_v_texture;
  size_t size() const { return alpha.size(); }
  bool microfacet() const { return !alpha_v.empty(); }
  bool textured() const { return !alpha_texture.empty(); }
};

/// Mitsuba `roughdielectric` (engine/bsdf/rough_dielectric.h): αu, αv, flags
/// (MicrofacetFlags), IORs, specular reflectance and transmittance.
struct RoughDielectricTable {
  AlignedVector<float> alpha_u, alpha_v, int_ior, ext_ior;
  AlignedVector<uint8_t> flags;
  AlignedVector<float> reflectance_r, reflectance_g, reflectance_b;
  AlignedVector<float> transmittance_r, transmittance_g, transmittance_b;
  /// Textured αu, αv (a TextureTable row or kNoTexture): empty until a row is textured.
  AlignedVector<uint32_t> alpha_texture, alpha_v_texture;
  size_t size() const { return alpha_u.size(); }
  bool textured() const { return !alpha_texture.empty(); }
};

/// Nori `microfacet`: Beckmann rough plastic, kd + ks specular lobe, ks = 1 - max(kd).
struct RoughPlasticTable {
  AlignedVector<float> alpha, int_ior, ext_ior, kd_r, kd_g, kd_b;
  size_t size() const { return alpha.size(); }
};

struct MaterialTables {
  DiffuseTable diffuse;
  MirrorTable mirror;
  DielectricTable dielectric;
  ConductorTable conductor;
  RoughPlasticTable rough_plastic;
  // matB
  PlasticTable plastic;
  ThinDielectricTable thin_dielectric;
  BlendTable blend;
  TwoSidedFlags two_sided;
  RoughDielectricTable rough_dielectric;  // matA
  ShadingPerturbations perturbation;      // normal: normalmap / bumpmap rows
  // principled: one table per tag (the same columns; engine/scene/principled_table.h).
  PrincipledTable principled, principled_thin;
  MaskTable mask;  // mask: Mitsuba's `mask` (engine/bsdf/mask.h)

  MaterialRef AddDiffuse(const Color3f& albedo) {
    diffuse.albedo_r.push_back(albedo.r), diffuse.albedo_g.push_back(albedo.g),
        diffuse.albedo_b.push_back(albedo.b);
    if (diffuse.textured()) diffuse.albedo_texture.push_back(kNoTexture);
    return MaterialRef::Make(MaterialTag::kDiffuse, uint32_t(diffuse.size() - 1));
  }
  /// A diffuse row whose albedo is texture `texture` (a TextureTable row id).
  MaterialRef AddTexturedDiffuse(uint32_t texture) {
    const MaterialRef ref = AddDiffuse({0, 0, 0});
    diffuse.albedo_texture.resize(diffuse.size(), kNoTexture);
    diffuse.albedo_texture.back() = texture;
    return ref;
  }
  MaterialRef AddMirror(const Color3f& reflectance = {1, 1, 1}) {
    mirror.reflectance_r.push_back(reflectance.r), mirror.reflectance_g.push_back(reflectance.g),
        mirror.reflectance_b.push_back(reflectance.b);
    if (mirror.fresnel()) {
      for (auto* c : {&mirror.eta_r, &mirror.eta_g, &mirror.eta_b, &mirror.k_r, &mirror.k_g,
                      &mirror.k_b})
        c->push_back(0.0f);
    }
    return MaterialRef::Make(MaterialTag::kMirror, uint32_t(mirror.size() - 1));
  }
  /// Mitsuba's smooth `conductor`: a mirror row weighted by specular_reflectance × F(η, κ).
  MaterialRef AddSmoothConductor(const Color3f& eta, const Color3f& k,
                                 const Color3f& specular = {1, 1, 1}) {
    auto& t = mirror;
    const MaterialRef ref = AddMirror(specular);
    // The first such row gives every row the columns (η = κ = 0: F = 1 for the earlier ones).
    for (auto* c : {&t.eta_r, &t.eta_g, &t.eta_b, &t.k_r, &t.k_g, &t.k_b})
      c->resize(t.size(), 0.0f);
    const size_t i = ref.index();
    t.eta_r[i] = eta.r, t.eta_g[i] = eta.g, t.eta_b[i] = eta.b;
    t.k_r[i] = k.r, t.k_g[i] = k.g, t.k_b[i] = k.b;
    return ref;
  }
  MaterialRef AddDielectric(float int_ior, float ext_ior, uint8_t flags = 0) {
    auto& t = dielectric;
    if (flags != 0 || !t.flags.empty()) {
      t.flags.resize(t.int_ior.size(), uint8_t{0});
      t.flags.push_back(flags);
    }
    t.int_ior.push_back(int_ior), t.ext_ior.push_back(ext_ior);
    if (t.tinted()) {
      for (auto* c : {&t.reflectance_r, &t.reflectance_g, &t.reflectance_b, &t.transmittance_r,
                      &t.transmittance_g, &t.transmittance_b})
        c->push_back(1.0f);
    }
    return MaterialRef::Make(MaterialTag::kDielectric, uint32_t(t.size() - 1));
  }
  /// A dielectric whose reflected and refracted samples are tinted (CS184 glass colors).
  MaterialRef AddTintedDielectric(float int_ior, float ext_ior, uint8_t flags,
                                  const Color3f& reflectance, const Color3f& transmittance) {
    auto& t = dielectric;
    const MaterialRef ref = AddDielectric(int_ior, ext_ior, flags);
    for (auto* c : {&t.reflectance_r, &t.reflectance_g, &t.reflectance_b, &t.transmittance_r,
                    &t.transmittance_g, &t.transmittance_b})
      c->resize(t.int_ior.size(), 1.0f);
    const size_t i = ref.index();
    t.reflectance_r[i] = reflectance.r, t.reflectance_g[i] = reflectance.g,
    t.reflectance_b[i] = reflectance.b;
    t.transmittance_r[i] = transmittance.r, t.transmittance_g[i] = transmittance.g,
    t.transmittance_b[i] = transmittance.b;
    return ref;
  }
  /// Beckmann rough conductor; eta/k per RGB channel (see engine/bsdf/conductor_presets.h).
  MaterialRef AddConductor(float alpha, const Color3f& eta, const Color3f& k) {
    auto& t = conductor;
    t.alpha.push_back(alpha);
    t.eta_r.push_back(eta.r), t.eta_g.push_back(eta.g), t.eta_b.push_back(eta.b);
    t.k_r.push_back(k.r), t.k_g.push_back(k.g), t.k_b.push_back(k.b);
    if (t.microfacet()) {
      t.alpha_v.push_back(alpha), t.flags.push_back(uint8_t{0});
      t.specular_r.push_back(1.0f), t.specular_g.push_back(1.0f), t.specular_b.push_back(1.0f);
    }
    if (t.textured())  // mask
      t.alpha_texture.push_back(kNoTexture), t.alpha_v_texture.push_back(kNoTexture);
    return MaterialRef::Make(MaterialTag::kConductor, uint32_t(t.size() - 1));
  }
  /// Mitsuba's roughconductor (switches the table to its Mitsuba form, see ConductorTable).
  MaterialRef AddRoughConductor(float alpha_u, float alpha_v, uint8_t microfacet_flags,
                                const Color3f& eta, const Color3f& k, const Color3f& specular) {
    auto& t = conductor;
    const bool first = !t.microfacet();
    const MaterialRef ref = AddConductor(alpha_u, eta, k);
    if (first) {  // earlier rows: αv = α, Beckmann, D cos θ sampling, specular 1
      t.alpha_v.assign(t.alpha.begin(), t.alpha.end());
      t.flags.assign(t.size(), uint8_t{0});
      for (auto* c : {&t.specular_r, &t.specular_g, &t.specular_b}) c->assign(t.size(), 1.0f);
    }
    const size_t i = ref.index();
    t.alpha_v[i] = alpha_v, t.flags[i] = microfacet_flags;
    t.specular_r[i] = specular.r, t.specular_g[i] = specular.g, t.specular_b[i] = specular.b;
    return ref;
  }
  /// mask: a Mitsuba roughconductor whose αu and / or αv are textures (kNoTexture: the
  /// constant alpha_u / alpha_v).
  MaterialRef AddTexturedRoughConductor(float alpha_u, float alpha_v, uint32_t alpha_u_texture,
                                        uint32_t alpha_v_texture, uint8_t microfacet_flags,
                                        const Color3f& eta, const Color3f& k,
                                        const Color3f& specular) {
    auto& t = conductor;
    const MaterialRef ref = AddRoughConductor(alpha_u, alpha_v, microfacet_flags, eta, k, specular);
    t.alpha_texture.resize(t.size(), kNoTexture), t.alpha_v_texture.resize(t.size(), kNoTexture);
    t.alpha_texture[ref.index()] = alpha_u_texture, t.alpha_v_texture[ref.index()] = alpha_v_texture;
    return ref;
  }
  /// Mitsuba's roughdielectric.
  MaterialRef AddRoughDielectric(float alpha_u, float alpha_v, uint8_t microfacet_flags,
                                 float int_ior, float ext_ior, const Color3f& reflectance = {1, 1, 1},
                                 const Color3f& transmittance = {1, 1, 1}) {
    auto& t = rough_dielectric;
    t.alpha_u.push_back(alpha_u), t.alpha_v.push_back(alpha_v), t.flags.push_back(microfacet_flags);
    t.int_ior.push_back(int_ior), t.ext_ior.push_back(ext_ior);
    t.reflectance_r.push_back(reflectance.r), t.reflectance_g.push_back(reflectance.g),
        t.reflectance_b.push_back(reflectance.b);
    t.transmittance_r.push_back(transmittance.r), t.transmittance_g.push_back(transmittance.g),
        t.transmittance_b.push_back(transmittance.b);
    if (t.textured()) t.alpha_texture.push_back(kNoTexture), t.alpha_v_texture.push_back(kNoTexture);
    return MaterialRef::Make(MaterialTag::kRoughDielectric, uint32_t(t.size() - 1));
  }
  /// A Mitsuba roughdielectric whose αu and / or αv are textures (kNoTexture: the constant).
  MaterialRef AddTexturedRoughDielectric(float alpha_u, float alpha_v, uint32_t alpha_u_texture,
                                         uint32_t alpha_v_texture, uint8_t microfacet_flags,
                                         float int_ior, float ext_ior, const Color3f& reflectance,
                                         const Color3f& transmittance) {
    auto& t = rough_dielectric;
    const MaterialRef ref = AddRoughDielectric(alpha_u, alpha_v, microfacet_flags, int_ior,
                                               ext_ior, reflectance, transmittance);
    t.alpha_texture.resize(t.size(), kNoTexture), t.alpha_v_texture.resize(t.size(), kNoTexture);
    t.alpha_texture[ref.index()] = alpha_u_texture, t.alpha_v_texture[ref.index()] = alpha_v_texture;
    return ref;
  }
  MaterialRef AddRoughPlastic(float alpha, float int_ior, float ext_ior, const Color3f& kd) {
    auto& t = rough_plastic;
    t.alpha.push_back(alpha), t.int_ior.push_back(int_ior), t.ext_ior.push_back(ext_ior);
    t.kd_r.push_back(kd.r), t.kd_g.push_back(kd.g), t.kd_b.push_back(kd.b);
    return MaterialRef::Make(MaterialTag::kRoughPlastic, uint32_t(t.size() - 1));
  }
  // matB: rows of the coated plastics, the thin dielectric and the blend (see their tables).
  MaterialRef AddPlastic(const PlasticRow& row) {
    return MaterialRef::Make(MaterialTag::kPlastic, plastic.Add(row));
  }
  MaterialRef AddThinDielectric(float eta, const Color3f& reflectance = {1, 1, 1},
                                const Color3f& transmittance = {1, 1, 1}) {
    return MaterialRef::Make(MaterialTag::kThinDielectric,
                             thin_dielectric.Add(eta, reflectance, transmittance));
  }
  MaterialRef AddBlend(float weight, MaterialRef first, MaterialRef second,
                       uint32_t weight_texture = kNoTexture) {  // mask: a textured weight
    return MaterialRef::Make(MaterialTag::kBlend,
                             blend.Add(weight, first, second, weight_texture));
  }
  // mask: a `mask` row over `nested`: a constant opacity, or texture `opacity_texture`.
  MaterialRef AddMask(float opacity, MaterialRef nested, uint32_t opacity_texture = kNoTexture) {
    return MaterialRef::Make(MaterialTag::kMask, mask.Add(opacity, nested, opacity_texture));
  }
  // principled: a `principled` row (thin = false) or a `principledthin` row.
  MaterialRef AddPrincipled(const PrincipledRow& row, bool thin = false) {
    return thin ? MaterialRef::Make(MaterialTag::kPrincipledThin, principled_thin.Add(row))
                : MaterialRef::Make(MaterialTag::kPrincipled, principled.Add(row));
  }
};

}  // namespace ptlab
