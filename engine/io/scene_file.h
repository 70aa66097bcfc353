// One entry point for scene files: picks the loader by extension, or by the root element.
#pragma once

#include <string>

#include "engine/core/status.h"
#include "engine/scene/scene.h"
#include "engine/io/xml_loader.h"

namespace ptlab {

enum class SceneFormat { kNoriXml, kCollada };

/// The format of the file at `path`: ".dae" is COLLADA and ".xml" Nori/Mitsuba XML (any
/// case); for other names, COLLADA when the document's root element is <COLLADA>, else XML.
SceneFormat SceneFormatOf(const std::string& path);

/// Loads `path` with the loader of SceneFormatOf(path): LoadScene (engine/io/xml_loader.h,
/// with `options`) or LoadColladaScene (engine/io/collada_loader.h).
StatusOr<Scene> LoadSceneFile(const std::string& path, const LoadOptions& options = {});

}  // namespace ptlab
