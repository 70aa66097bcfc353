// Mitsuba scenes: entry points, the scene element, sampler, integrator.
#include "engine/io/mitsuba_loader.h"

#include <cmath>
#include <filesystem>

#include "engine/io/mitsuba_document.h"
#include "engine/io/mitsuba_scene_builder.h"
#include "engine/io/mitsuba_spectrum.h"
#include "engine/io/text_parsing.h"
#include "engine/io/xml_properties.h"
#include "engine/scene/scene_limits.h"
#include "engine/scene/surface_tangents.h"  // normal

namespace ptlab {
namespace internal {

StatusOr<std::string> MitsubaSceneBuilder::Resolve(const MitsubaObject& obj, const char* property,
                                                   const std::string& filename) const {
  const std::string path = ResolveMitsubaPath(doc_.search_paths, filename);
  if (path.empty()) {
    std::string where;
    for (const std::string& dir : doc_.search_paths) where += (where.empty() ? "" : ", ") + dir;
    return obj.Error(property, "file '" + filename + "' of " + DescribeMitsuba(obj.node()) +
                                   " not found; looked in " + where);
  }
  return path;
}

Status MitsubaSceneBuilder::Build() {
  const std::string& v = doc_.version;
  int major = 0;
  const size_t dot = v.find('.');
  if (!ParseInt(std::string_view(v).substr(0, dot), &major) || major < 0)
    return doc_.root.Error("malformed scene version '" + v + "'; expected e.g. 3.0.0 or 0.6.0");
  if (major > 3) return doc_.root.Error("scene version '" + v + "' is newer than 3.x");
  legacy_ = major < 2;
  PTLAB_RETURN_IF_ERROR(CollectMitsubaIds(doc_.root, &ids_));
  StatusOr<MitsubaObject> root = Read(doc_.root);
  if (!root.ok()) return root.status();
  PTLAB_RETURN_IF_ERROR(root->Expect({}));
  for (const MitsubaNode* child : root->children()) PTLAB_RETURN_IF_ERROR(SceneChild(*child));
  if (!have_sensor_) return doc_.root.Error("no <sensor> in the scene; expected one");
  // Mitsuba 3's direct integrator weights each sample of a delta emitter (point, directional,
  // spot, projector) by 1 instead of 1 / emitter_samples, so its images count those lights
  // emitter_samples times; ptlab's direct_mis does not, and would not match them.
  if (multi_sample_direct_ && scene_.point_lights.size() + scene_.directional_lights.size() +
                                      scene_.spot_lights.size() + scene_.projectors.size() >
                                  0)
    return Unsupported(*multi_sample_direct_,
                       "emitter_samples > 1 with point, directional, spot or projector "
                       "emitters: Mitsuba 3 counts each such sample with weight 1, not 1 / "
                       "emitter_samples");
  // hide_emitters and area emitters: Mitsuba 3 up to 3.5 draws a directly seen area emitter
  // black (its emission dropped, its surface shaded), Mitsuba 3.6 lets camera rays pass
  // through it; ptlab does neither until one is chosen.
  if (hide_emitters_ && scene_.area_lights.size() > 0)
    return Unsupported(*hide_emitters_,
                       "hide_emitters = true with area emitters (Mitsuba's versions differ: a "
                       "black emitter, or one that camera rays pass through)");
  if (!have_integrator_) {  // Mitsuba's default: path, unbounded depth
    scene_.integrator = IntegratorDesc{};
    scene_.integrator.type = IntegratorDesc::Type::kPathMis;
    scene_.integrator.max_depth = -1;
    scene_.integrator.power_heuristic = true;
    scene_.integrator.light_selection = LightSelection::kUniform;
  }
  return Status::Ok();
}

Status MitsubaSceneBuilder::SceneChild(const MitsubaNode& node) {
  const std::string& tag = node.tag;
  if (tag == "shape") return SceneShape(node);  // mitsuba_instances.cpp
  if (tag == "emitter") return SceneEmitter(node);
  if (tag == "bsdf") {
    StatusOr<MaterialRef> m = Bsdf(node);  // declared for <ref>s; built once, checked now
    return m.ok() ? Status::Ok() : m.status();
  }
  if (tag == "sensor") {
    if (have_sensor_) return Unsupported(node, "a second sensor; ptlab renders one");
    have_sensor_ = true;
    return Sensor(node);
  }
  if (tag == "integrator") {
    if (have_integrator_) return node.Error("a second <integrator>; expected at most one");
    have_integrator_ = true;
    return Integrator(node);
  }
  // A top-level texture is read where a material refers to it (<ref id>).
  if (tag == "texture") return Status::Ok();
  if (tag == "medium" || tag == "phase" || tag == "volume") return Unsupported(node);
  return node.Error("<" + tag +
                    "> is not allowed directly inside <scene>; expected shape, "
                    "emitter, bsdf, texture, sensor or integrator");
}

Status MitsubaSceneBuilder::Sampler(const MitsubaNode& node) {
  StatusOr<MitsubaObject> obj = Read(node);
  if (!obj.ok()) return obj.status();
  const std::string& type = obj->type();
  if (type == "independent") {
    scene_.sampler.type = SamplerType::kIndependent;
  } else if (type == "stratified" || type == "multijitter" || type == "orthogonal" ||
             type == "ldsampler") {
    // Stratified and low-discrepancy samplers: ptlab's best one (Owen-scrambled Sobol').
    scene_.sampler.type = SamplerType::kSobol;
  } else {
    return node.Error("unknown sampler type '" + type +
                      "'; expected independent, stratified, "
                      "multijitter, orthogonal or ldsampler");
  }
  PTLAB_RETURN_IF_ERROR(obj->Expect({"sample_count", "seed", "jitter", "strength", "dimension"}));
  int count = 4, seed = 0, dimension = 0;  // 0.6's `dimension`: ignored
  PTLAB_RETURN_IF_ERROR(obj->Integer("dimension", &dimension));
  bool jitter = true;
  float strength = 0;
  PTLAB_RETURN_IF_ERROR(obj->Integer("sample_count", &count));
  PTLAB_RETURN_IF_ERROR(obj->Integer("seed", &seed));  // ptlab's --seed sets the streams
  PTLAB_RETURN_IF_ERROR(obj->Boolean("jitter", &jitter));
  PTLAB_RETURN_IF_ERROR(obj->Float("strength", &strength));
  if (count < 1 || count > kMaxSampleCount)
    return obj->Error("sample_count", "sample_count " + std::to_string(count) +
                                          " is out of range; expected 1.." +
                                          std::to_string(kMaxSampleCount) + " (as -s)");
  scene_.sampler.sample_count = uint32_t(count);
  return Status::Ok();
}

Status MitsubaSceneBuilder::Integrator(const MitsubaNode& node) {
  StatusOr<MitsubaObject> obj = Read(node);
  if (!obj.ok()) return obj.status();
  const std::string& type = obj->type();
  IntegratorDesc desc;
  desc.power_heuristic = true;                      // Mitsuba's MIS weights
  desc.light_selection = LightSelection::kUniform;  // Mitsuba picks emitters uniformly
  desc.triangle_sampling = TriangleSampling::kArea;
  if (type == "moment") {  // a wrapper that adds second moments: render what it wraps
    PTLAB_RETURN_IF_ERROR(obj->Expect({}));
    if (obj->children().size() != 1 || obj->children()[0]->tag != "integrator")
      return node.Error("<integrator type=\"moment\"> must hold exactly one <integrator>");
    return Integrator(*obj->children()[0]);
  }
  if (!obj->children().empty())
    return obj->children()[0]->Error("<" + obj->children()[0]->tag + "> is not allowed inside " +
                                     DescribeMitsuba(node));
  bool hide = false;
  if (type == "path") {
    PTLAB_RETURN_IF_ERROR(
        obj->Expect({"max_depth", "rr_depth", "hide_emitters", "strict_normals"}));
    PTLAB_RETURN_IF_ERROR(obj->OnlyDefault("strict_normals", false));
    int max_depth = -1, rr_depth = 5;
    PTLAB_RETURN_IF_ERROR(obj->Integer("max_depth", &max_depth));
    PTLAB_RETURN_IF_ERROR(obj->Integer("rr_depth", &rr_depth));
    if (max_depth < -1) return obj->Error("max_depth", "max_depth must be >= 0, or -1 (unbounded)");
    if (max_depth == 0)
      return obj->Error("max_depth",
                        "unsupported: integrator \"path\" with max_depth 0 (an "
                        "all-black image)");
    if (rr_depth < 1) return obj->Error("rr_depth", "rr_depth must be >= 1");
    // Mitsuba counts vertices (1 = emitters seen directly, 2 = direct light); ptlab counts
    // bounces as CS184 (0 = emitted only, 1 = direct).
    desc.type = IntegratorDesc::Type::kPathMis;
    desc.max_depth = max_depth < 0 ? -1 : max_depth - 1;
    PTLAB_RETURN_IF_ERROR(obj->Boolean("hide_emitters", &hide));
    if (obj->Has("rr_depth"))
      scene_.load_warnings.push_back(obj->node().where +
                                     ": rr_depth is accepted but ptlab applies its own Russian "
                                     "roulette (from depth 3); the expected image is the same");
  } else if (type == "direct") {
    PTLAB_RETURN_IF_ERROR(obj->Expect(
        {"shading_samples", "emitter_samples", "bsdf_samples", "hide_emitters", "strict_normals"}));
    PTLAB_RETURN_IF_ERROR(obj->OnlyDefault("strict_normals", false));
    int shading = 1;
    PTLAB_RETURN_IF_ERROR(obj->Integer("shading_samples", &shading));
    int emitter = shading, bsdf = shading;
    PTLAB_RETURN_IF_ERROR(obj->Integer("emitter_samples", &emitter));
    PTLAB_RETURN_IF_ERROR(obj->Integer("bsdf_samples", &bsdf));
    if (emitter < 1) return obj->Error("emitter_samples", "emitter_samples must be >= 1");
    if (bsdf != 1)
      return obj->Error(obj->Has("bsdf_samples") ? "bsdf_samples" : "shading_samples",
                        "unsupported: integrator \"direct\" with bsdf_samples != 1 (ptlab's "
                        "direct_mis takes one BSDF sample)");
    desc.type = IntegratorDesc::Type::kDirectMis;
    desc.light_samples = emitter;
    if (emitter > 1) multi_sample_direct_ = &node;
    PTLAB_RETURN_IF_ERROR(obj->Boolean("hide_emitters", &hide));
  } else if (type == "ptracer") {
    // Mitsuba 3's particle tracer: ptlab's ptracer (docs/bdpt.md). max_depth counts as for
    // path; samples_per_pass only batches Mitsuba's work (the image's expectation is the same).
    PTLAB_RETURN_IF_ERROR(
        obj->Expect({"max_depth", "rr_depth", "hide_emitters", "samples_per_pass"}));
    int max_depth = -1, rr_depth = 5, per_pass = -1;
    PTLAB_RETURN_IF_ERROR(obj->Integer("max_depth", &max_depth));
    PTLAB_RETURN_IF_ERROR(obj->Integer("rr_depth", &rr_depth));
    PTLAB_RETURN_IF_ERROR(obj->Integer("samples_per_pass", &per_pass));
    if (max_depth < -1) return obj->Error("max_depth", "max_depth must be >= 0, or -1 (unbounded)");
    if (max_depth == 0)
      return obj->Error("max_depth",
                        "unsupported: integrator \"ptracer\" with max_depth 0 (an "
                        "all-black image)");
    if (rr_depth < 1) return obj->Error("rr_depth", "rr_depth must be >= 1");
    if (per_pass == 0 || per_pass < -1)
      return obj->Error("samples_per_pass", "samples_per_pass must be >= 1, or -1 (automatic)");
    desc.type = IntegratorDesc::Type::kPtracer;
    desc.max_depth = max_depth < 0 ? -1 : max_depth - 1;
    PTLAB_RETURN_IF_ERROR(obj->OnlyDefault("hide_emitters", false));
    if (obj->Has("rr_depth"))
      scene_.load_warnings.push_back(obj->node().where +
                                     ": rr_depth is accepted but ptlab applies its own Russian "
                                     "roulette (from the fourth vertex); the expected image is "
                                     "the same");
  } else {
    return Unsupported(node);
  }
  desc.hide_emitters = hide;
  if (hide) hide_emitters_ = &node;
  scene_.integrator = desc;
  return Status::Ok();
}

}  // namespace internal

StatusOr<Scene> LoadMitsubaSceneFromString(const std::string& xml, const std::string& base_dir,
                                           const std::string& display_name,
                                           const LoadOptions& options) {
  StatusOr<internal::MitsubaDocument> doc =
      internal::ReadMitsubaDocument(xml, base_dir, display_name, options);
  if (!doc.ok()) return doc.status();
  internal::MitsubaSceneBuilder builder(&*doc, options);
  PTLAB_RETURN_IF_ERROR(builder.Build());
  Scene scene = builder.TakeScene();
  scene.source_path = display_name;
  scene.input_files.insert(scene.input_files.begin(), doc->files.begin(), doc->files.end());
  FinalizeAreaLights(&scene);
  BuildSurfaceTangents(&scene);  // normal: only with normal / bump maps
  return scene;
}

StatusOr<Scene> LoadMitsubaScene(const std::string& path, const LoadOptions& options) {
  std::string xml;
  PTLAB_RETURN_IF_ERROR(ReadTextFile(path, "scene file", &xml));
  StatusOr<Scene> scene = LoadMitsubaSceneFromString(
      xml, std::filesystem::path(path).parent_path().string(), path, options);
  if (scene.ok()) scene->input_files.insert(scene->input_files.begin(), path);
  return scene;
}

Status LookupMitsubaConductor(const std::vector<std::string>& search_paths, const std::string& name,
                              Color3f* eta, Color3f* k) {
  if (name == "none") {
    *eta = {0, 0, 0};
    *k = {1, 1, 1};
    return Status::Ok();
  }
  if (name.empty() || name.find('/') != std::string::npos || name.find('\\') != std::string::npos)
    return Status::Error("unknown conductor '" + name + "'");
  std::vector<std::string> dirs = search_paths;
  for (const std::string& dir : search_paths)
    dirs.push_back(std::filesystem::path(dir).parent_path().string());
  const std::string eta_path = internal::ResolveMitsubaPath(dirs, "ior/" + name + ".eta.spd");
  const std::string k_path = internal::ResolveMitsubaPath(dirs, "ior/" + name + ".k.spd");
  if (eta_path.empty() || k_path.empty())
    return Status::Error("unknown conductor '" + name + "': no ior/" + name +
                         ".eta.spd and .k.spd in the search paths or their parent folders");
  std::vector<double> w, v;
  PTLAB_RETURN_IF_ERROR(ReadSpdFile(eta_path, &w, &v));
  *eta = SpectrumToRgb(w, v, SpectrumUse::kUnbounded);
  PTLAB_RETURN_IF_ERROR(ReadSpdFile(k_path, &w, &v));
  *k = SpectrumToRgb(w, v, SpectrumUse::kUnbounded);
  return Status::Ok();
}

}  // namespace ptlab
