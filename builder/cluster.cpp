// cluster.cpp: faces or triangles into clusters of <= 128 triangles and <= 256 vertices.
// The graph is the dual mesh (faces sharing an edge), each face weighted by its triangle count, and
// partitionGraph cuts it by recursive bisection (partition.cpp). Leaf clusters are made of whole faces
// of the level-N cage, so a quad's two triangles never part and every patch belongs to one cluster.
#include <algorithm>
#include <span>

#include "../common/bucket_sort.h"
#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {

void triangulateQuad(const glm::vec3* positions, const uint32_t* v, uint32_t out[6]) {
  // Along the shorter diagonal.
  float d02 = glm::distance(positions[v[0]], positions[v[2]]), d13 = glm::distance(positions[v[1]], positions[v[3]]);
  const uint32_t pick[2][6] = {{0, 1, 2, 0, 2, 3}, {0, 1, 3, 1, 2, 3}};
  for (int i = 0; i < 6; i++) out[i] = v[pick[d13 < d02][i]];
}

void triangulateFace(const glm::vec3* positions, const uint32_t* v, uint32_t n, std::vector<uint32_t>& out) {
  if (n == 4) {
    uint32_t quad[6];
    triangulateQuad(positions, v, quad);
    out.insert(out.end(), quad, quad + 6);
    return;
  }
  for (uint32_t i = 1; i + 1 < n; i++) out.insert(out.end(), {v[0], v[i], v[i + 1]});
}

VertexFaces vertexFaces(std::span<const uint32_t> faceStart, std::span<const uint32_t> faceVertices, size_t vertexCount,
                        int threads) {
  VertexFaces out;
  const int vertexBits = bitsFor(std::max<size_t>(vertexCount, 1));
  out.faces = bucketSorted<uint32_t>(
      faceStart.size() - 1, vertexBits, vertexBits, threads,
      [&](size_t f, auto&& emit) {
        for (uint32_t c = faceStart[f]; c < faceStart[f + 1]; c++) emit(faceVertices[c], uint32_t(f));
      },
      std::less<uint32_t>(), &out.start);
  return out;
}

