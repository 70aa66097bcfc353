// Scene loader choice by file name or content.
#include "engine/io/scene_file.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string_view>

#include "engine/io/collada_loader.h"
#include "engine/io/mitsuba_document.h"
#include "engine/io/mitsuba_loader.h"

namespace ptlab {
namespace {

// The first 64 KiB of the file at `path` ("" if unreadable).
std::string Head(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return "";
  std::string buffer(65536, '\0');
  buffer.resize(std::fread(buffer.data(), 1, buffer.size(), file));
  std::fclose(file);
  return buffer;
}

// The name of the first element of `head` ("" if none is found).
std::string RootElementName(std::string_view head) {
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
  const std::string head = Head(path);
  const std::string root = RootElementName(head);
  if (root == "COLLADA") return SceneFormat::kCollada;
  if (root == "scene" && internal::LooksLikeMitsubaScene(head)) return SceneFormat::kMitsuba;
  return SceneFormat::kNoriXml;
}

StatusOr<Scene> LoadSceneFile(const std::string& path, const LoadOptions& options) {
  switch (SceneFormatOf(path)) {
    case SceneFormat::kCollada: return LoadColladaScene(path);
    case SceneFormat::kMitsuba: return LoadMitsubaScene(path, options);
    case SceneFormat::kNoriXml: break;
  }
  return LoadScene(path, options);
}

}  // namespace ptlab
