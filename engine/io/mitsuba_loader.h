// Mitsuba scenes (`<scene version="...">`, Mitsuba 3 and the 0.6 spellings) loaded into a
// Scene. docs/mitsuba.md lists what is supported and how each plugin maps to ptlab.
#pragma once

#include <string>

#include "engine/core/status.h"
#include "engine/io/xml_loader.h"
#include "engine/scene/scene.h"

namespace ptlab {

/// Loads the Mitsuba scene at `path` (options.defines set its parameters). Relative file names
/// resolve through the scene's <path>s and then its folder, as Mitsuba's file resolver does.
/// Errors are "file:line:col: message"; a plugin or property value ptlab cannot render exactly
/// is "file:line:col: unsupported: bsdf \"roughplastic\"" (shape, emitter, sensor, texture,
/// integrator, ...), never an approximation.
StatusOr<Scene> LoadMitsubaScene(const std::string& path, const LoadOptions& options = {});

/// As LoadMitsubaScene, from text: `base_dir` is the scene's folder, `display_name` what
/// messages call the file.
StatusOr<Scene> LoadMitsubaSceneFromString(const std::string& xml, const std::string& base_dir,
                                           const std::string& display_name,
                                           const LoadOptions& options = {});

/// η and k of a named conductor of Mitsuba's `material` list (e.g. "Au", "Cu", "Al"), read
/// from `ior/NAME.eta.spd` and `ior/NAME.k.spd` in the first of `search_paths` (or of their
/// parent folders) that holds them, converted to RGB as Mitsuba's rgb variant does
/// (SpectrumToRgb, SpectrumUse::kUnbounded). "none" is η = 0, k = 1 (Mitsuba's perfect
/// mirror).
Status LookupMitsubaConductor(const std::vector<std::string>& search_paths, const std::string& name,
                              Color3f* eta, Color3f* k);

}  // namespace ptlab
