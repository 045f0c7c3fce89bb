// shading_normals.cpp: the leaf mesh's shading normals as wedges (a vertex seen from one smooth side).
// A hard edge needs two normals at one position. The DAG is built on positions (a crease is no border
// to it), and each corner of a triangle then names a wedge: a vertex with one normal per smooth fan
// around it. Where the input gives normals (glTF NORMAL, OBJ vn, PLY nx ny nz), the corners of a
// vertex whose normals are equal (to the file's 32-bit octahedral encoding) share a wedge. Otherwise
// the corners of two faces that meet at an edge of the vertex join when the angle between the faces'
// normals is at most the crease angle (the usual "auto smooth" rule); a wedge's normal is the sum of
// its faces' area vectors. A crease angle of 180 degrees, or the limit normals of a subdivided cage,
// give one wedge a vertex. Coarser levels, whose triangles are new, take at each corner the wedge of
// that vertex whose normal is nearest their own face normal, so a box stays a box all the way up.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "../common/parallel.h"
#include "../common/vgeo_file.h"
#include "builder.h"
#include "union_find.h"

namespace vgeo {
namespace {

constexpr int kSerialNormalThreads = 2;  // vertexFaces costs a 2-thread build more than it saves

// Each vertex's faces' area vectors summed in face order, as one walk over the faces sums them. On
// more threads, the faces' area vectors are found first, and each vertex sums its own faces' from
// vertexFaces (made into `around`, which the leaf clusters' dual graph reads next): no thread writes
// where another does. Cutting the vertices into blocks, each walking a list of the faces that touch
// it, scaled 2x on 16 threads (three passes over the faces, few blocks); finding a face's area again
// at each of its corners took longer than the serial sums.
FillLaterVector<glm::vec3> faceSummedNormals(const PolygonMesh& mesh, int threads, VertexFaces* around) {
  const size_t vertexCount = mesh.positions.size(), faceCount = mesh.faceCount();
  if (threads <= kSerialNormalThreads) {
    FillLaterVector<glm::vec3> normals(vertexCount);
    std::vector<glm::dvec3> sums(vertexCount, glm::dvec3(0.0));
    for (size_t f = 0; f < faceCount; f++) {
      const glm::dvec3 n = mesh.areaVector(f);
      for (uint32_t k = 0; k < mesh.faceSize(f); k++) sums[mesh.face(f)[k]] += n;
    }
    for (size_t v = 0; v < vertexCount; v++) normals[v] = glm::vec3(sums[v]);
    return normals;
  }
  VertexFaces own;
  VertexFaces& faces = around ? *around : own;
  faces = vertexFaces(mesh.faceStart, mesh.faceVertices, vertexCount, threads);
  FillLaterVector<glm::dvec3> area(faceCount);
  parallelForRanges(faceCount, threads, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; f++) area[f] = mesh.areaVector(f);
  });
  FillLaterVector<glm::vec3> normals(vertexCount);
  parallelForRanges(vertexCount, threads, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; v++) {
      glm::dvec3 sum(0.0);
      for (size_t i = faces.start[v]; i < faces.start[v + 1]; i++) sum += area[faces.faces[i]];
      normals[v] = glm::vec3(sum);
    }
  });
  return normals;
}

void normalizeAll(FillLaterVector<glm::vec3>& normals, int threads) {
  parallelForRanges(normals.size(), threads, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; i++) {
      const float len = glm::length(normals[i]);
      normals[i] = len > 0.0f && std::isfinite(len) ? normals[i] / len : glm::vec3(0.0f, 0.0f, 1.0f);
    }
  });
}

}  // namespace

