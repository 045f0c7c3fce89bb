// layout.cpp: lays a DAG out as the renderer's buffers (a geometry of a VgeoData).
// Groups are stored in BVH leaf order, so a leaf node's groups are one run; clusters in group order, so a
// group's members are one run; leaf clusters' cage faces in cluster order, so a leaf's faces are one run.
// Each cluster lists its distinct vertices once (absolute indices) and its triangles as 8-bit local
// indices: the meshlet layout, which lets a pass read any cluster without a second index buffer.
#include <algorithm>

#include "../common/parallel.h"
#include "builder.h"
#include "layout.h"

#include <memory>

namespace vgeo {
namespace {

// The cone of a cluster's triangle normals (shaderio.h, clusterFacesAway): axis the normalised mean of
// the unit normals, w the sine of the widest angle from it, -1 when that angle reaches 90 degrees.
glm::vec4 normalCone(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions) {
  std::vector<glm::dvec3> normals;
  glm::dvec3 sum(0.0);
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    glm::dvec3 a(positions[indices[t]]), b(positions[indices[t + 1]]), c(positions[indices[t + 2]]);
    glm::dvec3 n = glm::cross(b - a, c - a);
    double len = glm::length(n);
    if (len == 0.0) continue;  // degenerate: faces nowhere, culling it is harmless
    normals.push_back(n / len);
    sum += n / len;
  }
  double len = glm::length(sum);
  if (normals.empty() || len < 1e-9) return glm::vec4(0.0f, 0.0f, 1.0f, -1.0f);
  glm::dvec3 axis = sum / len;
  double minCos = 1.0;
  for (const auto& n : normals) minCos = std::min(minCos, glm::dot(axis, n));
  if (minCos <= 0.02) return glm::vec4(glm::vec3(axis), -1.0f);
  double sine = std::sqrt(std::max(0.0, 1.0 - minCos * minCos));
  // Rounded up a little so that float tests never cull a cluster that has a triangle facing the eye.
  return glm::vec4(glm::vec3(axis), float(std::min(1.0, sine * 1.0001 + 1e-6)));
}

}  // namespace