namespace {

constexpr size_t kSmallSoupFaces = 65536;  // smaller soups keep their scratch arrays for the next one

// The dual graph of a triangle soup, the same as dualGraph's below but found through lists of each
// vertex's edges (an edge listed at its lower vertex) in one pass on one thread. It serves every
// simplified group on its way to clusters, where dualGraph's sort of every vertex's faces cost several
// times the work itself, and a one-thread build's leaves (a third of dualGraph's time there). Returns
// false, leaving `g` alone, where an edge has more than two triangles or a triangle a repeated vertex
// (dualGraph keeps its own order of neighbours there). partner[c]: the other triangle's corner on
// corner c's edge (from c to the next corner), or UINT32_MAX where the edge has one triangle.
bool triangleDualGraph(std::span<const uint32_t> corners, size_t vertexCount, Graph& g,
                       std::vector<uint32_t>& partner) {
  const size_t faceCount = corners.size() / 3;
  constexpr uint32_t kNone = UINT32_MAX;
  // edgesAt[v]: the first corner of each edge whose lower vertex is v, linked through listed[c].next,
  // which holds the edge's upper vertex beside the link (a step along a list reads one entry).
  struct Listed {
    uint32_t next, upper;
  };
  thread_local std::vector<uint32_t> keptEdgesAt;
  thread_local std::vector<Listed> keptListed;
  std::vector<uint32_t> ownEdgesAt;
  std::vector<Listed> ownListed;
  const bool small = faceCount <= kSmallSoupFaces;
  std::vector<uint32_t>& edgesAt = small ? keptEdgesAt : ownEdgesAt;
  std::vector<Listed>& listed = small ? keptListed : ownListed;
  edgesAt.assign(vertexCount, kNone);
  listed.resize(corners.size());
  partner.assign(corners.size(), kNone);
  for (size_t t = 0; t < faceCount; t++)
    for (size_t k = 0; k < 3; k++) {
      const size_t c = 3 * t + k;
      const uint32_t a = corners[c], b = corners[k == 2 ? c - 2 : c + 1];  // the corner's edge's ends
      if (a == b) return false;
      const uint32_t low = std::min(a, b), high = std::max(a, b);
      uint32_t e = edgesAt[low];
      while (e != kNone && listed[e].upper != high) e = listed[e].next;
      if (e == kNone) {
        listed[c] = {edgesAt[low], high};
        edgesAt[low] = uint32_t(c);
      } else if (partner[e] == kNone) {
        partner[e] = uint32_t(c);
        partner[c] = e;
      } else {
        return false;  // a third triangle on the edge
      }
    }
  // A face's neighbours: the other triangle on each of its edges, in corner order.
  auto across = [&](size_t c) { return partner[c] == kNone ? kNone : partner[c] / 3; };
  g.offsets.resize(faceCount + 1);
  g.offsets[0] = 0;
  for (size_t f = 0; f < faceCount; f++)
    g.offsets[f + 1] =
        g.offsets[f] + (across(3 * f) != kNone) + (across(3 * f + 1) != kNone) + (across(3 * f + 2) != kNone);
  g.adjacency.resize(g.offsets[faceCount]);
  for (size_t c = 0, at = 0; c < corners.size(); c++)
    if (const uint32_t o = across(c); o != kNone) g.adjacency[at++] = o;
  return true;
}

// Faces sharing an edge are neighbours (all of them, should an edge have more than two faces). Found
// through each vertex's faces rather than by sorting edges: linear, ~3x faster on large meshes, and
// every pass parallel over faces. `given`: the faces' vertexFaces when made already (taken over).
Graph dualGraph(std::span<const uint32_t> faceStart, std::span<const uint32_t> faceVertices, size_t vertexCount,
                int threads, VertexFaces* given) {
  const size_t faceCount = faceStart.size() - 1;
  const VertexFaces around =
      given && !given->start.empty() ? std::move(*given) : vertexFaces(faceStart, faceVertices, vertexCount, threads);
  const bool triangles = faceVertices.size() == 3 * faceCount;  // then face f's corners are 3f..3f+2
  auto hasVertex = [&](uint32_t f, uint32_t v) -> bool {
    if (triangles) {
      const uint32_t* c = &faceVertices[3 * size_t(f)];
      return (c[0] == v) | (c[1] == v) | (c[2] == v);
    }
    for (uint32_t c = faceStart[f]; c < faceStart[f + 1]; c++)
      if (faceVertices[c] == v) return true;
    return false;
  };
  // Each face writes its neighbours into a slot per corner edge (one neighbour an edge on a manifold
  // mesh); faces with an edge of several neighbours are listed apart, a chunk's in face order.
  const uint32_t kNone = UINT32_MAX;
  FillLaterVector<uint32_t> slots = parallelFilled(faceVertices.size(), kNone, threads);
  const size_t chunk = 4096, chunks = (faceCount + chunk - 1) / chunk;
  auto chunkFaces = [&](size_t ch) {
    return std::pair<uint32_t, uint32_t>(uint32_t(ch * chunk), uint32_t(std::min(faceCount, (ch + 1) * chunk)));
  };
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> extraByChunk(chunks);
  parallelFor(chunks, threads, [&](size_t ch) {
    for (uint32_t f = chunkFaces(ch).first; f < chunkFaces(ch).second; f++) {
      uint32_t n = faceStart[f + 1] - faceStart[f];
      for (uint32_t i = 0; i < n; i++) {
        uint32_t a = faceVertices[faceStart[f] + i], b = faceVertices[faceStart[f] + (i + 1) % n];
        for (size_t k = around.start[a]; k < around.start[a + 1]; k++) {
          uint32_t other = around.faces[k];
          if (other == f || !hasVertex(other, b)) continue;
          uint32_t& slot = slots[faceStart[f] + i];
          if (slot == kNone)
            slot = other;
          else
            extraByChunk[ch].push_back({f, other});
        }
      }
    }
  });
  // A face's neighbours: its slots' in corner order, then its extra ones.
  auto forNeighbours = [&](size_t ch, auto&& visit) {
    size_t e = 0;
    const auto& extra = extraByChunk[ch];
    for (uint32_t f = chunkFaces(ch).first; f < chunkFaces(ch).second; f++) {
      for (uint32_t c = faceStart[f]; c < faceStart[f + 1]; c++)
        if (slots[c] != kNone) visit(f, slots[c]);
      for (; e < extra.size() && extra[e].first == f; e++) visit(f, extra[e].second);
    }
  };
  Graph g;
  g.offsets = parallelFilled(faceCount + 1, 0u, threads);
  parallelFor(chunks, threads,
              [&](size_t ch) { forNeighbours(ch, [&](uint32_t f, uint32_t) { g.offsets[f + 1]++; }); });
  parallelPrefix(
      faceCount, threads, [&](size_t f) { return g.offsets[f + 1]; }, [](size_t) {},
      [&](size_t f, size_t before, size_t count) { g.offsets[f + 1] = uint32_t(before + count); });
  g.adjacency.resize(g.offsets.back());
  parallelFor(chunks, threads, [&](size_t ch) {
    uint32_t filled = 0, face = kNone;
    forNeighbours(ch, [&](uint32_t f, uint32_t other) {
      if (f != face) face = f, filled = 0;
      g.adjacency[g.offsets[f] + filled++] = other;
    });
  });
  return g;
}

// True when the faces use at most VGEO_MAX_CLUSTER_VERTICES distinct vertices. They are counted in a
// small open-addressing table per thread, twice the corners' size, not in an array over all vertex
// ids: on a large mesh every mark in such an array missed the cache. The count stops past the limit.
bool fitsVertexLimit(std::span<const uint32_t> faceStart, std::span<const uint32_t> faceVertices, const uint32_t* faces,
                     size_t count) {
  size_t corners = 0;
  for (size_t i = 0; i < count; i++) corners += faceStart[faces[i] + 1] - faceStart[faces[i]];
  if (corners <= VGEO_MAX_CLUSTER_VERTICES) return true;
  thread_local std::vector<uint32_t> table;
  const int bits = bitsFor(2 * corners);
  table.assign(size_t(1) << bits, UINT32_MAX);
  const uint32_t mask = (1u << bits) - 1;
  size_t distinct = 0;
  for (size_t i = 0; i < count; i++)
    for (uint32_t c = faceStart[faces[i]]; c < faceStart[faces[i] + 1]; c++) {
      const uint32_t v = faceVertices[c];
      uint32_t slot = (v * 0x9e3779b1u) >> (32 - bits);
      while (table[slot] != UINT32_MAX && table[slot] != v) slot = (slot + 1) & mask;
      if (table[slot] == v) continue;
      table[slot] = v;
      if (++distinct > VGEO_MAX_CLUSTER_VERTICES) return false;
    }
  return true;
}

// `wedges`, when given (one a corner, like faceVertices), are what the vertex limit counts, and each
// cluster lists those of its triangles' corners. `around`: the faces' vertexFaces when made already.
// With `findBorders`, each cluster's border is found too, in the ids of faceVertices and in no order
// (the caller renumbers and sorts it); leaves go without (grouping counts theirs), so that they are
// not held from the leaves' making through the first round's peak.
std::vector<BuildCluster> clustersFromFaces(std::span<const uint32_t> faceStart, std::span<const uint32_t> faceVertices,
                                            const std::vector<glm::vec3>& positions, int threads, bool keepFaces,
                                            bool findBorders, uint32_t targetTriangles,
                                            const std::vector<uint32_t>* wedges, VertexFaces* around = nullptr) {
  const size_t faceCount = faceStart.size() - 1;
  // A soup's partner corners, where its graph was found through them: each cluster's border is then
  // read off them instead of counted again.
  thread_local std::vector<uint32_t> keptPartner;
  std::vector<uint32_t> ownPartner;
  std::vector<uint32_t>& partner = faceCount <= kSmallSoupFaces ? keptPartner : ownPartner;
  bool paired = false;
  Partition parts;
  {  // the graph and its node data are freed before the clusters are made
    Graph graph;
    const bool listed = faceVertices.size() == 3 * faceCount && (faceCount <= kSmallSoupFaces || threads <= 1);
    paired = listed && triangleDualGraph(faceVertices, positions.size(), graph, partner);
    if (!paired) graph = dualGraph(faceStart, faceVertices, positions.size(), threads, around);
    // A large soup's partner corners (12 bytes a triangle) are freed here where no border is wanted.
    if (!findBorders) std::vector<uint32_t>().swap(ownPartner);
    if (around) *around = VertexFaces();  // freed, unused by the soup's lists
    std::vector<uint8_t> weights(faceCount);
    FillLaterVector<glm::vec3> centroids(faceCount);
    parallelForRanges(faceCount, threads, [&](size_t begin, size_t end) {
      for (size_t f = begin; f < end; f++) {
        uint32_t n = faceStart[f + 1] - faceStart[f];
        weights[f] = uint8_t(n - 2);
        glm::vec3 sum(0.0f);
        for (uint32_t c = faceStart[f]; c < faceStart[f + 1]; c++) sum += positions[faceVertices[c]];
        centroids[f] = sum / float(n);
      }
    });
    const std::span<const uint32_t> limited = wedges ? std::span<const uint32_t>(*wedges) : faceVertices;
    auto fits = [&](const uint32_t* faces, size_t count) { return fitsVertexLimit(faceStart, limited, faces, count); };
    parts = partitionGraph(graph, weights, centroids, VGEO_MAX_CLUSTER_TRIANGLES, targetTriangles, threads, fits);
  }
  std::vector<uint32_t> partOf(findBorders && paired ? faceCount : 0);
  if (!partOf.empty())
    parallelFor(parts.partCount(), threads, [&](size_t p) {
      for (uint32_t i = parts.partStart[p]; i < parts.partStart[p + 1]; i++) partOf[parts.order[i]] = uint32_t(p);
    });
  std::vector<BuildCluster> clusters(parts.partCount());
  parallelFor(parts.partCount(), threads, [&](size_t p) {
    BuildCluster& c = clusters[p];
    size_t corners = 0;  // of the part's triangles: its arrays are allocated once, at their size
    for (uint32_t i = parts.partStart[p]; i < parts.partStart[p + 1]; i++)
      corners += 3 * (faceStart[parts.order[i] + 1] - faceStart[parts.order[i]] - 2);
    c.indices.reserve(corners);
    if (keepFaces) c.cageFaces.reserve(parts.partStart[p + 1] - parts.partStart[p]);
    if (wedges) c.wedges.reserve(corners);
    for (uint32_t i = parts.partStart[p]; i < parts.partStart[p + 1]; i++) {
      uint32_t f = parts.order[i];
      const size_t first = c.indices.size();
      triangulateFace(positions.data(), &faceVertices[faceStart[f]], faceStart[f + 1] - faceStart[f], c.indices);
      if (keepFaces) c.cageFaces.push_back(f);
      if (!wedges) continue;
      for (size_t k = first; k < c.indices.size(); k++) {  // the corner of the face at that vertex
        uint32_t corner = faceStart[f];
        while (faceVertices[corner] != c.indices[k]) corner++;
        c.wedges.push_back((*wedges)[corner]);
      }
    }
    if (!findBorders) return;
    if (!paired) {
      c.border = edgesUsedOnce(c.indices);
      return;
    }
    // A triangle's edge is on the border where no triangle of the cluster is across it.
    for (uint32_t i = parts.partStart[p]; i < parts.partStart[p + 1]; i++)
      for (uint32_t k = 0, t = parts.order[i]; k < 3; k++) {
        const uint32_t corner = 3 * t + k, across = partner[corner];
        if (across != UINT32_MAX && partOf[across / 3] == p) continue;
        const uint32_t a = faceVertices[corner], b = faceVertices[k == 2 ? corner - 2 : corner + 1];
        c.border.push_back(undirectedEdge(a, b));
      }
  });
  return clusters;
}

// Whether a face of `mesh` has more than kMaxLeafFaceCorners corners, looked for on the threads.
bool hasLargeFace(const PolygonMesh& mesh, int threads) {
  bool found = false;
  parallelForRanges(mesh.faceCount(), threads, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; f++)
      if (mesh.faceSize(f) > kMaxLeafFaceCorners) {
        __atomic_store_n(&found, true, __ATOMIC_RELAXED);
        return;
      }
  });
  return found;
}

}  // namespace

