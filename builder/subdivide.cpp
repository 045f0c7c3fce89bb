// subdivide.cpp: one round of Catmull-Clark subdivision (Catmull & Clark 1978) on an indexed manifold
// polygon mesh, with the usual boundary rules (the boundary curve is a cubic B-spline; a boundary vertex
// with a single face is a corner and stays put, like OpenSubdiv's "edge and corner" interpolation).
// Written here rather than taken from OpenMesh because OpenMesh's CatmullClarkT uses a different
// boundary vertex mask (2/3, 1/6, 1/6), keeps no corners, and needs a half-edge mesh ~3x the memory;
// tests compare the interior rules against OpenMesh on closed meshes.
#include <algorithm>

#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {

uint64_t subdividedFaceCount(const PolygonMesh& mesh, int levels) {
  if (levels <= 0) return mesh.faceCount();
  uint64_t count = mesh.faceVertices.size();  // level 1: one quad per corner
  for (int l = 1; l < levels; l++) {
    if (count > (uint64_t(1) << 60)) return UINT64_MAX;
    count *= 4;
  }
  return count;
}

PolygonMesh subdivideCatmullClark(const PolygonMesh& mesh, int threads) {
  const size_t vertexCount = mesh.positions.size(), faceCount = mesh.faceCount();
  const size_t cornerCount = mesh.faceVertices.size();

  // Every corner's edge (to the next corner of its face) and face; the corners sorted by edge, so that
  // an edge's corners are a run, in the order of their faces.
  std::vector<std::pair<uint64_t, uint32_t>> edgeOfCorner(cornerCount);
  std::vector<uint32_t> faceOf(cornerCount);
  parallelFor(faceCount, threads, [&](size_t f) {
    const uint32_t n = mesh.faceSize(f), first = mesh.faceStart[f];
    for (uint32_t i = 0; i < n; i++) {
      edgeOfCorner[first + i] = {undirectedEdge(mesh.face(f)[i], mesh.face(f)[(i + 1) % n]), first + i};
      faceOf[first + i] = uint32_t(f);
    }
  });
  parallelSort(edgeOfCorner, threads);
  // Edges numbered in that order, from each run's first corner.
  std::vector<uint64_t> edgeKey;
  std::vector<uint32_t> edgeFirst;  // each edge's first entry in edgeOfCorner; one more, the end
  parallelNumber(
      cornerCount, threads, [&](size_t i) { return i == 0 || edgeOfCorner[i].first != edgeOfCorner[i - 1].first; },
      [&](size_t edges) {
        edgeKey.resize(edges);
        edgeFirst.resize(edges + 1);
      },
      [&](size_t i, size_t e) {
        edgeKey[e] = edgeOfCorner[i].first;
        edgeFirst[e] = uint32_t(i);
      });
  edgeFirst.back() = uint32_t(cornerCount);
  std::vector<uint32_t> cornerEdge(cornerCount);
  parallelForRanges(edgeKey.size(), threads, [&](size_t begin, size_t end) {
    for (size_t e = begin; e < end; e++)
      for (uint32_t k = edgeFirst[e]; k < edgeFirst[e + 1]; k++) cornerEdge[edgeOfCorner[k].second] = uint32_t(e);
  });
  const size_t edgeCount = edgeKey.size();
  auto edgeFaces = [&](size_t e) { return edgeFirst[e + 1] - edgeFirst[e]; };  // 1 (boundary) or 2

  // Face points.
  std::vector<glm::dvec3> facePoint(faceCount);
  parallelFor(faceCount, threads, [&](size_t f) {
    glm::dvec3 sum(0.0);
    for (uint32_t i = 0; i < mesh.faceSize(f); i++) sum += glm::dvec3(mesh.positions[mesh.face(f)[i]]);
    facePoint[f] = sum / double(mesh.faceSize(f));
  });
  // Edge points: midpoint plus, inside, the two face points (added in the order of their faces).
  std::vector<glm::dvec3> edgePoint(edgeCount);
  parallelForRanges(edgeCount, threads, [&](size_t begin, size_t end) {
    for (size_t e = begin; e < end; e++) {
      glm::dvec3 a(mesh.positions[edgeKey[e] >> 32]), b(mesh.positions[edgeKey[e] & 0xffffffffu]);
      edgePoint[e] = edgeFaces(e) == 1 ? (a + b) * 0.5 : (a + b) * 0.25;
      if (edgeFaces(e) == 2)
        for (uint32_t k = edgeFirst[e]; k < edgeFirst[e + 1]; k++)
          edgePoint[e] += facePoint[faceOf[edgeOfCorner[k].second]] * 0.25;
    }
  });
  std::vector<std::pair<uint64_t, uint32_t>>().swap(edgeOfCorner);

  // Vertex points. Interior: (Q + 2R + (n-3) V) / n with Q the mean of the face points, R the mean of
  // the edge midpoints, n the valence. Boundary: 3/4 V + 1/8 (A + B) over the two boundary neighbours.
  // Each vertex gathers from its own corners: its faces in face order, its edges (the two sides of each
  // corner, once each) in edge order, the order one pass over the faces and one over the edges would
  // add them in.
  FillLaterVector<uint32_t> cornerStart, cornersAt;
  cornersByVertex(mesh.faceVertices, vertexCount, threads, cornerStart, cornersAt);
  PolygonMesh out;
  out.positions.resize(vertexCount + edgeCount + faceCount);
  parallelForRanges(vertexCount, threads, [&](size_t begin, size_t end) {
    std::vector<uint32_t> edges;
    for (size_t v = begin; v < end; v++) {
      glm::dvec3 p(mesh.positions[v]), sumFaces(0.0), sumMid(0.0), sumBoundary(0.0);
      edges.clear();
      for (size_t k = cornerStart[v]; k < cornerStart[v + 1]; k++) {
        const uint32_t c = cornersAt[k], f = faceOf[c], first = mesh.faceStart[f];
        sumFaces += facePoint[f];
        edges.push_back(cornerEdge[c]);
        edges.push_back(cornerEdge[c == first ? mesh.faceStart[f + 1] - 1 : c - 1]);
      }
      std::sort(edges.begin(), edges.end());
      edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      uint32_t boundary = 0;
      for (uint32_t e : edges) {
        const glm::dvec3 a(mesh.positions[edgeKey[e] >> 32]), b(mesh.positions[edgeKey[e] & 0xffffffffu]);
        sumMid += (a + b) * 0.5;
        if (edgeFaces(e) == 1) {
          sumBoundary += (edgeKey[e] >> 32) == v ? b : a;
          boundary++;
        }
      }
      const size_t faces = cornerStart[v + 1] - cornerStart[v];
      if (boundary == 0 && !edges.empty()) {
        double n = double(edges.size());
        p = (sumFaces / double(faces) + 2.0 * sumMid / n + (n - 3.0) * p) / n;
      } else if (boundary == 2 && faces >= 2) {
        p = 0.75 * p + 0.125 * sumBoundary;
      }  // corners (one face) and unused vertices stay
      out.positions[v] = glm::vec3(p);
    }
  });
  std::vector<uint32_t>().swap(faceOf);
  parallelForRanges(edgeCount, threads, [&](size_t begin, size_t end) {
    for (size_t e = begin; e < end; e++) out.positions[vertexCount + e] = glm::vec3(edgePoint[e]);
  });
  parallelForRanges(faceCount, threads, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; f++) out.positions[vertexCount + edgeCount + f] = glm::vec3(facePoint[f]);
  });

  // A quad a corner, in the order of the corners.
  out.faceStart.resize(cornerCount + 1);
  out.faceVertices.resize(cornerCount * 4);
  parallelFor(faceCount, threads, [&](size_t f) {
    const uint32_t n = mesh.faceSize(f), first = mesh.faceStart[f];
    for (uint32_t i = 0; i < n; i++) {
      const uint32_t c = first + i;
      uint32_t* quad = &out.faceVertices[4 * size_t(c)];
      quad[0] = mesh.face(f)[i];
      quad[1] = uint32_t(vertexCount + cornerEdge[c]);
      quad[2] = uint32_t(vertexCount + edgeCount + f);
      quad[3] = uint32_t(vertexCount + cornerEdge[first + (i + n - 1) % n]);
      out.faceStart[c + 1] = 4 * (c + 1);
    }
  });
  out.faceStart[0] = 0;
  return out;
}

}  // namespace vgeo