void appendGeometry(VgeoData& file, const Dag& dag, const PolygonMesh& leafMesh, const ShadingNormals& shading,
                    MeshPatches&& patches, const std::vector<PatchErrors>& patchErrors, bool closed, int threads) {
  Bvh bvh = buildBvh(dag.groups);
  // Each cluster's normal cone and the sphere of its own vertices (a leaf's is its self sphere): apart
  // from the serial layout below, since CGAL's exact sphere is the layout's costliest step.
  std::vector<shaderio::ClusterCone> cones(dag.clusters.size());
  parallelFor(dag.clusters.size(), threads, [&](size_t id) {
    const BuildCluster& c = dag.clusters[id];
    cones[id].cone = normalCone(c.indices, leafMesh.positions);
    if (c.level == 0) {
      cones[id].sphere = c.selfSphere;
      return;
    }
    std::vector<uint32_t> vertices, local;
    localIds(c.wedges.empty() ? c.indices : c.wedges, vertices, local);
    for (uint32_t& v : vertices) v = shading.wedgeVertex[v];  // the wedges' positions
    cones[id].sphere = sphereOfPoints(leafMesh.positions, vertices.data(), vertices.size());
  });
  const uint32_t vertexOffset = uint32_t(file.vertexCount()), clusterOffset = uint32_t(file.clusters.size()),
                 groupOffset = uint32_t(file.groups.size()), nodeOffset = uint32_t(file.nodes.size()),
                 cageOffset = uint32_t(file.cageFaces.size());

  std::vector<uint32_t> groupIndex(dag.groups.size());
  for (uint32_t i = 0; i < bvh.groupOrder.size(); i++) groupIndex[bvh.groupOrder[i]] = groupOffset + i;
  std::vector<uint32_t> clusterOrder, clusterIndex(dag.clusters.size(), UINT32_MAX);
  for (uint32_t g : bvh.groupOrder)
    for (uint32_t m : dag.groups[g].members) {
      clusterIndex[m] = clusterOffset + uint32_t(clusterOrder.size());
      clusterOrder.push_back(m);
    }
  if (clusterOrder.size() != dag.clusters.size())
    throw std::logic_error("appendGeometry: a cluster belongs to no group");
  // Exact room up front: growth by doubling left up to twice the largest arrays allocated at once, the
  // build's peak memory.
  size_t triangles = 0, faces = 0;
  for (const BuildCluster& c : dag.clusters) triangles += c.indices.size() / 3, faces += c.cageFaces.size();
  const size_t vertices = shading.wedgeVertex.size();
  file.positions.reserve(file.positions.size() + 3 * vertices);
  file.controlPoints.reserve(file.controlPoints.size() + 3 * patches.points.size());
  file.normals.reserve(file.normals.size() + vertices);
  file.clusterTriangles.reserve(file.clusterTriangles.size() + triangles);
  file.clusterVertices.reserve(file.clusterVertices.size() + 3 * triangles / 2 + 2 * dag.clusters.size());
  file.clusters.reserve(file.clusters.size() + dag.clusters.size());
  file.clusterCones.reserve(file.clusterCones.size() + dag.clusters.size());
  file.cageFaces.reserve(file.cageFaces.size() + faces);
  file.patches.reserve(file.patches.size() + faces);
  file.cageFaceVertices.reserve(file.cageFaceVertices.size() + 4 * faces);

  // Vertices: one a wedge (shading_normals.cpp), which is one a leaf vertex unless the mesh has hard edges.
  for (size_t w = 0; w < vertices; w++) {
    const glm::vec3& p = leafMesh.positions[shading.wedgeVertex[w]];
    file.positions.insert(file.positions.end(), {p.x, p.y, p.z});
    file.normals.push_back(encodeNormal(shading.wedgeNormal[w]));
  }

  // One patch per face of the cage (its words verbatim: control-point indices relative to the
  // geometry's first control point). Neighbours name faces by their index in the file, whose order
  // (cluster order) is known first; an edge is locked at factor 1 where the face on its other side
  // belongs to another level-0 group (which may be drawn coarser) or is flat.
  const uint32_t pointBase = uint32_t(file.controlPoints.size() / 3);
  for (const glm::vec3& p : patches.points) file.controlPoints.insert(file.controlPoints.end(), {p.x, p.y, p.z});
  std::vector<glm::vec3>().swap(patches.points);
  // The words keep the mesh's face order (a patch names its first word): moved, not copied, into an
  // empty file, so the layout's peak memory holds them once.
  const uint32_t wordBase = uint32_t(file.patchPoints.size());
  if (file.patchPoints.empty()) {
    file.patchPoints = std::move(patches.words);
  } else {
    file.patchPoints.insert(file.patchPoints.end(), patches.words.begin(), patches.words.end());
    std::vector<uint32_t>().swap(patches.words);
  }
  const bool patched = patches.info.size() == leafMesh.faceCount();
  std::vector<uint32_t> fileFace(leafMesh.faceCount(), UINT32_MAX), faceGroup(leafMesh.faceCount(), UINT32_MAX);
  uint32_t nextFace = cageOffset;
  for (uint32_t id : clusterOrder)
    for (uint32_t f : dag.clusters[id].cageFaces) {
      fileFace[f] = nextFace++;
      faceGroup[f] = dag.clusters[id].group;
    }
  auto flat = [&](uint32_t f) { return !patched || !patches.patched(f) || f >= patchErrors.size(); };
  auto filePatch = [&](uint32_t f) {
    shaderio::Patch out{};
    out.pointBase = pointBase;
    for (uint32_t& n : out.neighbours) n = VGEO_INVALID;
    if (flat(f)) {
      out.info = 0xfu << 16;  // VGEO_PATCH_NONE, every edge locked
      if (patched)
        for (uint32_t k = 0; k < 4; k++) {
          uint32_t n = patches.neighbours[f][k];
          if (n != UINT32_MAX && fileFace[n >> 2] != UINT32_MAX) out.neighbours[k] = fileFace[n >> 2] << 2 | (n & 3u);
        }
      return out;
    }
    uint32_t locked = 0;
    for (uint32_t k = 0; k < 4; k++) {
      uint32_t n = patches.neighbours[f][k];
      if (n == UINT32_MAX) continue;  // a boundary: nothing on the other side to disagree with
      if (fileFace[n >> 2] != UINT32_MAX) out.neighbours[k] = fileFace[n >> 2] << 2 | (n & 3u);
      if (flat(n >> 2) || faceGroup[n >> 2] != faceGroup[f]) locked |= 1u << k;
    }
    out.info = patches.info[f] | locked << 16;
    out.firstPoint = wordBase + patches.first[f];
    out.faceError = patchErrors[f].face;
    out.edgeError =
        glm::vec4(patchErrors[f].edge[0], patchErrors[f].edge[1], patchErrors[f].edge[2], patchErrors[f].edge[3]);
    return out;
  };
  std::vector<uint32_t> local;
  std::vector<uint32_t> slotOf(vertices, UINT32_MAX);  // wedge -> local index, reset per cluster
  for (uint32_t id : clusterOrder) {
    const BuildCluster& c = dag.clusters[id];
    const BuildGroup& parent = dag.groups[c.group];
    shaderio::Cluster out{};
    out.selfSphere = c.selfSphere;
    out.selfError = c.selfError;
    out.parentSphere = parent.sphere;
    out.parentError = parent.error;
    out.group = groupIndex[c.group];
    out.producer = c.producer == VGEO_NO_GROUP ? VGEO_NO_GROUP : groupIndex[c.producer];
    out.vertexOffset = uint32_t(file.clusterVertices.size());
    out.triangleOffset = uint32_t(file.clusterTriangles.size());
    local.clear();
    const std::vector<uint32_t>& corners = c.wedges.empty() ? c.indices : c.wedges;
    for (uint32_t v : corners)
      if (slotOf[v] == UINT32_MAX) {
        slotOf[v] = uint32_t(local.size());
        local.push_back(v);
      }
    for (uint32_t v : local) file.clusterVertices.push_back(vertexOffset + v);
    for (size_t t = 0; t + 2 < corners.size(); t += 3)
      file.clusterTriangles.push_back(slotOf[corners[t]] | slotOf[corners[t + 1]] << 8 | slotOf[corners[t + 2]] << 16);
    for (uint32_t v : local) slotOf[v] = UINT32_MAX;
    out.cageFaceOffset = uint32_t(file.cageFaces.size());
    uint32_t firstTriangle = 0;
    for (uint32_t f : c.cageFaces) {
      shaderio::CageFace face{};
      face.firstVertex = uint32_t(file.cageFaceVertices.size());
      face.vertexCount = leafMesh.faceSize(f);
      face.leafCluster = clusterIndex[id];
      face.firstTriangle = firstTriangle;
      firstTriangle += face.vertexCount - 2;
      for (uint32_t k = 0; k < face.vertexCount; k++)
        file.cageFaceVertices.push_back(vertexOffset + shading.wedgeOfCorner(leafMesh, leafMesh.faceStart[f] + k));
      file.cageFaces.push_back(face);
      file.patches.push_back(filePatch(f));
    }
    file.clusterCones.push_back(cones[id]);
    out.counts = shaderio::packClusterCounts(uint32_t(local.size()), uint32_t(c.indices.size() / 3), c.level,
                                             uint32_t(c.cageFaces.size()));
    file.clusters.push_back(out);
  }

  for (uint32_t g : bvh.groupOrder) {
    const BuildGroup& src = dag.groups[g];
    shaderio::Group out{};
    out.sphere = src.sphere;
    out.error = src.error;
    out.clusterOffset = clusterIndex[src.members.front()];
    out.clusterCount = uint32_t(src.members.size());
    out.level = src.level;
    file.groups.push_back(out);
  }
  for (shaderio::BvhNode node : bvh.nodes) {
    node.childOffset += (node.childCountAndFlags & VGEO_NODE_LEAF_BIT) ? groupOffset : nodeOffset;
    file.nodes.push_back(node);
  }

  shaderio::Geometry geometry{};
  geometry.boundsSphere = bvh.nodes[0].sphere;
  geometry.clusterOffset = clusterOffset;
  geometry.clusterCount = uint32_t(dag.clusters.size());
  geometry.groupOffset = groupOffset;
  geometry.groupCount = uint32_t(dag.groups.size());
  geometry.nodeOffset = nodeOffset;
  geometry.nodeCount = uint32_t(bvh.nodes.size());
  geometry.vertexOffset = vertexOffset;
  geometry.vertexCount = uint32_t(vertices);
  geometry.cageFaceOffset = cageOffset;
  geometry.cageFaceCount = uint32_t(file.cageFaces.size() - cageOffset);
  geometry.levelCount = uint32_t(dag.levelClusters.size());
  geometry.flags = closed ? VGEO_GEOMETRY_CLOSED : 0u;
  file.geometries.push_back(geometry);
}

}  // namespace vgeo
