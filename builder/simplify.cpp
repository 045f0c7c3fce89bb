// simplify.cpp: one group's triangles to about half, with the group border locked (meshoptimizer's
// quadric-error edge collapse, Garland & Heckbert 1997). Locked border vertices do not move, so the
// edges this group shares with its neighbours are the same before and after, which keeps every LOD cut
// watertight. When halving fails, relax step by step and say which step was needed:
//   0  error bounded by kBoundedError of the group's extent
//   1  any error (still only collapses that keep the border and the topology)
//   2  border unlocked: only for a group that is a whole component (no neighbour can crack)
//   3  sloppy vertex clustering: likewise, whole components only
// A group that still cannot be halved keeps its clusters, which are regrouped in the next round with
// other neighbours (their old borders are then inside the new group).
#include <meshoptimizer.h>

#include <algorithm>
#include <cfloat>

#include "builder.h"

namespace vgeo {
namespace {
constexpr float kBoundedError = 0.02f;
constexpr float kHalvedRatio = 0.55f;

// Directed edges of a triangle list, sorted.
std::vector<uint64_t> directedEdges(const uint32_t* indices, size_t count) {
  std::vector<uint64_t> edges;
  edges.reserve(count);
  for (size_t t = 0; t + 2 < count; t += 3)
    for (int k = 0; k < 3; k++) edges.push_back(uint64_t(indices[t + size_t(k)]) << 32 | indices[t + size_t((k + 1) % 3)]);
  std::sort(edges.begin(), edges.end());
  return edges;
}
// Directed edges without their reverse: the border of a triangle list.
std::vector<uint64_t> borderEdges(const std::vector<uint64_t>& sorted) {
  std::vector<uint64_t> border;
  for (uint64_t e : sorted)
    if (!std::binary_search(sorted.begin(), sorted.end(), (e << 32) | (e >> 32))) border.push_back(e);
  return border;
}

// meshopt's collapses keep the border but do not test the link condition, so a collapse can fold the
// surface into a non-manifold edge (two triangles on one directed edge). Such a result is rejected, as
// is one whose border changed though it was locked.
bool keepsTopology(const std::vector<uint64_t>& inputBorder, const std::vector<uint64_t>& edges, bool borderLocked) {
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  std::vector<uint64_t> border = borderEdges(edges);
  return borderLocked ? border == inputBorder : border.empty() == inputBorder.empty();
}

// New edges (absent from the input) between two border vertices: a neighbour may have the same edge,
// which would give the cut an edge of four triangles. The DAG builder checks them against every edge
// already made (dag.cpp).
std::vector<uint64_t> newBorderChords(const std::vector<uint64_t>& inputEdges, const std::vector<uint64_t>& inputBorder,
                                      const std::vector<uint64_t>& edges) {
  std::vector<uint32_t> borderVertices;
  for (uint64_t e : inputBorder) borderVertices.push_back(uint32_t(e >> 32));
  std::sort(borderVertices.begin(), borderVertices.end());
  auto onBorder = [&](uint32_t v) { return std::binary_search(borderVertices.begin(), borderVertices.end(), v); };
  std::vector<uint64_t> chords;
  for (uint64_t e : edges) {
    uint32_t a = uint32_t(e >> 32), b = uint32_t(e);
    if (a < b && onBorder(a) && onBorder(b) && !std::binary_search(inputEdges.begin(), inputEdges.end(), e)) chords.push_back(e);
  }
  return chords;
}
}  // namespace

SimplifiedGroup simplifyGroup(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions, bool isWholeComponent,
                              const std::function<bool(uint64_t)>& edgeExists) {
  // Compact the group's vertices: meshopt's cost is linear in the vertex buffer it is given.
  std::vector<uint32_t> globals(indices);
  std::sort(globals.begin(), globals.end());
  globals.erase(std::unique(globals.begin(), globals.end()), globals.end());
  std::vector<uint32_t> local(indices.size());
  for (size_t i = 0; i < indices.size(); i++)
    local[i] = uint32_t(std::lower_bound(globals.begin(), globals.end(), indices[i]) - globals.begin());
  std::vector<glm::vec3> points(globals.size());
  for (size_t i = 0; i < globals.size(); i++) points[i] = positions[globals[i]];
  const float* xyz = &points[0].x;
  const float scale = meshopt_simplifyScale(xyz, points.size(), sizeof(glm::vec3));

  const size_t triangles = indices.size() / 3;
  const size_t halved = size_t(float(triangles) * kHalvedRatio) * 3;
  std::vector<uint32_t> out(indices.size());
  const std::vector<uint64_t> inputEdges = directedEdges(local.data(), local.size());
  const std::vector<uint64_t> inputBorder = borderEdges(inputEdges);
  SimplifiedGroup result;
  size_t count = indices.size();
  float error = 0.0f;
  // Each step tries a few targets: meshopt collapses in error order, so stopping at another count often
  // avoids the one collapse that folded the surface.
  static const float kTargets[] = {0.5f, 0.45f, 0.4f, 0.53f, 0.35f};
  for (int step = 0; step < 4 && !result.halved; step++) {
    if (step >= 2 && !isWholeComponent) break;
    result.relaxation = step;
    for (float ratio : kTargets) {
      const size_t target = size_t(float(triangles) * ratio) * 3;
      if (step < 3) {
        unsigned options = step < 2 ? meshopt_SimplifyLockBorder : 0;
        count = meshopt_simplify(out.data(), local.data(), local.size(), xyz, points.size(), sizeof(glm::vec3), target,
                                 step == 0 ? kBoundedError : FLT_MAX, options, &error);
      } else {
        count = meshopt_simplifySloppy(out.data(), local.data(), local.size(), xyz, points.size(), sizeof(glm::vec3), target,
                                       FLT_MAX, &error);
      }
      if (count > halved || count == 0) { if (getenv("VGEO_DEBUG")) fprintf(stderr, "step %d ratio %.2f tris %zu -> %zu not halved (whole %d)\n", step, ratio, triangles, count / 3, isWholeComponent); break; }
      std::vector<uint64_t> edges = directedEdges(out.data(), count);
      if (!keepsTopology(inputBorder, edges, step < 2)) { if (getenv("VGEO_DEBUG")) fprintf(stderr, "step %d ratio %.2f tris %zu -> %zu topology (whole %d)\n", step, ratio, triangles, count / 3, isWholeComponent); continue; }
      std::vector<uint64_t> chords;
      for (uint64_t chord : newBorderChords(inputEdges, inputBorder, edges))
        chords.push_back(uint64_t(globals[chord >> 32]) << 32 | globals[chord & 0xffffffffu]);
      bool taken = false;
      for (uint64_t c : chords) taken |= edgeExists && edgeExists(c);
      if (taken) { if (getenv("VGEO_DEBUG")) fprintf(stderr, "step %d ratio %.2f chord taken\n", step, ratio); continue; }
      result.halved = true;
      result.borderChords = std::move(chords);
      break;
    }
  }
  result.error = error * scale;
  result.indices.resize(count);
  for (size_t i = 0; i < count; i++) result.indices[i] = globals[out[i]];
  return result;
}

}  // namespace vgeo
