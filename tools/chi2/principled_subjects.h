// Chi-square subjects of Mitsuba's principled and principledthin BSDFs (several parameter sets).
#pragma once

#include "tools/chi2/subjects.h"

namespace ptlab {

void RegisterPrincipledBsdfSubjects(Chi2Registry* registry);

}  // namespace ptlab