void triangulateLargeFaces(PolygonMesh& mesh, int threads) {
  if (!hasLargeFace(mesh, threads)) return;
  PolygonMesh split;
  split.positions = std::move(mesh.positions);
  for (size_t f = 0; f < mesh.faceCount(); f++) {
    if (mesh.faceSize(f) <= kMaxLeafFaceCorners) {
      split.addFace(mesh.face(f), mesh.faceSize(f), mesh.faceNormals(f));
      continue;
    }
    // A zigzag strip from both ends, not a fan: a fan puts every triangle on its first corner, and the
    // dual graph, found through each vertex's faces, took quadratic time there (a 150,000-corner
    // polygon: 30 s). In the strip no corner has more than four triangles.
    const uint32_t* v = mesh.face(f);
    const glm::vec3* n = mesh.faceNormals(f);
    auto triangle = [&](uint32_t a, uint32_t b, uint32_t c) {
      const uint32_t t[3] = {v[a], v[b], v[c]};
      glm::vec3 tn[3];
      if (n) tn[0] = n[a], tn[1] = n[b], tn[2] = n[c];
      split.addFace(t, 3, n ? tn : nullptr);
    };
    for (uint32_t a = 0, b = mesh.faceSize(f) - 1, left = 1; b - a >= 2; left ^= 1) {
      if (left)
        triangle(a, a + 1, b), a++;
      else
        triangle(a, b - 1, b), b--;
    }
  }
  mesh = std::move(split);
}

