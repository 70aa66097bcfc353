// One entry point for scene files: picks the loader by extension, or by the root element.
#pragma once

#include <string>

#include "engine/core/status.h"
#include "engine/scene/scene.h"
#include "engine/io/xml_loader.h"

namespace ptlab {

enum class SceneFormat { kNoriXml, kCollada, kMitsuba };

/// The format of the file at `path`: ".dae" (any case) is COLLADA; otherwise, by the head of
/// the document: a <COLLADA> root is COLLADA, a <scene> root with a `version` attribute or
/// with a Mitsuba-only child (<sensor>, <default>, <include>, <path>) is Mitsuba
/// (engine/io/mitsuba_loader.h), anything else Nori XML.
SceneFormat SceneFormatOf(const std::string& path);

/// Loads `path` with the loader of SceneFormatOf(path): LoadScene (engine/io/xml_loader.h,
/// with `options`), LoadMitsubaScene (engine/io/mitsuba_loader.h, with `options`) or
/// LoadColladaScene (engine/io/collada_loader.h).
StatusOr<Scene> LoadSceneFile(const std::string& path, const LoadOptions& options = {});

}  // namespace ptlab
