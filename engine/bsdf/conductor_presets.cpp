// Named conductor presets: complex IOR η + iκ at 614/549/466 nm, from published spectral tables.
#include "engine/bsdf/conductor_presets.h"

namespace ptlab {
namespace {

struct Preset {
  std::string_view name;
  Color3f eta, k;
};

// Values are linear interpolations, in wavelength, of the tabulated data at 614 nm (R),
// 549 nm (G) and 466 nm (B), rounded to 4 decimals:
// - Ag, Al, Au, Cu: the luxpop.com tables that Mitsuba 0.6 ships as data/ior/<name>.{eta,k}.spd
//   (mitsuba-renderer/mitsuba).
// - Na: Palik, Handbook of Optical Constants of Solids II (1991), via Mitsuba's
//   data/ior/Na_palik.{eta,k}.spd.
// - Fe: P. B. Johnson and R. W. Christy, Phys. Rev. B 9, 5056 (1974), via the refractiveindex.info
//   database (CC0), database/data-nk/main/Fe/Johnson.yml.
// - Si: D. E. Aspnes and A. A. Studna, Phys. Rev. B 27, 985 (1983), via the refractiveindex.info
//   database (CC0), database/data-nk/main/Si/Aspnes.yml.
// - Sn: the one visible-range measurement we could find, n = 2.384, k = 4.727 at 632.8 nm (the
//   Filmetrics refractive-index database, "Sn/Tin", typical sample), used for all three channels:
//   a spectrally flat, neutral-grey tin (normal-incidence reflectance 0.718). The published
//   tables we can read (Golovashkin & Motulevich 1964, via refractiveindex.info) start at 730 nm;
//   replace these values when a 400-700 nm table is available.
constexpr Preset kPresets[] = {
    {"Ag", {0.1288f, 0.1252f, 0.1388f}, {3.8355f, 3.3314f, 2.6228f}},
    {"Al", {1.2687f, 0.9543f, 0.6633f}, {7.4134f, 6.6744f, 5.6663f}},
    {"Au", {0.2012f, 0.3551f, 1.3631f}, {3.0424f, 2.6982f, 1.8214f}},
    {"Cu", {0.3030f, 0.9656f, 1.1563f}, {3.1502f, 2.5776f, 2.4614f}},
    {"Fe", {2.8851f, 2.9500f, 2.6500f}, {3.0449f, 2.9300f, 2.8075f}},
    {"Na", {0.0521f, 0.0587f, 0.0662f}, {2.5458f, 2.2434f, 1.8655f}},
    {"Na_palik", {0.0521f, 0.0587f, 0.0662f}, {2.5458f, 2.2434f, 1.8655f}},
    {"Sn", {2.384f, 2.384f, 2.384f}, {4.727f, 4.727f, 4.727f}},
    {"Si", {3.9186f, 4.0903f, 4.5288f}, {0.0236f, 0.0415f, 0.1146f}},
    {"none", {0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}},  // Mitsuba: a 100% reflecting mirror
};

}  // namespace

bool LookupConductorPreset(std::string_view name, Color3f* eta, Color3f* k) {
  for (const Preset& p : kPresets) {
    if (p.name == name) {
      *eta = p.eta;
      *k = p.k;
      return true;
    }
  }
  return false;
}

const char* ConductorPresetNames() { return "Ag, Al, Au, Cu, Fe, Na, Na_palik, Si, Sn, none"; }

}  // namespace ptlab
