// PTLAB_TARGET (target_select.h).
#include "simd/targets.h"  // first: the compiled target set

#include "simd/target_select.h"

#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "hwy/targets.h"

namespace ptlab::simd {
namespace {

std::string Upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::string AvailableTargetNames() {
  std::string names;
  for (int64_t t : hwy::SupportedAndGeneratedTargets())
    names += (names.empty() ? "" : " ") + std::string(hwy::TargetName(t));
  return names;
}

Status SelectTargetFromEnvironment() {
  const char* value = std::getenv("PTLAB_TARGET");
  if (value == nullptr || *value == '\0') return Status::Ok();
  const std::string wanted = Upper(value);
  hwy::SetSupportedTargetsForTest(0);  // what the CPU supports, should an earlier call have pinned
  for (int64_t t : hwy::SupportedAndGeneratedTargets()) {
    if (Upper(hwy::TargetName(t)) == wanted) {
      hwy::SetSupportedTargetsForTest(t);
      return Status::Ok();
    }
  }
  return Status::Error("PTLAB_TARGET=" + std::string(value) +
                       " is not a Highway target compiled in and supported by this CPU; "
                       "expected one of: " + AvailableTargetNames());
}

}  // namespace ptlab::simd
