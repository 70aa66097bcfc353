// Sampler names.
#include "engine/sampling/sampler.h"

namespace ptlab {

const char* SamplerTypeName(SamplerType type) {
  switch (type) {
    case SamplerType::kIndependent: return "independent";
    case SamplerType::kSobol: return "sobol";
  }
  return "";
}

bool SamplerTypeFromName(std::string_view name, SamplerType* type) {
  for (const SamplerType t : {SamplerType::kIndependent, SamplerType::kSobol}) {
    if (name == SamplerTypeName(t)) {
      *type = t;
      return true;
    }
  }
  return false;
}

}  // namespace ptlab
