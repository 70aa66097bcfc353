// Counting what a COLLADA node tree instances, before expanding it (collada_instance_count.h).
#include "engine/io/collada_instance_count.h"

#include <string_view>

namespace ptlab::collada {
namespace {
constexpr uint64_t kCounting = UINT64_MAX;  // a node whose count is under way
}  // namespace

std::string NodeName(const pugi::xml_node& node) {
  if (const char* id = node.attribute("id").value(); *id) return id;
  return node.attribute("name").value();
}

uint64_t SaturatingAdd(uint64_t a, uint64_t b) {
  return a > kCountSaturated - b ? kCountSaturated : a + b;
}

Status NodesTooDeep(const Document& doc, const pugi::xml_node& node) {
  return doc.Error(node, "<node>s nested deeper than " + std::to_string(kMaxNodeDepth) +
                             " levels (through <node> and <instance_node>); expected at most " +
                             std::to_string(kMaxNodeDepth));
}

Status InstanceCounter::Count(const pugi::xml_node& node, size_t depth, uint64_t* count) {
  if (depth >= kMaxNodeDepth) return NodesTooDeep(doc_, node);
  const auto [it, inserted] = memo_.emplace(node.offset_debug(), kCounting);
  if (!inserted) {
    if (it->second == kCounting)
      return doc_.Error(node, "node '" + NodeName(node) + "' instances itself (a cycle of "
                              "<instance_node>s); expected a tree");
    *count = it->second;
    return Status::Ok();
  }
  uint64_t sum = 0;
  for (const pugi::xml_node child : node.children()) {
    const std::string_view name = child.name();
    uint64_t n = 0;
    if (name == "node") {
      PTLAB_RETURN_IF_ERROR(Count(child, depth + 1, &n));
    } else if (name == "instance_node") {
      pugi::xml_node target;
      PTLAB_RETURN_IF_ERROR(doc_.Resolve(child, "url", "node", &target));
      PTLAB_RETURN_IF_ERROR(Count(target, depth + 1, &n));
    } else if (name == "instance_geometry" || name == "instance_light") {
      n = 1;  // a sphere or a light (an area light: two triangles)
      pugi::xml_node geometry;
      if (name == "instance_geometry" &&
          doc_.Resolve(child, "url", "geometry", &geometry).ok()) {
        const auto g = geometries_.find(geometry.offset_debug());
        if (g != geometries_.end() && !g->second.is_sphere) {
          n = 0;
          for (const collada::MeshPart& part : g->second.parts)
            n = SaturatingAdd(n, part.mesh.triangle_count());
        }
      }
    }
    sum = SaturatingAdd(sum, n);
  }
  memo_[node.offset_debug()] = sum;
  *count = sum;
  return Status::Ok();
}

}  // namespace ptlab::collada
