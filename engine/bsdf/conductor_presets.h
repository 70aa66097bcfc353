// Named conductor presets (Mitsuba-style `material` names): complex IOR η + iκ at 614/549/466 nm.
#pragma once

#include <string_view>

#include "engine/core/vec.h"

namespace ptlab {

/// Looks up a named conductor ("Au", "Ag", "Al", "Cu", "Fe", "Na", "Si", plus the aliases
/// "Na_palik" and "none"; case-sensitive, as Mitsuba). Sets *eta and *k to the complex IOR
/// relative to vacuum at 614, 549 and 466 nm (R, G, B). "none" is a perfect mirror
/// (η = 0, κ = 1: F = 1 at every angle, as Mitsuba). Returns false, leaving the outputs
/// untouched, for unknown names.
bool LookupConductorPreset(std::string_view name, Color3f* eta, Color3f* k);

/// The preset names LookupConductorPreset accepts, for error messages:
/// "Ag, Al, Au, Cu, Fe, Na, Na_palik, Si, none".
const char* ConductorPresetNames();

}  // namespace ptlab
