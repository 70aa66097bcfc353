// Variants of a scene for `ptlab converge`: one table row per key.
#include "tools/converge/variant.h"

#include <cfloat>
#include <cmath>
#include <cstring>

#include "engine/core/parse_number.h"

namespace ptlab {
namespace {

using Type = IntegratorDesc::Type;

// An integer in [lo, hi] through the shared checked parser (engine/core/parse_number.h).
bool ParseIntIn(const std::string& s, int lo, int hi, int* out) {
  return ParseNumberQuietly<int>(s, lo, hi, out) == NumberError::kOk;
}

// One overridable key: its name, what it accepts (for messages) and how it applies.
struct VariantKey {
  const char* name;
  const char* expected;
  // Checks the value; with a target, applies it too.
  Status (*apply)(const std::string& value, VariantTarget* target);
};

Status Expected(const char* key, const char* expected, const std::string& value) {
  return Status::Error("variant key '" + std::string(key) + "': '" + value + "' is not " +
                       expected);
}

constexpr VariantKey kKeys[] = {
    {"integrator", "one of normals, direct_ems, direct_mats, direct_mis, whitted, path_mats, "
                   "path_ems, path_mis, bdpt, ptracer",
     [](const std::string& v, VariantTarget* t) {
       Type type;
       if (!IntegratorTypeFromName(v, &type)) return Status::Error("");
       if (t) t->scene->integrator.type = type;
       // bdpt's default heuristic is the power heuristic (a later heuristic= key overrides).
       if (t && type == Type::kBdpt) t->scene->integrator.power_heuristic = true;
       return Status::Ok();
     }},
    {"heuristic", "balance or power",
     [](const std::string& v, VariantTarget* t) {
       if (v != "balance" && v != "power") return Status::Error("");
       if (t) t->scene->integrator.power_heuristic = v == "power";
       return Status::Ok();
     }},
    {"lightSamples", "an integer in [1, 65536] (as render -l)",
     [](const std::string& v, VariantTarget* t) {
       int n = 0;
       if (!ParseIntIn(v, 1, 1 << 16, &n)) return Status::Error("");
       if (t) t->scene->integrator.light_samples = n;
       return Status::Ok();
     }},
    {"maxDepth", "an integer in [-1, 1048576] (-1: unbounded)",
     [](const std::string& v, VariantTarget* t) {
       int n = 0;
       if (!ParseIntIn(v, -1, 1 << 20, &n)) return Status::Error("");
       if (t) t->scene->integrator.max_depth = n;
       return Status::Ok();
     }},
    {"sampler", "independent or sobol",
     [](const std::string& v, VariantTarget* t) {
       SamplerType type;
       if (!SamplerTypeFromName(v, &type)) return Status::Error("");
       if (t) t->scene->sampler.type = type;
       return Status::Ok();
     }},
    {"lights", "uniform or power (how emitter sampling picks the emitter)",
     [](const std::string& v, VariantTarget* t) {
       if (v != "uniform" && v != "power") return Status::Error("");
       if (t)
         t->scene->integrator.light_selection =
             v == "power" ? LightSelection::kPower : LightSelection::kUniform;
       return Status::Ok();
     }},
    {"triangles", "area or solidAngle (how emitter sampling draws a point on a triangle)",
     [](const std::string& v, VariantTarget* t) {
       if (v != "area" && v != "solidAngle") return Status::Error("");
       if (t)
         t->scene->integrator.triangle_sampling =
             v == "area" ? TriangleSampling::kArea : TriangleSampling::kSolidAngle;
       return Status::Ok();
     }},
    {"sampling", "uniform or importance",
     [](const std::string& v, VariantTarget* t) {
       if (v != "uniform" && v != "importance") return Status::Error("");
       if (!t) return Status::Ok();
       EnvironmentMapTable& maps = t->scene->environment_maps;
       for (size_t i = 0; i < maps.size(); ++i) {
         if (v == "uniform") {
           maps.sampling[i] = EnvironmentSampling::kUniform;
         } else if (maps.sampling[i] != EnvironmentSampling::kImportance) {
           // Uniform rows store no distribution (emitter_tables.h).
           return Status::Error(
               "variant sampling=importance: environment map " + std::to_string(i) +
               " was loaded with sampling=\"uniform\" and has no importance distribution; "
               "load the scene with importance sampling and use sampling=uniform instead");
         }
       }
       return Status::Ok();
     }},
    {"adaptive", "BATCH:TOLERANCE (an integer in [2, 1048576] and a number > 0) or off",
     [](const std::string& v, VariantTarget* t) {
       AdaptiveSampling a;
       if (v != "off") {
         const size_t colon = v.find(':');
         int batch = 0;
         if (colon == std::string::npos || !ParseIntIn(v.substr(0, colon), 2, 1 << 20, &batch))
           return Status::Error("");
         const std::string tol = v.substr(colon + 1);
         float tolerance = 0;
         if (ParseNumberQuietly<float>(tol, FLT_MIN, FLT_MAX, &tolerance) != NumberError::kOk)
           return Status::Error("");
         a.batch = uint32_t(batch), a.tolerance = tolerance;
       }
       if (t) t->adaptive = a;
       return Status::Ok();
     }},
    {"path", "packet or scalar",
     [](const std::string& v, VariantTarget* t) {
       if (v != "packet" && v != "scalar") return Status::Error("");
       if (t) t->scalar = v == "scalar";
       return Status::Ok();
     }},
};

const VariantKey* FindKey(const std::string& name) {
  for (const VariantKey& k : kKeys)
    if (name == k.name) return &k;
  return nullptr;
}

}  // namespace

std::string VariantKeys() {
  std::string keys;
  for (const VariantKey& k : kKeys) keys += std::string(keys.empty() ? "" : ", ") + k.name;
  return keys;
}

StatusOr<Variant> ParseVariant(const std::string& spec) {
  Variant variant;
  variant.name = spec.empty() ? "scene" : spec;
  size_t at = 0;
  while (at < spec.size()) {
    size_t end = spec.find(',', at);
    if (end == std::string::npos) end = spec.size();
    const std::string item = spec.substr(at, end - at);
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      return Status::Error("variant '" + spec + "': '" + item + "' is not key=value (keys: " +
                           VariantKeys() + ")");
    const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
    const VariantKey* k = FindKey(key);
    if (!k)
      return Status::Error("variant '" + spec + "': unknown key '" + key + "'; expected one of " +
                           VariantKeys());
    // A key given twice is ambiguous (the last one silently won): refused.
    for (const auto& setting : variant.settings)
      if (setting.first == key)
        return Status::Error("variant '" + spec + "': key '" + key +
                             "' is given twice; expected each key at most once");
    if (!k->apply(value, nullptr).ok()) return Expected(k->name, k->expected, value);
    variant.settings.emplace_back(key, value);
    at = end + 1;
  }
  return variant;
}

Status ApplyVariant(const Variant& variant, VariantTarget* target) {
  for (const auto& [key, value] : variant.settings) {
    const VariantKey* k = FindKey(key);
    if (!k) return Status::Error("variant '" + variant.name + "': unknown key '" + key + "'");
    const Status st = k->apply(value, target);
    if (!st.ok())
      return st.message().empty() ? Expected(k->name, k->expected, value) : st;
  }
  return Status::Ok();
}

}  // namespace ptlab
