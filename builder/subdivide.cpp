// subdivide.cpp: one round of Catmull-Clark subdivision (Catmull & Clark 1978) on an indexed manifold
// polygon mesh, with the usual boundary rules (the boundary curve is a cubic B-spline; a boundary vertex
// with a single face is a corner and stays put, like OpenSubdiv's "edge and corner" interpolation).
// Written here rather than taken from OpenMesh because OpenMesh's CatmullClarkT uses a different
// boundary vertex mask (2/3, 1/6, 1/6), keeps no corners, and needs a half-edge mesh ~3x the memory;
// tests compare the interior rules against OpenMesh on closed meshes.
#include <algorithm>

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

PolygonMesh subdivideCatmullClark(const PolygonMesh& mesh) {
  const size_t vertexCount = mesh.positions.size(), faceCount = mesh.faceCount();
  const size_t cornerCount = mesh.faceVertices.size();

  // Edge id of every corner (the edge from it to the next corner of its face).
  std::vector<std::pair<uint64_t, uint32_t>> edgeOfCorner(cornerCount);
  for (size_t f = 0; f < faceCount; f++) {
    uint32_t n = mesh.faceSize(f);
    for (uint32_t i = 0; i < n; i++) {
      uint32_t a = mesh.face(f)[i], b = mesh.face(f)[(i + 1) % n];
      edgeOfCorner[mesh.faceStart[f] + i] = {undirectedEdge(a, b), mesh.faceStart[f] + i};
    }
  }
  std::sort(edgeOfCorner.begin(), edgeOfCorner.end());
  std::vector<uint32_t> cornerEdge(cornerCount);
  std::vector<uint32_t> edgeFaces;  // faces on each edge: 1 (boundary) or 2
  std::vector<uint64_t> edgeKey;
  for (size_t i = 0; i < cornerCount; i++) {
    if (i == 0 || edgeOfCorner[i].first != edgeOfCorner[i - 1].first) {
      edgeKey.push_back(edgeOfCorner[i].first);
      edgeFaces.push_back(0);
    }
    edgeFaces.back()++;
    cornerEdge[edgeOfCorner[i].second] = uint32_t(edgeKey.size() - 1);
  }
  std::vector<std::pair<uint64_t, uint32_t>>().swap(edgeOfCorner);
  const size_t edgeCount = edgeKey.size();

  // Face points.
  std::vector<glm::dvec3> facePoint(faceCount);
  for (size_t f = 0; f < faceCount; f++) {
    glm::dvec3 sum(0.0);
    for (uint32_t i = 0; i < mesh.faceSize(f); i++) sum += glm::dvec3(mesh.positions[mesh.face(f)[i]]);
    facePoint[f] = sum / double(mesh.faceSize(f));
  }
  // Edge points: midpoint plus, inside, the two face points.
  std::vector<glm::dvec3> edgePoint(edgeCount, glm::dvec3(0.0));
  for (size_t e = 0; e < edgeCount; e++) {
    glm::dvec3 a(mesh.positions[edgeKey[e] >> 32]), b(mesh.positions[edgeKey[e] & 0xffffffffu]);
    edgePoint[e] = edgeFaces[e] == 1 ? (a + b) * 0.5 : (a + b) * 0.25;
  }
  for (size_t f = 0; f < faceCount; f++)
    for (uint32_t c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; c++)
      if (edgeFaces[cornerEdge[c]] == 2) edgePoint[cornerEdge[c]] += facePoint[f] * 0.25;

  // Vertex points. Interior: (Q + 2R + (n-3) V) / n with Q the mean of the face points, R the mean of
  // the edge midpoints, n the valence. Boundary: 3/4 V + 1/8 (A + B) over the two boundary neighbours.
  std::vector<glm::dvec3> sumFaces(vertexCount, glm::dvec3(0.0)), sumMid(vertexCount, glm::dvec3(0.0)),
      sumBoundary(vertexCount, glm::dvec3(0.0));
  std::vector<uint32_t> valence(vertexCount, 0), faces(vertexCount, 0), boundary(vertexCount, 0);
  for (size_t f = 0; f < faceCount; f++)
    for (uint32_t i = 0; i < mesh.faceSize(f); i++) {
      sumFaces[mesh.face(f)[i]] += facePoint[f];
      faces[mesh.face(f)[i]]++;
    }
  for (size_t e = 0; e < edgeCount; e++) {
    uint32_t a = uint32_t(edgeKey[e] >> 32), b = uint32_t(edgeKey[e] & 0xffffffffu);
    glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]);
    glm::dvec3 mid = (pa + pb) * 0.5;
    sumMid[a] += mid;
    sumMid[b] += mid;
    valence[a]++;
    valence[b]++;
    if (edgeFaces[e] == 1) {
      sumBoundary[a] += pb;
      sumBoundary[b] += pa;
      boundary[a]++;
      boundary[b]++;
    }
  }

  PolygonMesh out;
  out.positions.resize(vertexCount + edgeCount + faceCount);
  for (size_t v = 0; v < vertexCount; v++) {
    glm::dvec3 p(mesh.positions[v]);
    if (boundary[v] == 0 && valence[v] > 0) {
      double n = valence[v];
      p = (sumFaces[v] / double(faces[v]) + 2.0 * sumMid[v] / n + (n - 3.0) * p) / n;
    } else if (boundary[v] == 2 && faces[v] >= 2) {
      p = 0.75 * p + 0.125 * sumBoundary[v];
    }  // corners (one face) and unused vertices stay
    out.positions[v] = glm::vec3(p);
  }
  for (size_t e = 0; e < edgeCount; e++) out.positions[vertexCount + e] = glm::vec3(edgePoint[e]);
  for (size_t f = 0; f < faceCount; f++) out.positions[vertexCount + edgeCount + f] = glm::vec3(facePoint[f]);

  out.faceVertices.reserve(cornerCount * 4);
  out.faceStart.reserve(cornerCount + 1);
  for (size_t f = 0; f < faceCount; f++) {
    uint32_t n = mesh.faceSize(f), first = mesh.faceStart[f];
    for (uint32_t i = 0; i < n; i++) {
      uint32_t quad[4] = {mesh.face(f)[i], uint32_t(vertexCount + cornerEdge[first + i]),
                          uint32_t(vertexCount + edgeCount + f),
                          uint32_t(vertexCount + cornerEdge[first + (i + n - 1) % n])};
      out.addFace(quad, 4);
    }
  }
  return out;
}

}  // namespace vgeo
