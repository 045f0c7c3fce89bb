// cluster.cpp: faces or triangles into clusters of <= 128 triangles and <= 256 vertices.
// The graph is the dual mesh (faces sharing an edge), each face weighted by its triangle count, and
// partitionGraph cuts it by recursive bisection (partition.cpp). Leaf clusters are made of whole faces
// of the level-N cage, so a quad's two triangles never part and every patch belongs to one cluster.
#include <algorithm>

#include "builder.h"

namespace vgeo {
namespace {

// Faces sharing an edge are neighbours; an edge with more than two faces links consecutive ones.
Graph dualGraph(const std::vector<uint32_t>& faceStart, const std::vector<uint32_t>& faceVertices) {
  const size_t faceCount = faceStart.size() - 1;
  std::vector<std::pair<uint64_t, uint32_t>> edges;
  edges.reserve(faceVertices.size());
  for (size_t f = 0; f < faceCount; f++) {
    uint32_t n = faceStart[f + 1] - faceStart[f];
    const uint32_t* v = &faceVertices[faceStart[f]];
    for (uint32_t i = 0; i < n; i++) {
      uint32_t a = v[i], b = v[(i + 1) % n];
      edges.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), uint32_t(f)});
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<uint32_t> degree(faceCount, 0);
  std::vector<std::pair<uint32_t, uint32_t>> links;
  for (size_t i = 0; i + 1 < edges.size(); i++)
    if (edges[i].first == edges[i + 1].first && edges[i].second != edges[i + 1].second) {
      links.push_back({edges[i].second, edges[i + 1].second});
      degree[edges[i].second]++;
      degree[edges[i + 1].second]++;
    }
  Graph g;
  g.offsets.resize(faceCount + 1, 0);
  for (size_t f = 0; f < faceCount; f++) g.offsets[f + 1] = g.offsets[f] + degree[f];
  g.adjacency.resize(g.offsets.back());
  std::vector<uint32_t> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (auto [a, b] : links) {
    g.adjacency[fill[a]++] = b;
    g.adjacency[fill[b]++] = a;
  }
  return g;
}

// True when the faces use at most VGEO_MAX_CLUSTER_VERTICES distinct vertices.
bool fitsVertexLimit(const std::vector<uint32_t>& faceStart, const std::vector<uint32_t>& faceVertices, const uint32_t* faces, size_t count) {
  thread_local std::vector<uint32_t> vertices;
  vertices.clear();
  for (size_t i = 0; i < count; i++)
    for (uint32_t c = faceStart[faces[i]]; c < faceStart[faces[i] + 1]; c++) vertices.push_back(faceVertices[c]);
  if (vertices.size() <= VGEO_MAX_CLUSTER_VERTICES) return true;
  std::sort(vertices.begin(), vertices.end());
  return size_t(std::unique(vertices.begin(), vertices.end()) - vertices.begin()) <= VGEO_MAX_CLUSTER_VERTICES;
}

void triangulateFace(const glm::vec3* positions, const uint32_t* v, uint32_t n, std::vector<uint32_t>& out) {
  if (n == 4) {
    // Split a quad along its shorter diagonal.
    float d02 = glm::distance(positions[v[0]], positions[v[2]]), d13 = glm::distance(positions[v[1]], positions[v[3]]);
    if (d13 < d02) out.insert(out.end(), {v[0], v[1], v[3], v[1], v[2], v[3]});
    else out.insert(out.end(), {v[0], v[1], v[2], v[0], v[2], v[3]});
    return;
  }
  for (uint32_t i = 1; i + 1 < n; i++) out.insert(out.end(), {v[0], v[i], v[i + 1]});
}

std::vector<BuildCluster> clustersFromFaces(const std::vector<uint32_t>& faceStart, const std::vector<uint32_t>& faceVertices,
                                            const std::vector<glm::vec3>& positions, int threads, bool keepFaces,
                                            uint32_t targetTriangles) {
  const size_t faceCount = faceStart.size() - 1;
  Graph graph = dualGraph(faceStart, faceVertices);
  std::vector<uint8_t> weights(faceCount);
  std::vector<glm::vec3> centroids(faceCount);
  for (size_t f = 0; f < faceCount; f++) {
    uint32_t n = faceStart[f + 1] - faceStart[f];
    weights[f] = uint8_t(n - 2);
    glm::vec3 sum(0.0f);
    for (uint32_t c = faceStart[f]; c < faceStart[f + 1]; c++) sum += positions[faceVertices[c]];
    centroids[f] = sum / float(n);
  }
  auto fits = [&](const uint32_t* faces, size_t count) { return fitsVertexLimit(faceStart, faceVertices, faces, count); };
  Partition parts = partitionGraph(graph, weights, centroids, VGEO_MAX_CLUSTER_TRIANGLES, targetTriangles, threads, fits);
  std::vector<BuildCluster> clusters(parts.partCount());
  for (size_t p = 0; p < parts.partCount(); p++) {
    BuildCluster& c = clusters[p];
    for (uint32_t i = parts.partStart[p]; i < parts.partStart[p + 1]; i++) {
      uint32_t f = parts.order[i];
      triangulateFace(positions.data(), &faceVertices[faceStart[f]], faceStart[f + 1] - faceStart[f], c.indices);
      if (keepFaces) c.cageFaces.push_back(f);
    }
  }
  return clusters;
}

}  // namespace

void fanLargeFaces(PolygonMesh& mesh) {
  bool needsFan = false;
  for (size_t f = 0; f < mesh.faceCount() && !needsFan; f++) needsFan = mesh.faceSize(f) > kMaxLeafFaceCorners;
  if (!needsFan) return;
  PolygonMesh fanned;
  fanned.positions = std::move(mesh.positions);
  for (size_t f = 0; f < mesh.faceCount(); f++) {
    if (mesh.faceSize(f) <= kMaxLeafFaceCorners) {
      fanned.addFace(mesh.face(f), mesh.faceSize(f));
      continue;
    }
    for (uint32_t i = 1; i + 1 < mesh.faceSize(f); i++) {
      uint32_t t[3] = {mesh.face(f)[0], mesh.face(f)[i], mesh.face(f)[i + 1]};
      fanned.addFace(t, 3);
    }
  }
  mesh = std::move(fanned);
}

std::vector<BuildCluster> buildLeafClusters(const PolygonMesh& mesh, int threads) {
  for (size_t f = 0; f < mesh.faceCount(); f++)
    if (mesh.faceSize(f) > kMaxLeafFaceCorners) throw std::logic_error("buildLeafClusters: call fanLargeFaces first");
  // Leaves: nearly full clusters (the builder's promise is >= 124 triangles on average), with a little
  // room left for merging cut-off pieces.
  return clustersFromFaces(mesh.faceStart, mesh.faceVertices, mesh.positions, threads, true, 126);
}

std::vector<BuildCluster> splitIntoClusters(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions) {
  std::vector<uint32_t> faceStart(indices.size() / 3 + 1);
  for (size_t i = 0; i < faceStart.size(); i++) faceStart[i] = uint32_t(3 * i);
  // Simplified groups have a fine border ring around coarse insides, which cuts pieces off easily:
  // leave more room for merging them back.
  return clustersFromFaces(faceStart, indices, positions, 1, false, 120);
}

}  // namespace vgeo