std::vector<BuildCluster> buildLeafClusters(const PolygonMesh& mesh, int threads, const ShadingNormals* shading,
                                            VertexFaces* around) {
  if (hasLargeFace(mesh, threads)) throw std::logic_error("buildLeafClusters: call triangulateLargeFaces first");
  const bool hardEdges = shading && !shading->oneAVertex;
  return clustersFromFaces(mesh.faceStart, mesh.faceVertices, mesh.positions, threads, true, false, kClusterFill,
                           hardEdges ? &shading->cornerWedge : nullptr, around);
}

std::vector<BuildCluster> splitIntoClusters(const SimplifiedGroup& group, const std::vector<glm::vec3>& positions,
                                            const ShadingNormals* shading) {
  // The group's own vertex ids: the adjacency arrays are sized by the vertex count.
  const std::vector<uint32_t>&local = group.indices, &globals = group.globals;
  std::vector<glm::vec3> points(globals.size());
  for (size_t i = 0; i < globals.size(); i++) points[i] = positions[globals[i]];
  std::vector<uint32_t> faceStart(local.size() / 3 + 1);
  for (size_t i = 0; i < faceStart.size(); i++) faceStart[i] = uint32_t(3 * i);
  std::vector<uint32_t> wedges;
  if (shading && !shading->oneAVertex) {
    wedges.resize(local.size());
    for (size_t t = 0; t + 2 < local.size(); t += 3) {
      const glm::vec3 &a = points[local[t]], &b = points[local[t + 1]], &d = points[local[t + 2]];
      const glm::vec3 normal = glm::cross(b - a, d - a);
      for (size_t k = 0; k < 3; k++) wedges[t + k] = shading->nearestWedge(globals[local[t + k]], normal);
    }
  }
  std::vector<BuildCluster> clusters =
      clustersFromFaces(faceStart, local, points, 1, false, true, kClusterFill, wedges.empty() ? nullptr : &wedges);
  for (BuildCluster& c : clusters) {
    for (uint32_t& v : c.indices) v = globals[v];
    for (uint64_t& edge : c.border) {
      const uint32_t a = globals[edge >> 32], b = globals[edge & 0xffffffffu];
      edge = undirectedEdge(a, b);
    }
    std::sort(c.border.begin(), c.border.end());
  }
  return clusters;
}

}  // namespace vgeo
