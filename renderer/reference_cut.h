// reference_cut.h: the CPU reference cut of a whole scene, with frustum culling (reference_cut.cpp).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "camera.h"
#include "scene.h"

namespace vgeo {

struct CutEntry {
  uint32_t instance, cluster;
  bool operator==(const CutEntry& o) const { return instance == o.instance && cluster == o.cluster; }
};
struct SceneCut {
  std::vector<CutEntry> entries;     // drawn, with every test clear of its boundary
  std::vector<CutEntry> borderline;  // some test within epsilon of its boundary: may go either way
};
// The cut the GPU must produce for the cull view `cull` and `tau` (pixels); `epsilon` is relative.
SceneCut selectSceneCut(const RenderScene& scene, const View& cull, float tau, float epsilon = 1e-5f);
// True when the GPU list equals the reference as a set, borderline entries either way (with `subset`, when
// it is a subset of it: occlusion culling lists only what it found not hidden); else says why.
bool compareCuts(const SceneCut& reference, std::vector<CutEntry> gpu, std::string& firstDifference,
                 bool subset = false);

}  // namespace vgeo
