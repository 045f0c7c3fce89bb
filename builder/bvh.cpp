// bvh.cpp: the hierarchy the renderer walks to find the groups whose clusters may be in the cut.
// One subtree per simplification level (groups of one level have similar errors and do not overlap, so
// a subtree's max error is tight and its spheres are small), VGEO_BVH_WIDTH children a node, joined
// under one root of up to VGEO_BVH_ROOT_WIDTH children (instance culling tests them all at once).
// Subtrees are built top-down: a set is cut at the median of its longest axis three times into up to 8
// children, which gives balanced nodes of nearby groups.
#include <algorithm>
#include <map>

#include "builder.h"

namespace vgeo {
namespace {

struct Builder {
  const std::vector<BuildGroup>& groups;
  Bvh& bvh;

  // Splits `items` (sorted in place) into up to VGEO_BVH_WIDTH runs by rounds of longest-axis median cuts
  // (three for 8; 16 children measured slower on an H100: see bench/README.md).
  template <class CenterOf>
  std::vector<std::pair<size_t, size_t>> splitRuns(std::vector<uint32_t>& items, size_t lo, size_t hi,
                                                   CenterOf centerOf) {
    std::vector<std::pair<size_t, size_t>> runs{{lo, hi}};
    for (uint32_t width = 1; width < VGEO_BVH_WIDTH; width *= 2) {
      std::vector<std::pair<size_t, size_t>> nextRuns;
      for (auto [a, b] : runs) {
        if (b - a < 2) {
          nextRuns.push_back({a, b});
          continue;
        }
        glm::vec3 lower(INFINITY), upper(-INFINITY);
        for (size_t i = a; i < b; i++) {
          lower = glm::min(lower, centerOf(items[i]));
          upper = glm::max(upper, centerOf(items[i]));
        }
        glm::vec3 e = upper - lower;
        int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
        size_t mid = (a + b) / 2;
        std::nth_element(items.begin() + long(a), items.begin() + long(mid), items.begin() + long(b),
                         [&](uint32_t x, uint32_t y) {
                           float cx = centerOf(x)[axis], cy = centerOf(y)[axis];
                           return cx != cy ? cx < cy : x < y;
                         });
        nextRuns.push_back({a, mid});
        nextRuns.push_back({mid, b});
      }
      runs = std::move(nextRuns);
    }
    return runs;
  }

  void fill(uint32_t node, const std::vector<glm::vec4>& spheres, const std::vector<float>& errors) {
    bvh.nodes[node].sphere = sphereOfSpheres(spheres.data(), spheres.size());
    float e = 0.0f;
    for (float x : errors) e = std::max(e, x);
    bvh.nodes[node].maxError = e;
  }

  // Builds the subtree over groups[items[lo..hi)] into the already allocated node `node`.
  void buildGroups(uint32_t node, std::vector<uint32_t>& items, size_t lo, size_t hi, uint32_t level) {
    shaderio::BvhNode& n = bvh.nodes[node];
    n.level = level;
    std::vector<glm::vec4> spheres;
    std::vector<float> errors;
    if (hi - lo <= VGEO_BVH_WIDTH) {
      n.childOffset = uint32_t(bvh.groupOrder.size());
      n.childCountAndFlags = uint32_t(hi - lo) | VGEO_NODE_LEAF_BIT;
      for (size_t i = lo; i < hi; i++) {
        bvh.groupOrder.push_back(items[i]);
        spheres.push_back(groups[items[i]].sphere);
        errors.push_back(groups[items[i]].error);
      }
      fill(node, spheres, errors);
      return;
    }
    auto runs = splitRuns(items, lo, hi, [&](uint32_t g) { return glm::vec3(groups[g].sphere); });
    uint32_t first = uint32_t(bvh.nodes.size());
    bvh.nodes.resize(bvh.nodes.size() + runs.size());
    bvh.nodes[node].childOffset = first;
    bvh.nodes[node].childCountAndFlags = uint32_t(runs.size());
    for (size_t r = 0; r < runs.size(); r++) {
      buildGroups(first + uint32_t(r), items, runs[r].first, runs[r].second, level);
      spheres.push_back(bvh.nodes[first + r].sphere);
      errors.push_back(bvh.nodes[first + r].maxError);
    }
    fill(node, spheres, errors);
  }

  // Joins `count` contiguous nodes starting at `first` under node 0, through inner nodes of up to 8
  // children when there are more than the root's width.
  void buildTop(uint32_t first, uint32_t count) {
    while (count > VGEO_BVH_ROOT_WIDTH) {
      uint32_t innerFirst = uint32_t(bvh.nodes.size()), innerCount = (count + VGEO_BVH_WIDTH - 1) / VGEO_BVH_WIDTH;
      bvh.nodes.resize(bvh.nodes.size() + innerCount);
      for (uint32_t i = 0; i < innerCount; i++)
        join(innerFirst + i, first + i * VGEO_BVH_WIDTH,
             std::min<uint32_t>(VGEO_BVH_WIDTH, count - i * VGEO_BVH_WIDTH));
      first = innerFirst;
      count = innerCount;
    }
    join(0, first, count);
  }
  void join(uint32_t node, uint32_t first, uint32_t count) {
    std::vector<glm::vec4> spheres;
    std::vector<float> errors;
    for (uint32_t i = first; i < first + count; i++) {
      spheres.push_back(bvh.nodes[i].sphere);
      errors.push_back(bvh.nodes[i].maxError);
    }
    bvh.nodes[node].childOffset = first;
    bvh.nodes[node].childCountAndFlags = count;
    bvh.nodes[node].level = 0xffffffffu;
    fill(node, spheres, errors);
  }
};

}  // namespace

Bvh buildBvh(const std::vector<BuildGroup>& groups) {
  Bvh bvh;
  bvh.nodes.push_back({});  // the root
  std::map<uint32_t, std::vector<uint32_t>> byLevel;
  for (uint32_t g = 0; g < groups.size(); g++) byLevel[groups[g].level].push_back(g);
  Builder b{groups, bvh};
  // Level roots first, so that they are contiguous; their subtrees follow.
  const uint32_t levelRoots = uint32_t(bvh.nodes.size());
  bvh.nodes.resize(bvh.nodes.size() + byLevel.size());
  uint32_t slot = levelRoots;
  for (auto& [level, items] : byLevel) b.buildGroups(slot++, items, 0, items.size(), level);
  b.buildTop(levelRoots, uint32_t(byLevel.size()));
  return bvh;
}

}  // namespace vgeo
