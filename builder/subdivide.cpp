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

PolygonMesh subdivideCatmullClark(const PolygonMesh& mesh, int threads, size_t vertexPoints) {
  const size_t vertexCount = mesh.positions.size(), faceCount = mesh.faceCount();
  const size_t cornerCount = mesh.faceVertices.size();
  vertexPoints = std::min(vertexPoints, vertexCount);

  // Each vertex's corners (in corner order) and each corner's face.
  FillLaterVector<uint32_t> cornerStart, cornersAt;
  cornersByVertex(mesh.faceVertices, vertexCount, threads, cornerStart, cornersAt);
  FillLaterVector<uint32_t> faceOf(cornerCount);
  parallelFor(faceCount, threads, [&](size_t f) {
    for (uint32_t c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; c++) faceOf[c] = uint32_t(f);
  });
  // Vertex v's edges: its neighbours ascending (the order of the edges' numbers, which follow their
  // keys min << 32 | max), each beside every corner on the edge in corner order. A corner is on the
  // edge to the next corner of its face.
  auto edgesAt = [&](size_t v, std::vector<std::pair<uint32_t, uint32_t>>& edges) {
    edges.clear();
    for (uint32_t k = cornerStart[v]; k < cornerStart[v + 1]; k++) {
      const uint32_t c = cornersAt[k], f = faceOf[c], first = mesh.faceStart[f], end = mesh.faceStart[f + 1];
      const uint32_t before = c == first ? end - 1 : c - 1;
      edges.push_back({mesh.faceVertices[c + 1 == end ? first : c + 1], c});
      edges.push_back({mesh.faceVertices[before], before});
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());  // a corner twice: a repeated vertex
  };

  // Face points.
  FillLaterVector<glm::dvec3> facePoint(faceCount);
  parallelFor(faceCount, threads, [&](size_t f) {
    glm::dvec3 sum(0.0);
    for (uint32_t i = 0; i < mesh.faceSize(f); i++) sum += glm::dvec3(mesh.positions[mesh.face(f)[i]]);
    facePoint[f] = sum / double(mesh.faceSize(f));
  });

  // Edges are numbered by their lower vertex, in its neighbours' order; then each vertex numbers its
  // edges and makes their edge points (midpoint plus, inside, the two face points in corner order) and
  // its own vertex point. Interior: (Q + 2R + (n-3) V) / n with Q the mean of the face points, R the
  // mean of the edge midpoints, n the valence. Boundary: 3/4 V + 1/8 (A + B) over the two boundary
  // neighbours. Its faces are added in face order, its edges in edge order.
  FillLaterVector<uint32_t> edgesOwned(vertexCount);
  parallelForRanges(
      vertexCount, threads,
      [&](size_t begin, size_t end) {
        std::vector<std::pair<uint32_t, uint32_t>> edges;
        for (size_t v = begin; v < end; v++) {
          edgesAt(v, edges);
          uint32_t owned = 0;
          for (size_t i = 0; i < edges.size(); i++)
            owned += edges[i].first >= v && (i == 0 || edges[i - 1].first != edges[i].first);
          edgesOwned[v] = owned;
        }
      },
      kHeavyRange);
  PolygonMesh out;
  FillLaterVector<uint32_t> cornerEdge(cornerCount);
  const size_t edgeCount = parallelPrefix(
      vertexCount, threads, [&](size_t v) { return edgesOwned[v]; },
      [&](size_t total) { out.positions.resize(vertexCount + total + faceCount); },
      [&](size_t v, size_t firstEdge, size_t) {
        // Per thread: visit makes no parallel call, so no other visit runs on this thread meanwhile.
        static thread_local std::vector<std::pair<uint32_t, uint32_t>> edges;
        edgesAt(v, edges);
        const glm::dvec3 p(mesh.positions[v]);
        glm::dvec3 sumFaces(0.0), sumMid(0.0), sumBoundary(0.0);
        uint32_t boundary = 0, valence = 0;
        size_t e = firstEdge;
        for (size_t i = 0, next; i < edges.size(); i = next) {
          const uint32_t b = edges[i].first;
          for (next = i + 1; next < edges.size() && edges[next].first == b; next++) {
          }
          const glm::dvec3 low(mesh.positions[std::min<size_t>(v, b)]), high(mesh.positions[std::max<size_t>(v, b)]);
          const bool open = next - i == 1;
          valence++;
          sumMid += (low + high) * 0.5;
          if (open) {
            sumBoundary += glm::dvec3(mesh.positions[b]);
            boundary++;
          }
          if (b < v) continue;  // numbered by b
          for (size_t k = i; k < next; k++) cornerEdge[edges[k].second] = uint32_t(e);
          glm::dvec3 point = open ? (low + high) * 0.5 : (low + high) * 0.25;
          if (next - i == 2)
            for (size_t k = i; k < next; k++) point += facePoint[faceOf[edges[k].second]] * 0.25;
          out.positions[vertexCount + e++] = glm::vec3(point);
        }
        if (v >= vertexPoints) {
          out.positions[v] = mesh.positions[v];
          return;
        }
        for (uint32_t k = cornerStart[v]; k < cornerStart[v + 1]; k++) sumFaces += facePoint[faceOf[cornersAt[k]]];
        const size_t faces = cornerStart[v + 1] - cornerStart[v];
        glm::dvec3 q = p;
        if (boundary == 0 && valence > 0) {
          double n = double(valence);
          q = (sumFaces / double(faces) + 2.0 * sumMid / n + (n - 3.0) * p) / n;
        } else if (boundary == 2 && faces >= 2) {
          q = 0.75 * p + 0.125 * sumBoundary;
        }  // corners (one face) and unused vertices stay
        out.positions[v] = glm::vec3(q);
      },
      kHeavyRange);
  FillLaterVector<uint32_t>().swap(faceOf);
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