ShadingNormals shadingNormals(const PolygonMesh& mesh, std::span<const glm::vec3> vertexNormals,
                              float creaseAngleDegrees, int threads, VertexFaces* leafFaces) {
  ShadingNormals out;
  const size_t cornerCount = mesh.faceVertices.size(), vertexCount = mesh.positions.size();
  const bool given = vertexNormals.size() == vertexCount && vertexCount > 0;
  const bool fromInput = !given && mesh.cornerNormals.size() == cornerCount;
  if (given || (!fromInput && creaseAngleDegrees >= 180.0f)) {
    // One wedge a vertex, numbered as the vertices: nothing a corner to store. The arrays are written
    // on the threads (a large mesh's pages, first touched on one, took milliseconds).
    out.wedgeVertex.resize(vertexCount);
    out.wedgeStart.resize(vertexCount + 1);
    if (given) out.wedgeNormal.resize(vertexCount);
    parallelForRanges(vertexCount, threads, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; v++) {
        out.wedgeStart[v] = out.wedgeVertex[v] = uint32_t(v);
        if (given) out.wedgeNormal[v] = vertexNormals[v];
      }
    });
    out.wedgeStart[vertexCount] = uint32_t(vertexCount);
    if (!given) out.wedgeNormal = faceSummedNormals(mesh, threads, leafFaces);
    normalizeAll(out.wedgeNormal, threads);
    return out;
  }
  std::vector<uint32_t> cornerFace(cornerCount);
  std::vector<glm::dvec3> faceArea(mesh.faceCount());
  parallelForRanges(mesh.faceCount(), threads, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; f++) {
      for (uint32_t c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; c++) cornerFace[c] = uint32_t(f);
      faceArea[f] = mesh.areaVector(f);
    }
  });

  // Corners joined into wedges.
  UnionFind wedges(cornerCount, threads);
  if (fromInput) {
    // Equal encoded normals at one vertex share a wedge; an unusable normal takes its face's.
    std::vector<std::pair<uint64_t, uint32_t>> keys(cornerCount);
    parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; c++) {
        glm::vec3 n = mesh.cornerNormals[c];
        const float len = glm::length(n);
        if (!(len > 1e-12f) || !std::isfinite(len)) n = glm::vec3(faceArea[cornerFace[c]]);
        keys[c] = {uint64_t(mesh.faceVertices[c]) << 32 | encodeNormal(n), uint32_t(c)};
      }
    });
    parallelSort(keys, threads);
    parallelForRanges(keys.size(), threads, [&](size_t begin, size_t end) {
      for (size_t i = std::max<size_t>(begin, 1); i < end; i++)
        if (keys[i].first == keys[i - 1].first) wedges.unite(keys[i - 1].second, keys[i].second);
    });
  } else {
    // Across each edge v -> w of a face, the face holding w -> v joins its corner at v when the faces
    // meet at no more than the crease angle (and likewise at w, from that face's side).
    const double cosCrease = std::cos(double(creaseAngleDegrees) * 3.14159265358979323846 / 180.0);
    auto nextCorner = [&](uint32_t c) {
      return c + 1 == mesh.faceStart[cornerFace[c] + 1] ? mesh.faceStart[cornerFace[c]] : c + 1;
    };
    std::vector<std::pair<uint64_t, uint32_t>> directed(cornerCount);  // (v << 32 | w, corner at v)
    parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; c++)
        directed[c] = {uint64_t(mesh.faceVertices[c]) << 32 | mesh.faceVertices[nextCorner(uint32_t(c))], uint32_t(c)};
    });
    parallelSort(directed, threads);
    parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
      for (uint32_t c = uint32_t(begin); c < end; c++) {
        const uint32_t v = mesh.faceVertices[c], w = mesh.faceVertices[nextCorner(c)];
        auto it = std::lower_bound(directed.begin(), directed.end(),
                                   std::pair<uint64_t, uint32_t>(uint64_t(w) << 32 | v, 0u));
        if (it == directed.end() || it->first != (uint64_t(w) << 32 | v)) continue;  // a boundary edge
        const uint32_t other = it->second;  // the corner at w of the face across; its next corner is at v
        const glm::dvec3 a = faceArea[cornerFace[c]], b = faceArea[cornerFace[other]];
        const double la = glm::length(a), lb = glm::length(b);
        if (la > 0.0 && lb > 0.0 && glm::dot(a, b) < cosCrease * la * lb) continue;  // a crease
        wedges.unite(c, nextCorner(other));
      }
    });
  }

  // Wedges numbered by (vertex, first corner), so that one wedge a vertex numbers them as the vertices.
  std::vector<uint32_t> order(cornerCount);
  std::iota(order.begin(), order.end(), 0u);
  std::vector<uint32_t> root(cornerCount);
  parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; c++) root[c] = wedges.find(uint32_t(c));
  });
  parallelSort(order, threads, [&](uint32_t x, uint32_t y) {
    uint32_t vx = mesh.faceVertices[x], vy = mesh.faceVertices[y];
    return vx != vy ? vx < vy : root[x] != root[y] ? root[x] < root[y] : x < y;
  });
  out.cornerWedge.assign(cornerCount, UINT32_MAX);
  out.wedgeStart.assign(vertexCount + 1, 0);
  std::vector<glm::dvec3> sums;
  for (uint32_t i = 0; i < cornerCount; i++) {
    const uint32_t c = order[i];
    if (i == 0 || root[c] != root[order[i - 1]] || mesh.faceVertices[c] != mesh.faceVertices[order[i - 1]]) {
      out.wedgeVertex.push_back(mesh.faceVertices[c]);
      out.wedgeStart[mesh.faceVertices[c] + 1]++;
      sums.push_back(glm::dvec3(0.0));
    }
    const uint32_t w = uint32_t(out.wedgeVertex.size() - 1);
    out.cornerWedge[c] = w;
    sums[w] += faceArea[cornerFace[c]];
  }
  std::partial_sum(out.wedgeStart.begin(), out.wedgeStart.end(), out.wedgeStart.begin());
  out.wedgeNormal.resize(sums.size());
  for (size_t w = 0; w < sums.size(); w++) out.wedgeNormal[w] = glm::vec3(sums[w]);
  if (fromInput) {
    // The input's normal of each wedge's first corner (all its corners encode alike).
    std::vector<uint8_t> set(sums.size(), 0);
    for (uint32_t c = 0; c < cornerCount; c++) {
      const uint32_t w = out.cornerWedge[c];
      if (set[w]) continue;
      set[w] = 1;
      glm::vec3 n = mesh.cornerNormals[c];
      const float len = glm::length(n);
      out.wedgeNormal[w] = (len > 1e-12f && std::isfinite(len)) ? n : glm::vec3(faceArea[cornerFace[c]]);
    }
  }
  normalizeAll(out.wedgeNormal, threads);
  out.oneAVertex = true;
  for (size_t v = 0; v < vertexCount && out.oneAVertex; v++)
    out.oneAVertex = out.wedgeStart[v + 1] - out.wedgeStart[v] == 1;
  return out;
}

uint32_t ShadingNormals::nearestWedge(uint32_t vertex, glm::vec3 faceNormal) const {
  uint32_t best = wedgeStart[vertex];
  float bestDot = -INFINITY;
  for (uint32_t w = wedgeStart[vertex]; w < wedgeStart[vertex + 1]; w++) {
    const float d = glm::dot(wedgeNormal[w], faceNormal);
    if (d > bestDot) bestDot = d, best = w;
  }
  return best;
}

}  // namespace vgeo
