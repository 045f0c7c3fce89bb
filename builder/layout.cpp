// layout.cpp: lays a DAG out as the renderer's buffers (a geometry of a .vgeo), written as they are made.
// Groups are stored in BVH leaf order, so a leaf node's groups are one run; clusters in group order, so a
// group's members are one run; leaf clusters' cage faces in cluster order, so a leaf's faces are one run.
// Each cluster lists its distinct vertices once (absolute indices) and its triangles as 8-bit local
// indices: the meshlet layout, which lets a pass read any cluster without a second index buffer.
#include <malloc.h>

#include <algorithm>

#include "../common/parallel.h"
#include "builder.h"
#include "layout.h"

namespace vgeo {
PatchBases appendPatchPoints(SectionSink& file, MeshPatches& patches) {
  PatchBases bases{uint32_t(file.count(Section::ControlPoints)), uint32_t(file.count(Section::PatchPoints))};
  file.append(Section::ControlPoints, patches.points);
  FillLaterVector<glm::vec3>().swap(patches.points);
  for (MeshPatches::Block& block : patches.blocks) {
    file.append(Section::ControlPoints, block.points);
    FillLaterVector<glm::vec3>().swap(block.points);
  }
  for (MeshPatches::Block& block : patches.blocks) {
    file.append(Section::PatchPoints, block.words);
    FillLaterVector<uint32_t>().swap(block.words);
  }
  // The blocks came from the heaps of the threads that made them, where freed memory stays with the
  // process (unlike a large array's own mapping): handed back now, before the DAG needs its own. A mesh
  // without patches freed nothing here, and a scene may have thousands of them.
  if (!patches.blocks.empty()) malloc_trim(0);
  return bases;
}

void appendGeometry(SectionSink& file, const Dag& dag, const PolygonMesh& leafMesh, const ShadingNormals& shading,
                    const MeshPatches& patches, PatchBases bases, const PatchErrorList& patchErrors, bool closed,
                    bool last, int threads) {
  Bvh bvh = buildBvh(dag.groups);
  const uint32_t vertexOffset = uint32_t(file.count(Section::Positions)),
                 clusterOffset = uint32_t(file.count(Section::Clusters)),
                 groupOffset = uint32_t(file.count(Section::Groups)),
                 nodeOffset = uint32_t(file.count(Section::BvhNodes)),
                 cageOffset = uint32_t(file.count(Section::CageFaces));

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
  if (dag.bounds.size() != dag.clusters.size()) throw std::logic_error("appendGeometry: a cluster has no bounds");
  const bool patched = patches.info.size() == leafMesh.faceCount() && leafMesh.faceCount() > 0;
  const size_t vertices = shading.wedgeVertex.size();
  // The file's last geometry: what each section will hold is known before it is appended (its patch
  // points are in already), so that a file sink writes them in place.
  auto expectMore = [&](Section s, uint64_t more) {
    if (last) file.expectTotal(s, file.count(s) + more);
  };
  // Where each cluster's arrays start in their sections, in cluster order (one more: the ends): known
  // from the counts, so that a batch of clusters is laid out straight into its place.
  struct Place {
    uint64_t vertex, triangle, face, faceVertex;
  };
  std::vector<Place> places(clusterOrder.size() + 1);
  places[0] = {file.count(Section::ClusterVertices), file.count(Section::ClusterTriangles),
               file.count(Section::CageFaces), file.count(Section::CageFaceVertices)};
  for (size_t i = 0; i < clusterOrder.size(); i++) {
    const BuildCluster& c = dag.clusters[clusterOrder[i]];
    Place next = places[i];
    next.vertex += dag.bounds[clusterOrder[i]].vertexCount;
    next.triangle += c.indices.size() / 3;
    if (patched) {
      next.face += c.cageFaces.size();
      for (uint32_t f : c.cageFaces) next.faceVertex += leafMesh.faceSize(f);
    }
    places[i + 1] = next;
  }
  if (last) {
    const Place& from = places.front();
    const Place& to = places.back();
    expectMore(Section::Geometries, 1);
    expectMore(Section::Positions, vertices);
    expectMore(Section::Normals, vertices);
    expectMore(Section::Clusters, dag.clusters.size());
    expectMore(Section::ClusterVertices, to.vertex - from.vertex);
    expectMore(Section::ClusterTriangles, to.triangle - from.triangle);
    expectMore(Section::Groups, dag.groups.size());
    expectMore(Section::BvhNodes, bvh.nodes.size());
    expectMore(Section::CageFaces, to.face - from.face);
    expectMore(Section::CageFaceVertices, to.faceVertex - from.faceVertex);
    expectMore(Section::ClusterCones, dag.clusters.size());
    expectMore(Section::ControlPoints, 0);
    expectMore(Section::Patches, to.face - from.face);
    expectMore(Section::PatchPoints, 0);
  }

  // Vertices: one a wedge (shading_normals.cpp), which is one a leaf vertex unless the mesh has hard
  // edges; they go to the file on one thread while the others number the faces.
  auto appendVertices = [&] {
    FillLaterVector<glm::vec3> positions(vertices);
    FillLaterVector<uint32_t> normals(vertices);
    parallelForRanges(vertices, threads, [&](size_t begin, size_t end) {
      for (size_t w = begin; w < end; w++) {
        positions[w] = leafMesh.positions[shading.wedgeVertex[w]];
        normals[w] = encodeNormal(shading.wedgeNormal[w]);
      }
    });
    file.append(Section::Positions, positions.data(), vertices);
    file.append(Section::Normals, normals.data(), vertices);
  };
  // One patch per face of a subdivided cage (its words verbatim: control-point indices relative to the
  // geometry's first control point). Neighbours name faces by their index in the file, whose order
  // (cluster order) is known first; an edge is locked at factor 1 where the face on its other side
  // belongs to another level-0 group (which may be drawn coarser) or is flat.
  const uint32_t pointBase = bases.point, wordBase = bases.word;
  std::vector<uint32_t> fileFace, faceGroup;
  auto numberFaces = [&] {
    if (!patched) return;
    fileFace.assign(leafMesh.faceCount(), UINT32_MAX);
    faceGroup.assign(leafMesh.faceCount(), UINT32_MAX);
    uint32_t nextFace = cageOffset;
    for (uint32_t id : clusterOrder)
      for (uint32_t f : dag.clusters[id].cageFaces) {
        fileFace[f] = nextFace++;
        faceGroup[f] = dag.clusters[id].group;
      }
  };
  withThreads(threads, [&] { parallelInvoke(threads > 1, appendVertices, numberFaces); });
  auto flat = [&](uint32_t f) { return !patches.patched(f) || f >= patchErrors.size(); };
  auto filePatch = [&](uint32_t f) {
    shaderio::Patch out{};
    out.pointBase = pointBase;
    for (uint32_t& n : out.neighbours) n = VGEO_INVALID;
    if (flat(f)) {
      out.info = 0xfu << 16;  // VGEO_PATCH_NONE, every edge locked
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

  // Clusters in cluster order, each with its vertices, triangles, normal cone and (leaves of a
  // subdivided cage) faces with their patches. A batch of clusters is laid out on the threads into the
  // batch's arrays, each cluster at its place, then appended whole on one thread while the next batch
  // is laid out on the others.
  struct Batch {
    std::vector<shaderio::Cluster> clusters;
    std::vector<shaderio::ClusterCone> cones;
    std::vector<uint32_t> vertices, triangles, faceVertices;
    std::vector<shaderio::CageFace> faces;
    std::vector<shaderio::Patch> patches;
  };
  constexpr size_t kBatch = 1024;
  auto layOut = [&](size_t first, Batch& batch) {
    const size_t count = std::min(kBatch, clusterOrder.size() - first);
    const Place& from = places[first];
    const Place& to = places[first + count];
    batch.clusters.resize(count);
    batch.cones.resize(count);
    batch.vertices.resize(to.vertex - from.vertex);
    batch.triangles.resize(to.triangle - from.triangle);
    batch.faces.resize(to.face - from.face);
    batch.patches.resize(to.face - from.face);
    batch.faceVertices.resize(to.faceVertex - from.faceVertex);
    parallelFor(count, threads, [&](size_t i) {
      const uint32_t id = clusterOrder[first + i];
      const BuildCluster& c = dag.clusters[id];
      const BuildGroup& parent = dag.groups[c.group];
      const Place& at = places[first + i];
      shaderio::Cluster& out = batch.clusters[i];
      out = {};
      out.selfSphere = c.selfSphere;
      out.selfError = c.selfError;
      out.parentSphere = parent.sphere;
      out.parentError = parent.error;
      out.group = groupIndex[c.group];
      out.producer = c.producer == VGEO_NO_GROUP ? VGEO_NO_GROUP : groupIndex[c.producer];
      out.vertexOffset = uint32_t(at.vertex);
      out.triangleOffset = uint32_t(at.triangle);
      out.cageFaceOffset = uint32_t(at.face);
      batch.cones[i] = {dag.bounds[id].cone, dag.bounds[id].sphere};
      // Its vertices in order of first use, its triangles as three local indices.
      thread_local std::vector<uint32_t> own, local;
      localIds(c.wedges.empty() ? c.indices : c.wedges, own, local);
      if (own.size() != places[first + i + 1].vertex - at.vertex)
        throw std::logic_error("appendGeometry: a cluster's vertices changed count");
      uint32_t* vertices = batch.vertices.data() + (at.vertex - from.vertex);
      for (size_t k = 0; k < own.size(); k++) vertices[k] = own[k] + vertexOffset;
      uint32_t* triangles = batch.triangles.data() + (at.triangle - from.triangle);
      for (size_t t = 0; t + 2 < local.size(); t += 3) *triangles++ = local[t] | local[t + 1] << 8 | local[t + 2] << 16;
      uint32_t firstTriangle = 0;
      uint64_t faceVertex = at.faceVertex;
      const uint32_t faceCount = patched ? uint32_t(c.cageFaces.size()) : 0u;
      for (uint32_t k = 0; k < faceCount; k++) {
        const uint32_t f = c.cageFaces[k];
        shaderio::CageFace& face = batch.faces[at.face - from.face + k];
        face = {};
        face.firstVertex = uint32_t(faceVertex);
        face.vertexCount = leafMesh.faceSize(f);
        face.leafCluster = clusterIndex[id];
        face.firstTriangle = firstTriangle;
        firstTriangle += face.vertexCount - 2;
        for (uint32_t j = 0; j < face.vertexCount; j++)
          batch.faceVertices[faceVertex++ - from.faceVertex] =
              vertexOffset + shading.wedgeOfCorner(leafMesh, leafMesh.faceStart[f] + j);
        batch.patches[at.face - from.face + k] = filePatch(f);
      }
      out.counts =
          shaderio::packClusterCounts(uint32_t(own.size()), uint32_t(c.indices.size() / 3), c.level, faceCount);
    });
  };
  auto append = [&](const Batch& batch) {
    file.append(Section::Clusters, batch.clusters);
    file.append(Section::ClusterVertices, batch.vertices);
    file.append(Section::ClusterTriangles, batch.triangles);
    file.append(Section::CageFaces, batch.faces);
    file.append(Section::CageFaceVertices, batch.faceVertices);
    file.append(Section::ClusterCones, batch.cones);
    file.append(Section::Patches, batch.patches);
  };
  Batch batches[2];
  if (!clusterOrder.empty()) layOut(0, batches[0]);
  withThreads(threads, [&] {
    for (size_t first = 0, k = 0; first < clusterOrder.size(); first += kBatch, k ^= 1)
      parallelInvoke(
          threads > 1, [&] { append(batches[k]); },
          [&] {
            if (first + kBatch < clusterOrder.size()) layOut(first + kBatch, batches[k ^ 1]);
          });
  });

  std::vector<shaderio::Group> groups(bvh.groupOrder.size());
  for (size_t i = 0; i < groups.size(); i++) {
    const BuildGroup& src = dag.groups[bvh.groupOrder[i]];
    shaderio::Group& out = groups[i];
    out = {};
    out.sphere = src.sphere;
    out.error = src.error;
    out.clusterOffset = clusterIndex[src.members.front()];
    out.clusterCount = uint32_t(src.members.size());
    out.level = src.level;
  }
  file.append(Section::Groups, groups);
  for (shaderio::BvhNode& node : bvh.nodes)
    node.childOffset += (node.childCountAndFlags & VGEO_NODE_LEAF_BIT) ? groupOffset : nodeOffset;
  file.append(Section::BvhNodes, bvh.nodes);

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
  geometry.cageFaceCount = uint32_t(file.count(Section::CageFaces) - cageOffset);
  geometry.levelCount = uint32_t(dag.levelClusters.size());
  geometry.flags = closed ? VGEO_GEOMETRY_CLOSED : 0u;
  file.append(Section::Geometries, &geometry, 1);
}

}  // namespace vgeo
