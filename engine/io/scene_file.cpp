// Scene loader choice by file name or content.
#include "engine/io/scene_file.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string_view>

#include "engine/io/collada_loader.h"

namespace ptlab {
namespace {

// The name of the first element of the document at `path` ("" if none is found in its head).
std::string RootElementName(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return "";
  char buffer[4096];
  const size_t n = std::fread(buffer, 1, sizeof buffer, file);
  std::fclose(file);
  const std::string_view head(buffer, n);
  for (size_t i = head.find('<'); i != std::string_view::npos; i = head.find('<', i + 1)) {
    if (i + 1 >= head.size()) break;
    const char c = head[i + 1];
    if (c == '?' || c == '!') continue;  // declaration, comment, doctype
    size_t end = i + 1;
    while (end < head.size() && (std::isalnum(static_cast<unsigned char>(head[end])) ||
                                 head[end] == '_' || head[end] == ':'))
      ++end;
    return std::string(head.substr(i + 1, end - i - 1));
  }
  return "";
}

}  // namespace

SceneFormat SceneFormatOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".dae") return SceneFormat::kCollada;
  if (ext == ".xml") return SceneFormat::kNoriXml;
  return RootElementName(path) == "COLLADA" ? SceneFormat::kCollada : SceneFormat::kNoriXml;
}

StatusOr<Scene> LoadSceneFile(const std::string& path, const LoadOptions& options) {
  if (SceneFormatOf(path) == SceneFormat::kCollada) return LoadColladaScene(path);
  return LoadScene(path, options);
}

}  // namespace ptlab
