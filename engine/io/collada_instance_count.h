// Counting what a COLLADA node tree instances before expanding it: a few kilobytes of
// <instance_node>s can multiply into billions of triangles (the loader refuses a tree over the
// expansion budget), and the depth limit shared with the node reader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <pugixml.hpp>
#include <string>

#include "engine/core/status.h"
#include "engine/io/collada_document.h"
#include "engine/io/collada_mesh.h"

namespace ptlab::collada {

/// Deepest nesting of nodes read (through <node> children and <instance_node>s): the node
/// reader recurses once a level, and ~10,000 levels overflowed its stack.
inline constexpr size_t kMaxNodeDepth = 256;

/// A count that reached this value has saturated (it means "this many or more").
inline constexpr uint64_t kCountSaturated = UINT64_MAX - 1;
/// a + b, saturating at kCountSaturated.
uint64_t SaturatingAdd(uint64_t a, uint64_t b);

/// The error for a node nested deeper than kMaxNodeDepth.
Status NodesTooDeep(const Document& doc, const pugi::xml_node& node);

/// A node's id, else its name (for messages).
std::string NodeName(const pugi::xml_node& node);

/// The triangles and spheres a node instances, its subtree and the nodes it instances
/// included; memoised per node, so shared subtrees are counted once however often they are
/// instanced. Cycles and depth are refused here as the node reader would.
class InstanceCounter {
 public:
  /// `geometries`: the <library_geometries> read, by the element's offset.
  InstanceCounter(const Document& doc, const std::map<ptrdiff_t, Geometry>& geometries)
      : doc_(doc), geometries_(geometries) {}

  /// The count of `node` at nesting `depth` (0 for the visual scene's nodes).
  Status Count(const pugi::xml_node& node, size_t depth, uint64_t* count);

 private:
  const Document& doc_;
  const std::map<ptrdiff_t, Geometry>& geometries_;
  std::map<ptrdiff_t, uint64_t> memo_;
};

}  // namespace ptlab::collada
