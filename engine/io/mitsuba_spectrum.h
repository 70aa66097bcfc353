// Mitsuba spectra in RGB: wavelength/value lists integrated against the CIE 1931 observer (as
// Mitsuba 3's rgb variants do), `.spd` files, and Mitsuba's table of named dielectric IORs.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "engine/core/status.h"
#include "engine/core/vec.h"

namespace ptlab {

/// What a spectrum describes: Mitsuba converts emission without the D65 weight and unclamped
/// above 1, reflectances weighted by D65 and clamped to [0, 1], and IORs (η, k) unweighted,
/// only clamped below at 0.
enum class SpectrumUse { kReflectance, kEmission, kUnbounded };

/// Linear sRGB (Rec. 709 primaries) of the piecewise-linear spectrum through (wavelengths[i],
/// values[i]) (nm, ascending, at least 2 points), as Mitsuba 3's rgb variant computes it:
/// XYZ = Σ_i CMF(λ_i) v(λ_i) [D65(λ_i)] · (830 − 360) / 1000 / ∫ȳ over 1000 evenly spaced
/// λ_i from 360 to 830 nm (ends included; λ outside the list's range contributes nothing);
/// CMF = the CIE 1931 2° observer tabulated every 5 nm, linearly interpolated; ∫ȳ the same sum
/// for v = 1 (106.750); D65 is normalised by 1/98.99741751876255 (Mitsuba's constant); then
/// the XYZ → linear sRGB matrix, clamped as `use` says.
Color3f SpectrumToRgb(const std::vector<double>& wavelengths, const std::vector<double>& values,
                      SpectrumUse use);

/// Reads a Mitsuba `.spd` file: lines "wavelength value", '#' comments. Errors name the file and
/// line ("path:12: ...").
Status ReadSpdFile(const std::string& path, std::vector<double>* wavelengths,
                   std::vector<double>* values);

/// Mitsuba's named dielectric IORs (Hecht's values at ~589 nm: "bk7" 1.5046, "air" 1.000277,
/// "water" 1.333, "diamond" 2.419, ...); the name is matched case-insensitively. False if
/// unknown.
bool LookupNamedIor(std::string_view name, float* ior);
/// The accepted IOR names, for messages.
std::string NamedIorList();

}  // namespace ptlab
