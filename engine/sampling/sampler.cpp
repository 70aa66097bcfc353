// Sampler names; PathSampler's Sobol' draws.
#include "engine/sampling/sampler.h"

namespace ptlab {

const char* SamplerTypeName(SamplerType type) {
  switch (type) {
    case SamplerType::kIndependent: return "independent";
    case SamplerType::kSobol: return "sobol";
  }
  return "";
}

float PathSampler::Sobol1D(uint32_t dim, uint32_t sub, uint32_t sub_count) const {
  return ScrambledSobol1D(index_ * sub_count + sub, Seeds(dim));
}

Vec2f PathSampler::Sobol2D(uint32_t dim, uint32_t sub, uint32_t sub_count) const {
  return ScrambledSobol2D(index_ * sub_count + sub, Seeds(dim));
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
