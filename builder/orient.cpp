// orient.cpp: consistent face orientation, one connected component at a time.
// Meshes from scanners and CAD exports often have faces wound the wrong way round. Repair treats an
// edge walked the same way by both of its faces as non-manifold and cuts the surface there, and the
// simplifier cannot reduce across a cut, so such a mesh got no LOD at all. Faces are joined through
// edges that have exactly two faces, as in CGAL's Polygon Mesh Processing (orient_polygon_soup); two
// faces that walk their shared edge the same way must differ in whether they turn, others agree. Those
// relations go into a union-find that keeps each face's turn relative to its set (built on all threads
// at once); an edge with more than two faces joins nothing (which pairs belong together is not known).
// Of the two orientations a component can take, the one that keeps more of the input's face area as
// it was is chosen, so a mostly right mesh changes little and the result does not depend on an order. A
// component whose relations contradict each other (a Moebius strip) cannot be oriented: it is counted,
// takes the turns of a breadth-first walk from its first face, and is left to repair, which cuts it at
// the edges that disagree.
#include <algorithm>
#include <numeric>

#include "../common/bucket_sort.h"
#include "../common/parallel.h"
#include "builder.h"
#include "union_find.h"

namespace vgeo {
OrientReport orientFaces(PolygonMesh& mesh, int threads, OrientedEdges* oriented) {
  OrientReport report;
  const size_t faceCount = mesh.faceCount();
  // Every corner's edge, sorted by (key, corner): an edge's faces are adjacent, in face order (a face
  // holds an undirected edge once, as repair left its corners distinct).
  FillLaterVector<uint32_t> cornerFace(mesh.faceVertices.size());
  parallelForRanges(faceCount, threads, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; f++)
      std::fill(cornerFace.begin() + mesh.faceStart[f], cornerFace.begin() + mesh.faceStart[f + 1], uint32_t(f));
  });
  FillLaterVector<CornerEdge> halfEdges = bucketSorted<CornerEdge>(
      faceCount, bitsFor(mesh.positions.size()), bitsFor(mesh.positions.size()), threads,
      [&](size_t f, auto&& emit) {
        for (uint32_t i = 0, n = mesh.faceSize(f); i < n; i++) {
          uint32_t a = mesh.face(f)[i], b = mesh.face(f)[(i + 1) % n];
          emit(std::min(a, b), CornerEdge{std::min(a, b), std::max(a, b), mesh.faceStart[f] + i});
        }
      },
      std::less<CornerEdge>());
  // Across each two-face edge, the corner of the other face that starts it: a face's neighbours are
  // its corners' partners, visited in the order of their edges' keys.
  FillLaterVector<uint32_t> partner = parallelFilled(mesh.faceVertices.size(), UINT32_MAX, threads);
  bool crowded = false;  // an edge of more than two faces, or of one face twice
  parallelForRuns(
      halfEdges.size(), threads, [&](size_t i, size_t j) { return halfEdges[i].key() == halfEdges[j].key(); },
      [&](size_t i, size_t j) {
        const uint32_t c0 = halfEdges[i].corner, c1 = j - i == 2 ? halfEdges[i + 1].corner : c0;
        if (j - i == 2 && cornerFace[c0] != cornerFace[c1])
          partner[c0] = c1, partner[c1] = c0;
        else if (j - i > 1)
          __atomic_store_n(&crowded, true, __ATOMIC_RELAXED);
      });
  auto edgeKey = [&](uint32_t c) {
    const uint32_t f = cornerFace[c], next = c + 1 == mesh.faceStart[f + 1] ? mesh.faceStart[f] : c + 1;
    const uint32_t a = mesh.faceVertices[c], b = mesh.faceVertices[next];
    return undirectedEdge(a, b);
  };

  auto area = [&](size_t f) { return glm::length(mesh.areaVector(f)); };

  // Each face's turn relative to its component's first face, from the parity union-find over the
  // two-face edges (faces walking an edge the same way must differ, else agree).
  ParityUnionFind faces(faceCount, threads);
  // Faces where the relations met with opposite signs.
  FillLaterVector<uint8_t> conflict = parallelFilled(faceCount, uint8_t(0), threads);
  parallelForRanges(partner.size(), threads, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; c++) {
      const uint32_t p = partner[c];
      if (p == UINT32_MAX || p < c) continue;  // each edge once
      // Both faces walk the edge the same way when their corners on it start at the same vertex.
      const bool same = mesh.faceVertices[c] == mesh.faceVertices[p];
      if (!faces.unite(cornerFace[c], cornerFace[p], same)) conflict[cornerFace[c]] = 1;
    }
  });
  FillLaterVector<uint32_t> root(faceCount);
  FillLaterVector<uint8_t> flip(faceCount);
  parallelForRanges(faceCount, threads, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; f++) {
      const auto [r, parity] = faces.findWithTurn(uint32_t(f));
      root[f] = r, flip[f] = parity;
    }
  });
  faces = ParityUnionFind(0);
  // Components, and whether any face turns or any relation conflicts: a mesh already wound one way
  // (the usual case) has no areas to weigh and no walks to make.
  size_t components = 0;
  bool anyTurned = false, anyConflict = false;
  parallelForRanges(faceCount, threads, [&](size_t begin, size_t end) {
    size_t roots = 0;
    bool turned = false, conflicted = false;
    for (size_t f = begin; f < end; f++) {
      roots += root[f] == f;
      turned |= flip[f] != 0;
      conflicted |= conflict[f] != 0;
    }
    __atomic_fetch_add(&components, roots, __ATOMIC_RELAXED);
    if (turned) __atomic_store_n(&anyTurned, true, __ATOMIC_RELAXED);
    if (conflicted) __atomic_store_n(&anyConflict, true, __ATOMIC_RELAXED);
  });
  report.components = components;
  FillLaterVector<uint8_t> nonOrientable = parallelFilled(faceCount, uint8_t(0), threads);
  if (anyTurned || anyConflict) {
    // Which way each component keeps more of its area: kept minus turned, summed into the component's
    // first face in face order (so the sums do not depend on the thread count).
    FillLaterVector<double> keptMinusTurned(faceCount);
    parallelForRanges(faceCount, threads, [&](size_t begin, size_t end) {
      for (size_t f = begin; f < end; f++) keptMinusTurned[f] = flip[f] ? -area(f) : area(f);
    });
    for (size_t f = 0; f < faceCount; f++) {
      if (root[f] != f) keptMinusTurned[root[f]] += keptMinusTurned[f];
      if (conflict[f]) nonOrientable[root[f]] = 1;
    }
    parallelForRanges(faceCount, threads, [&](size_t begin, size_t end) {
      for (size_t f = begin; f < end; f++)
        if (!nonOrientable[root[f]] && keptMinusTurned[root[f]] < 0.0) flip[f] ^= 1u;
    });
  }
  FillLaterVector<uint8_t>().swap(conflict);
  // A component that cannot be oriented (a Moebius strip) takes the turns of a walk from its first face,
  // breadth first by edge key: where the walk meets itself with the other sign, repair cuts it.
  constexpr uint8_t kUnseen = 2;
  std::vector<uint32_t> component, stack;
  std::vector<std::pair<uint64_t, uint32_t>> neighbours;  // (edge key, corner) of the face being visited
  if (anyConflict)
    for (size_t f = 0; f < faceCount; f++)
      if (nonOrientable[root[f]]) flip[f] = kUnseen;
  for (size_t seed = 0; seed < faceCount && anyConflict; seed++) {
    if (root[seed] != seed || !nonOrientable[seed]) continue;
    report.nonOrientableComponents++;
    component.clear();
    stack.assign(1, uint32_t(seed));
    flip[seed] = 0;
    while (!stack.empty()) {
      uint32_t f = stack.back();
      stack.pop_back();
      component.push_back(f);
      neighbours.clear();
      for (uint32_t c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; c++)
        if (partner[c] != UINT32_MAX) neighbours.push_back({edgeKey(c), c});
      std::sort(neighbours.begin(), neighbours.end());
      for (const auto& [key, c] : neighbours) {
        const bool same = mesh.faceVertices[c] == mesh.faceVertices[partner[c]];
        uint32_t g = cornerFace[partner[c]];
        if (flip[g] == kUnseen) {
          flip[g] = uint8_t(flip[f] ^ uint8_t(same));
          stack.push_back(g);
        }
      }
    }
    double kept = 0.0, turned = 0.0;
    for (uint32_t f : component) (flip[f] ? turned : kept) += area(f);
    if (turned > kept)
      for (uint32_t f : component) flip[f] ^= 1u;
  }
  const bool anyFlip = anyTurned || anyConflict;  // else no face turns
  // Unturned, every two-face edge is walked once each way: a pair walking it alike would differ in turn.
  if (oriented && !anyFlip && !crowded)
    oriented->partner = std::move(partner);
  else
    FillLaterVector<uint32_t>().swap(partner);
  if (oriented && anyFlip) {
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
  }
  if (oriented) {
    oriented->edges = std::move(halfEdges);
    oriented->cornerFace = std::move(cornerFace);  // a face's corners stay its own when it turns
  }
  size_t flipped = 0;
  parallelForRanges(anyFlip ? faceCount : 0, threads, [&](size_t begin, size_t end) {
    size_t turned = 0;
    for (size_t f = begin; f < end; f++)
      if (flip[f] == 1) {
        std::reverse(mesh.faceVertices.begin() + mesh.faceStart[f], mesh.faceVertices.begin() + mesh.faceStart[f + 1]);
        if (!mesh.cornerNormals.empty())
          std::reverse(mesh.cornerNormals.begin() + mesh.faceStart[f],
                       mesh.cornerNormals.begin() + mesh.faceStart[f + 1]);
        turned++;
      }
    __atomic_fetch_add(&flipped, turned, __ATOMIC_RELAXED);
  });
  report.flippedFaces = flipped;
  return report;
}

}  // namespace vgeo
