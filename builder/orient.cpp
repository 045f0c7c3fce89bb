// orient.cpp: consistent face orientation, one connected component at a time.
// Meshes from scanners and CAD exports often have faces wound the wrong way round. Repair treats an
// edge walked the same way by both of its faces as non-manifold and cuts the surface there, and the
// simplifier cannot reduce across a cut, so such a mesh got no LOD at all. This step is the usual
// breadth-first propagation (as in CGAL's Polygon Mesh Processing, orient_polygon_soup): faces are
// joined through edges that have exactly two faces; walking from a seed, a neighbour that walks the
// shared edge the same way as its already-oriented face is flipped. An edge with more than two faces
// joins nothing (which pairs belong together is not known). Of the two orientations a component can
// take, the one that keeps more of the input's face area as it was is chosen, so a mostly right mesh
// changes little and the result does not depend on the seed. A component where propagation meets
// itself with the opposite sign (a Moebius strip) cannot be oriented; it is counted and left to
// repair, which cuts it at the edges that disagree.
#include <algorithm>
#include <numeric>

#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {

OrientReport orientFaces(PolygonMesh& mesh, int threads, std::vector<CornerEdge>* sortedEdges) {
  OrientReport report;
  const size_t faceCount = mesh.faceCount();
  // Every corner's edge, sorted by (key, corner): an edge's faces are adjacent, in face order (a face
  // holds an undirected edge once, as repair left its corners distinct).
  std::vector<uint32_t> cornerFace(mesh.faceVertices.size());
  std::vector<CornerEdge> halfEdges(mesh.faceVertices.size());
  parallelForRanges(faceCount, threads, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; f++)
      for (uint32_t i = 0, n = mesh.faceSize(f); i < n; i++) {
        uint32_t a = mesh.face(f)[i], b = mesh.face(f)[(i + 1) % n];
        cornerFace[mesh.faceStart[f] + i] = uint32_t(f);
        halfEdges[mesh.faceStart[f] + i] = {uint64_t(std::min(a, b)) << 32 | std::max(a, b), mesh.faceStart[f] + i};
      }
  });
  parallelSort(halfEdges, threads, [](const CornerEdge& x, const CornerEdge& y) {
    return x.key != y.key ? x.key < y.key : x.corner < y.corner;
  });
  // From min to max in face order (before any face turns).
  auto forward = [&](const CornerEdge& e) { return mesh.faceVertices[e.corner] == uint32_t(e.key >> 32); };

  // Face adjacency through two-face edges; `same` when both faces walk the edge the same way (one of
  // them must turn for the pair to agree).
  struct Link {
    uint32_t other;
    bool same;
  };
  std::vector<uint32_t> linkStart(faceCount + 1, 0);
  std::vector<std::array<uint32_t, 2>> pairs;
  std::vector<bool> pairSame;
  for (size_t i = 0; i < halfEdges.size();) {
    size_t j = i;
    while (j < halfEdges.size() && halfEdges[j].key == halfEdges[i].key) j++;
    const uint32_t f0 = cornerFace[halfEdges[i].corner], f1 = j - i == 2 ? cornerFace[halfEdges[i + 1].corner] : f0;
    if (j - i == 2 && f0 != f1) {
      pairs.push_back({f0, f1});
      pairSame.push_back(forward(halfEdges[i]) == forward(halfEdges[i + 1]));
      linkStart[f0 + 1]++;
      linkStart[f1 + 1]++;
    }
    i = j;
  }
  std::partial_sum(linkStart.begin(), linkStart.end(), linkStart.begin());
  std::vector<Link> links(linkStart.back());
  {
    std::vector<uint32_t> fill(linkStart.begin(), linkStart.end() - 1);
    for (size_t p = 0; p < pairs.size(); p++) {
      links[fill[pairs[p][0]]++] = {pairs[p][1], pairSame[p]};
      links[fill[pairs[p][1]]++] = {pairs[p][0], pairSame[p]};
    }
  }

  auto area = [&](size_t f) {
    const uint32_t* c = mesh.face(f);
    glm::dvec3 a(mesh.positions[c[0]]), n(0.0);
    for (uint32_t k = 1; k + 1 < mesh.faceSize(f); k++)
      n += glm::cross(glm::dvec3(mesh.positions[c[k]]) - a, glm::dvec3(mesh.positions[c[k + 1]]) - a);
    return glm::length(n);
  };

  constexpr uint8_t kUnseen = 2;
  std::vector<uint8_t> flip(faceCount, kUnseen);
  std::vector<uint32_t> component, stack;
  for (size_t seed = 0; seed < faceCount; seed++) {
    if (flip[seed] != kUnseen) continue;
    report.components++;
    component.clear();
    stack.assign(1, uint32_t(seed));
    flip[seed] = 0;
    bool orientable = true;
    while (!stack.empty()) {
      uint32_t f = stack.back();
      stack.pop_back();
      component.push_back(f);
      for (uint32_t l = linkStart[f]; l < linkStart[f + 1]; l++) {
        uint8_t want = uint8_t(flip[f] ^ uint8_t(links[l].same));
        uint32_t g = links[l].other;
        if (flip[g] == kUnseen) {
          flip[g] = want;
          stack.push_back(g);
        } else if (flip[g] != want) {
          orientable = false;
        }
      }
    }
    if (!orientable) report.nonOrientableComponents++;
    double kept = 0.0, turned = 0.0;
    for (uint32_t f : component) (flip[f] ? turned : kept) += area(f);
    if (turned > kept)
      for (uint32_t f : component) flip[f] ^= 1u;
  }
  if (sortedEdges) {
    // A turned face keeps its edges; the edge that started at corner k of n starts at n-2-k (mod n),
    // and the order stays (key, corner), since a key's corners are in distinct faces, in face order.
    parallelForRanges(halfEdges.size(), threads, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; i++) {
        const uint32_t c = halfEdges[i].corner, f = cornerFace[c];
        if (flip[f] != 1) continue;
        const uint32_t start = mesh.faceStart[f], n = mesh.faceSize(f);
        halfEdges[i].corner = start + (2 * n - 2 - (c - start)) % n;
      }
    });
    *sortedEdges = std::move(halfEdges);
  }
  for (size_t f = 0; f < faceCount; f++)
    if (flip[f] == 1) {
      std::reverse(mesh.faceVertices.begin() + mesh.faceStart[f], mesh.faceVertices.begin() + mesh.faceStart[f + 1]);
      if (!mesh.cornerNormals.empty())
        std::reverse(mesh.cornerNormals.begin() + mesh.faceStart[f],
                     mesh.cornerNormals.begin() + mesh.faceStart[f + 1]);
      report.flippedFaces++;
    }
  return report;
}

}  // namespace vgeo
