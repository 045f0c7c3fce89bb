// test_dag.cpp: the invariants of docs/design.md on real meshes (CGAL's demo data, the shipped cage, a
// multi-mesh glTF), through the same checker as `vgeo check`, plus the builder's promises on sizes.
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>

#include "../builder/chord_rule.h"
#include "test_util.h"

namespace vgeo {
namespace {

struct DagCase {
  std::string name;
  std::string path;
  int subdiv;
  bool closedConnected;
  bool connected = false;  // one component, maybe open: one root (its open boundary is simplified too)
};

void PrintTo(const DagCase& c, std::ostream* os) { *os << c.name; }

class Dag : public ::testing::TestWithParam<DagCase> {};

TEST_P(Dag, InvariantsHold) {
  const DagCase& c = GetParam();
  SceneBuildStats stats;
  VgeoData data = test::build(c.path, c.subdiv, 2, &stats);
  // Invariant 1 and the per-level reduction.
  for (const auto& cluster : data.clusters) {
    EXPECT_LE(shaderio::clusterTriangleCount(cluster.counts), uint32_t(VGEO_MAX_CLUSTER_TRIANGLES));
    EXPECT_LE(shaderio::clusterVertexCount(cluster.counts), uint32_t(VGEO_MAX_CLUSTER_VERTICES));
  }
  for (size_t l = 1; l < stats.levelTriangles.size(); l++)
    EXPECT_LE(double(stats.levelTriangles[l]), 0.55 * double(stats.levelTriangles[l - 1])) << "level " << l;
  if (c.closedConnected) {
    EXPECT_EQ(stats.rootClusters, 1u);
    EXPECT_EQ(stats.repair.boundaryEdges, 0u);
  }
  if (c.connected) {
    EXPECT_EQ(stats.repair.components, 1u);
    EXPECT_EQ(stats.rootClusters, 1u);
    EXPECT_GT(stats.repair.boundaryEdges, 0u);
  }
  if (c.closedConnected && stats.leafTriangles >= 50000) {
    EXPECT_GE(double(stats.levelTriangles[0]) / double(stats.leafClusters), 124.0);
    // Simplified groups are cut to whole clusters too (simplifyTarget).
    EXPECT_GE(double(stats.clusterTriangles) / double(stats.clusters), 122.0);
  }
  // Invariants 2-5 on random cuts.
  CheckResult result = checkVgeo(data, {24, 7});
  EXPECT_TRUE(result.ok) << result.firstViolation;
}

INSTANTIATE_TEST_SUITE_P(
    Meshes, Dag,
    ::testing::Values(
        DagCase{"CubeQuad0", test::cgalMesh("cube_quad.off"), 0, true},
        DagCase{"CubeQuad2", test::cgalMesh("cube_quad.off"), 2, true},
        DagCase{"CubeQuad4", test::cgalMesh("cube_quad.off"), 4, true},
        DagCase{"TorusQuad0", test::cgalMesh("torus_quad.off"), 0, true},
        DagCase{"TorusQuad2", test::cgalMesh("torus_quad.off"), 2, true},
        DagCase{"TorusQuad4", test::cgalMesh("torus_quad.off"), 4, true},
        DagCase{"Bunny0", test::cgalMesh("bunny00.off"), 0, true},
        DagCase{"Bunny1", test::cgalMesh("bunny00.off"), 1, true},
        DagCase{"Bunny2", test::cgalMesh("bunny00.off"), 2, true},
        DagCase{"Armadillo0", test::cgalMesh("armadillo.off"), 0, true},
        DagCase{"Armadillo1", test::cgalMesh("armadillo.off"), 1, true},
        DagCase{"Armadillo2", test::cgalMesh("armadillo.off"), 2, true},
        // Faces wound inconsistently (CGAL's shuffled copies): oriented first, then reduced to one root.
        DagCase{"BlobbyShuffled0", test::cgalMesh("blobby-shuffled.off"), 0, true},
        DagCase{"OblongShuffled1", test::cgalMesh("oblong-shuffled.off"), 1, true},
        // Open surfaces: their boundary is simplified along with the rest.
        DagCase{"Lion0", test::cgalMesh("lion.off"), 0, false, true},
        DagCase{"Blade2", test::cgalMesh("blade.off"), 2, false, true},
        DagCase{"MeshWithBorder1", test::cgalMesh("mesh_with_border.off"), 1, false, true},
        DagCase{"HornedCube0", test::asset("horned_cube.obj"), 0, true},
        DagCase{"HornedCube2", test::asset("horned_cube.obj"), 2, true},
        DagCase{"HornedCube4", test::asset("horned_cube.obj"), 4, true},
        DagCase{"CylinderEngineGltf", test::assimpModel("2CylinderEngine-glTF-Binary/2CylinderEngine.glb"), 0, false},
        DagCase{"CylinderEngineGltf1", test::assimpModel("2CylinderEngine-glTF-Binary/2CylinderEngine.glb"), 1, false}),
    [](const ::testing::TestParamInfo<DagCase>& info) { return info.param.name; });

TEST(DagBuild, GltfMeshesUsedTwiceAreBuiltOnceAndInstanced) {
  VgeoData data = test::build(test::assimpModel("2CylinderEngine-glTF-Binary/2CylinderEngine.glb"), 0);
  EXPECT_GT(data.instances.size(), data.geometries.size());
  for (const auto& inst : data.instances) EXPECT_LT(inst.geometry, data.geometries.size());
}

TEST(DagBuild, LeafClustersHoldWholeCageFaces) {
  VgeoData data = test::build(test::asset("horned_cube.obj"), 2);
  const auto& g = data.geometries[0];
  EXPECT_EQ(g.cageFaceCount, 342u * 16u);
  for (uint32_t f = g.cageFaceOffset; f < g.cageFaceOffset + g.cageFaceCount; f++) {
    const auto& face = data.cageFaces[f];
    EXPECT_EQ(face.vertexCount, 4u);
    const auto& leaf = data.clusters[face.leafCluster];
    ASSERT_EQ(leaf.producer, VGEO_NO_GROUP);
    ASSERT_LE(face.firstTriangle + 2, shaderio::clusterTriangleCount(leaf.counts));
    // The face's two triangles use exactly its four corners.
    std::vector<uint32_t> corners(data.cageFaceVertices.begin() + face.firstVertex,
                                  data.cageFaceVertices.begin() + face.firstVertex + 4);
    std::sort(corners.begin(), corners.end());
    std::vector<uint32_t> used;
    for (uint32_t t = face.firstTriangle; t < face.firstTriangle + 2; t++) {
      uint32_t tri = data.clusterTriangles[leaf.triangleOffset + t];
      for (int k = 0; k < 3; k++) used.push_back(data.clusterVertices[leaf.vertexOffset + ((tri >> (8 * k)) & 0xff)]);
    }
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    EXPECT_EQ(used, corners);
  }
}

TEST(DagBuild, OnlySubdividedCagesKeepCageFaces) {
  // A mesh built without subdivision has no surface below its leaves: no cage face, patch or patch
  // word is written (they were three quarters of such a file), and its clusters name none.
  VgeoData flat = test::build(test::cgalMesh("cow.off"), 0);
  EXPECT_TRUE(flat.cageFaces.empty() && flat.cageFaceVertices.empty() && flat.patches.empty());
  EXPECT_TRUE(flat.patchPoints.empty() && flat.controlPoints.empty());
  EXPECT_EQ(flat.geometries[0].cageFaceCount, 0u);
  for (const auto& c : flat.clusters) EXPECT_EQ(shaderio::clusterCageFaceCount(c.counts), 0u);
  // Subdivided once, every leaf triangle belongs to one of its leaf cluster's cage faces.
  VgeoData subdivided = test::build(test::cgalMesh("cow.off"), 1);
  EXPECT_EQ(subdivided.patches.size(), subdivided.cageFaces.size());
  for (const auto& c : subdivided.clusters) {
    if (c.producer != VGEO_NO_GROUP) continue;
    uint32_t triangles = 0;
    for (uint32_t k = 0; k < shaderio::clusterCageFaceCount(c.counts); k++)
      triangles += subdivided.cageFaces[c.cageFaceOffset + k].vertexCount - 2;
    EXPECT_EQ(triangles, shaderio::clusterTriangleCount(c.counts));
  }
}

TEST(DagBuild, ATriangleSoupBuildsTheSameOnAnyThreadCount) {
  // 3,000 triangles sharing no vertex: three new edges a triangle, past the room the chord rule's edge
  // set makes at first (about 1.6), so its insertion stops and runs again with more. Its clusters
  // share no edge, so they are grouped by position, and the soup still halves to one root.
  std::string obj;
  for (int i = 0; i < 3000; i++) {
    const float x = float(i % 60), y = float(i / 60);
    obj += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\nv " + std::to_string(x + 0.5f) + " " +
           std::to_string(y) + " 0\nv " + std::to_string(x) + " " + std::to_string(y + 0.5f) + " 0.25\n";
    obj += "f " + std::to_string(3 * i + 1) + " " + std::to_string(3 * i + 2) + " " + std::to_string(3 * i + 3) + "\n";
  }
  const std::string path = test::writeFile(test::tempDir(), "soup.obj", obj);
  SceneBuildStats stats;
  VgeoData one = test::build(path, 0, 1, &stats), two = test::build(path, 0, 2);
  EXPECT_EQ(stats.leafTriangles, 3000u);
  EXPECT_EQ(stats.rootClusters, 1u);
  EXPECT_EQ(serializeVgeo(one), serializeVgeo(two));
  CheckResult result = checkVgeo(one, {8, 7});
  EXPECT_TRUE(result.ok) << result.firstViolation;
}

TEST(DagBuild, GroupsAreTheSameOnAnyThreadCount) {
  // 6,400 clusters of 2 x 2 grid cells on a wavy sheet: past 2 * kGroupingPiece, so the level is cut
  // into pieces grouped side by side.
  constexpr uint32_t kCells = 160;
  std::vector<glm::vec3> positions;
  for (uint32_t y = 0; y <= kCells; y++)
    for (uint32_t x = 0; x <= kCells; x++)
      positions.push_back({float(x), float(y), std::sin(0.3f * float(x)) * std::cos(0.2f * float(y))});
  std::vector<BuildCluster> clusters((kCells / 2) * (kCells / 2));
  for (uint32_t y = 0; y < kCells; y++)
    for (uint32_t x = 0; x < kCells; x++) {
      const uint32_t v = y * (kCells + 1) + x;
      auto& indices = clusters[(y / 2) * (kCells / 2) + x / 2].indices;
      indices.insert(indices.end(), {v, v + 1, v + kCells + 2, v, v + kCells + 2, v + kCells + 1});
    }
  std::vector<uint32_t> active(clusters.size());
  for (uint32_t i = 0; i < active.size(); i++) active[i] = i;
  ASSERT_GT(clusters.size(), 2 * size_t(kGroupingPiece));
  const auto one = groupClusters(clusters, active, positions, 16, 1, nullptr);
  std::vector<int> seen(clusters.size(), 0);
  for (const auto& g : one)
    for (uint32_t c : g.clusters) seen[c]++;
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), long(clusters.size()));
  for (int run = 0; run < 3; run++) {
    const auto four = groupClusters(clusters, active, positions, 16, 4, nullptr);
    ASSERT_EQ(four.size(), one.size());
    for (size_t g = 0; g < one.size(); g++) ASSERT_EQ(four[g].clusters, one[g].clusters) << "group " << g;
  }
}

TEST(DagBuild, BvhRootHoldsOneSubtreePerLevel) {
  // The traversal's chain starts at the root's children (instance culling tests them): they must be the
  // simplification levels' subtrees, one each, even past 8 levels; every other node has at most 8.
  VgeoData data = test::build(test::cgalMesh("bunny00.off"), 2);
  const auto& g = data.geometries[0];
  std::set<uint32_t> levels;
  for (uint32_t i = g.groupOffset; i < g.groupOffset + g.groupCount; i++) levels.insert(data.groups[i].level);
  ASSERT_GT(levels.size(), size_t(VGEO_BVH_WIDTH));
  const shaderio::BvhNode& root = data.nodes[g.nodeOffset];
  ASSERT_EQ(root.childCountAndFlags & VGEO_NODE_LEAF_BIT, 0u);
  ASSERT_EQ(root.childCountAndFlags, uint32_t(levels.size()));
  std::set<uint32_t> childLevels;
  for (uint32_t k = 0; k < root.childCountAndFlags; k++) childLevels.insert(data.nodes[root.childOffset + k].level);
  EXPECT_EQ(childLevels, levels);
  for (uint32_t n = g.nodeOffset + 1; n < g.nodeOffset + g.nodeCount; n++)
    EXPECT_LE(data.nodes[n].childCountAndFlags & ~VGEO_NODE_LEAF_BIT, uint32_t(VGEO_BVH_WIDTH)) << "node " << n;
}

TEST(DagBuild, StatsJsonHasEveryPromisedField) {
  std::string dir = test::tempDir();
  test::RunResult r = test::runVgeo("build '" + test::asset("horned_cube.obj") + "' --subdiv 2 -o " + dir +
                                    "/h.vgeo --stats " + dir + "/s.json --threads 2 -q");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir + "/s.json");
  nlohmann::json j = nlohmann::json::parse(in);
  for (const char* key : {"input_triangles", "leaf_triangles", "levels", "clusters", "level_clusters",
                          "level_triangles", "root_clusters", "avg_leaf_cluster_triangles", "avg_cluster_triangles",
                          "relaxed_groups", "build_seconds", "total_seconds", "peak_rss_bytes", "threads"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["input_triangles"], 684);
  EXPECT_EQ(j["leaf_triangles"], 684 * 16);
  EXPECT_EQ(j["root_clusters"], 1);
  EXPECT_EQ(j["threads"], 2);
  test::RunResult check = test::runVgeo("check " + dir + "/h.vgeo --cuts 8");
  EXPECT_EQ(check.exitCode, 0) << check.output;
  EXPECT_NE(check.output.find("ok:"), std::string::npos);
}

TEST(DagBuild, DenseBorderEdgesMatchTheHashedOnes) {
  // The simplifier finds a group's border with edgesUsedOnceDense over local ids; grouping, with
  // edgesUsedOnce over global ones. Both must give the same edges on slices of real meshes (closed, with
  // open boundaries and holes, unstitched), whole and in pieces of a group's size, and on an edge that
  // three triangles share and a triangle that holds one vertex twice.
  const std::vector<uint32_t> fan = {0, 1, 2, 1, 0, 3, 0, 1, 4, 2, 2, 5};
  const std::vector<uint64_t> fanDense = edgesUsedOnceDense(fan, 6);
  EXPECT_EQ(fanDense, edgesUsedOnce(fan));
  EXPECT_EQ(std::count(fanDense.begin(), fanDense.end(), uint64_t(0) << 32 | 1), 0);
  // A fan of 40 triangles around vertex 0, its apex's bucket past the insertion sort's size.
  std::vector<uint32_t> wideFan;
  for (uint32_t i = 1; i <= 40; i++) wideFan.insert(wideFan.end(), {0, i, i + 1});
  const std::vector<uint64_t> wideDense = edgesUsedOnceDense(wideFan, 42);
  EXPECT_EQ(wideDense, edgesUsedOnce(wideFan));
  EXPECT_EQ(wideDense.size(), size_t(42));  // the 40 rim edges and the two sides
  for (const char* name :
       {"bunny00.off", "mesh_with_border.off", "elephant-with-holes.off", "blade.off", "quads_to_stitch.off"}) {
    const PolygonMesh mesh = loadMeshFile(test::cgalMesh(name)).meshes[0];
    std::vector<uint32_t> triangles;
    for (size_t f = 0; f < mesh.faceCount(); f++)
      triangulateFace(mesh.positions.data(), mesh.face(f), mesh.faceSize(f), triangles);
    for (const size_t piece : {size_t(1) << 30, size_t(3 * 2048), size_t(3 * 257)}) {
      for (size_t first = 0; first < triangles.size(); first += piece) {
        const size_t end = std::min(triangles.size(), first + piece);
        std::vector<uint32_t> slice(triangles.begin() + long(first), triangles.begin() + long(end)), globals, local;
        localIds(slice, globals, local);
        ASSERT_EQ(edgesUsedOnceDense(local, uint32_t(globals.size())), edgesUsedOnce(local))
            << name << " triangles " << first / 3 << " to " << end / 3;
      }
    }
  }
}

// CGAL meshes closed, with open boundaries and holes, unstitched, and of quads.
constexpr const char* kBorderMeshes[] = {"bunny00.off", "mesh_with_border.off", "elephant-with-holes.off",
                                         "blade.off",   "quads_to_stitch.off",  "cross_quad.off"};

// The mesh's faces cut into groups of a round's size (2,048 triangles, in face order), each split into
// clusters as a simplified group is: split(first, end, clusters) for triangles [first, end).
template <class Split>
void splitRoundSizedGroups(const PolygonMesh& mesh, Split&& split) {
  std::vector<uint32_t> triangles;
  for (size_t f = 0; f < mesh.faceCount(); f++)
    triangulateFace(mesh.positions.data(), mesh.face(f), mesh.faceSize(f), triangles);
  for (size_t first = 0; first < triangles.size(); first += 3 * 2048) {
    const size_t end = std::min(triangles.size(), first + 3 * 2048);
    SimplifiedGroup group;
    localIds(std::vector<uint32_t>(triangles.begin() + long(first), triangles.begin() + long(end)), group.globals,
             group.indices);
    split(first / 3, end / 3, splitIntoClusters(group, mesh.positions));
  }
}

TEST(DagBuild, ClustersCarryTheBorderTheirTrianglesHave) {
  // A simplified group's clusters carry their border, read off the soup's partner corners (or counted
  // where the soup has an edge of three triangles); it must be what edgesUsedOnce counts on their
  // triangles, on groups of a round's size cut from real meshes. buildLeafClusters leaves the leaves'
  // empty: the DAG build counts them.
  for (const char* name : kBorderMeshes) {
    PolygonMesh mesh = loadMeshFile(test::cgalMesh(name)).meshes[0];
    triangulateLargeFaces(mesh, 1);
    for (const BuildCluster& c : buildLeafClusters(mesh, 1)) ASSERT_TRUE(c.border.empty()) << name;
    splitRoundSizedGroups(mesh, [&](size_t first, size_t end, std::vector<BuildCluster> clusters) {
      for (const BuildCluster& c : clusters)
        ASSERT_EQ(c.border, edgesUsedOnce(c.indices)) << name << " triangles " << first << " to " << end;
    });
  }
}

TEST(DagBuild, MergedGroupsAreConnectedBoundedAndCannotMergeFurther) {
  // The leaf clusters of real meshes as a graph weighted by the edges two clusters share: every group
  // is connected, holds at most 16 + 16 / 3 clusters, and no two neighbouring groups under 16 would fit
  // together; the groups' borders are shorter than those of the clusters' own order cut into runs of
  // 16 over the six meshes, in no more groups (the clusters come out of a recursive bisection, so
  // runs are compact too: merging gave 4,162 shared edges against the runs' 5,501).
  constexpr uint32_t kTarget = 16, kMost = kTarget + kTarget / 3;
  uint64_t mergedCut = 0, runsCut = 0;
  for (const char* name : kBorderMeshes) {
    PolygonMesh mesh = loadMeshFile(test::cgalMesh(name)).meshes[0];
    repairMesh(mesh, name);
    triangulateLargeFaces(mesh, 1);
    const std::vector<BuildCluster> clusters = buildLeafClusters(mesh, 1);
    std::map<uint64_t, std::vector<uint32_t>> edgeClusters;
    for (uint32_t c = 0; c < clusters.size(); c++)
      for (uint64_t edge : edgesUsedOnce(clusters[c].indices)) edgeClusters[edge].push_back(c);
    std::vector<std::map<uint32_t, uint32_t>> shared(clusters.size());
    for (const auto& [edge, holders] : edgeClusters)
      for (uint32_t a : holders)
        for (uint32_t b : holders)
          if (a != b) shared[a][b]++;
    WeightedGraph graph;
    for (const auto& row : shared) {
      for (const auto& [b, w] : row) graph.adjacency.push_back(b), graph.weights.push_back(w);
      graph.offsets.push_back(uint32_t(graph.adjacency.size()));
    }
    std::vector<uint32_t> group(clusters.size());
    std::vector<glm::vec3> centroids;
    for (const BuildCluster& c : clusters) {
      glm::vec3 sum(0.0f);
      for (uint32_t v : c.indices) sum += mesh.positions[v];
      centroids.push_back(sum / float(c.indices.size()));
    }
    const uint32_t groups = mergeIntoGroups(graph, centroids.data(), kTarget, group.data());
    std::vector<std::vector<uint32_t>> members(groups);
    uint32_t next = 0;
    for (uint32_t c = 0; c < clusters.size(); c++) {
      ASSERT_LE(group[c], next) << name << ": groups numbered in order of first cluster";
      next = std::max(next, group[c] + 1);
      members[group[c]].push_back(c);
    }
    ASSERT_EQ(next, groups) << name;
    auto cutOf = [&](const std::vector<uint32_t>& of) {
      uint64_t cut = 0;
      for (uint32_t a = 0; a < clusters.size(); a++)
        for (const auto& [b, w] : shared[a]) cut += of[a] != of[b] ? w : 0;
      return cut / 2;
    };
    for (uint32_t g = 0; g < groups; g++) {
      ASSERT_LE(members[g].size(), kMost) << name << " group " << g;
      std::set<uint32_t> reached{members[g][0]};
      for (std::vector<uint32_t> front{members[g][0]}; !front.empty();) {
        const uint32_t a = front.back();
        front.pop_back();
        for (const auto& [b, w] : shared[a])
          if (group[b] == g && reached.insert(b).second) front.push_back(b);
      }
      EXPECT_EQ(reached.size(), members[g].size()) << name << ": group " << g << " is not connected";
      for (uint32_t a : members[g])
        for (const auto& [b, w] : shared[a]) {
          const size_t mine = members[g].size(), theirs = members[group[b]].size();
          EXPECT_FALSE(group[b] != g && mine < kTarget && theirs < kTarget && mine + theirs <= kMost)
              << name << ": groups " << g << " and " << group[b] << " would still fit together";
        }
    }
    std::vector<uint32_t> runs(clusters.size());
    for (uint32_t c = 0; c < clusters.size(); c++) runs[c] = c / kTarget;
    EXPECT_LE(groups, (clusters.size() + kTarget - 1) / kTarget) << name;
    mergedCut += cutOf(group);
    runsCut += cutOf(runs);
  }
  EXPECT_LT(mergedCut * 5, runsCut * 4);
}

TEST(DagBuild, TheChordRuleForbidsEveryEdgeAClusterHas) {
  // The chord rule's set takes a cluster's edges as the upward half of each edge two of its triangles
  // share and its border: on real meshes, as leaves and as a simplified group's clusters, every edge of
  // every triangle must be in it, on any thread count, and a chord between border vertices no cluster
  // joins must still be allowed somewhere.
  size_t allowedChords[2] = {0, 0};  // on 1 and on 4 threads, of the first few pairs tried in each mesh
  for (const char* name : kBorderMeshes) {
    PolygonMesh mesh = loadMeshFile(test::cgalMesh(name)).meshes[0];
    repairMesh(mesh, name);  // oriented, as the build has it
    triangulateLargeFaces(mesh, 1);
    std::vector<BuildCluster> clusters = buildLeafClusters(mesh, 1);
    for (BuildCluster& c : clusters) c.border = edgesUsedOnce(c.indices);
    splitRoundSizedGroups(mesh, [&](size_t, size_t, std::vector<BuildCluster> split) {
      for (BuildCluster& c : split) clusters.push_back(std::move(c));
    });
    std::set<uint64_t> edges;
    for (const BuildCluster& c : clusters)
      for (size_t t = 0; t + 2 < c.indices.size(); t += 3)
        for (size_t k = 0; k < 3; k++) edges.insert(undirectedEdge(c.indices[t + k], c.indices[t + (k + 1) % 3]));
    std::vector<GroupPlan> plans(clusters.size());  // a group a cluster
    for (uint32_t i = 0; i < clusters.size(); i++) plans[i].clusters = {i};
    for (int threads : {1, 4}) {
      size_t& allowed = allowedChords[threads > 1];
      const size_t before = allowed;
      ChordRule chords(mesh.positions.size(), threads);
      chords.makeRoom(clusters, 0, nullptr, threads);
      chords.addClusters(clusters, 0, threads);
      chords.startRound(plans, clusters, threads);
      size_t e = 0;
      for (const uint64_t edge : edges)  // each asked of one group: the set answers for all of them
        ASSERT_FALSE(chords.allowed(uint32_t(e++ % clusters.size()), uint32_t(edge >> 32), uint32_t(edge)))
            << name << " threads " << threads;
      for (uint32_t g = 0; g < clusters.size(); g++) {
        const std::vector<uint64_t>& border = clusters[g].border;
        for (size_t i = 0; i + 2 < border.size() && allowed < before + 8; i += 3)
          if (uint32_t(border[i] >> 32) != uint32_t(border[i + 2]) &&
              !edges.count(undirectedEdge(uint32_t(border[i] >> 32), uint32_t(border[i + 2]))))
            allowed += chords.allowed(g, uint32_t(border[i] >> 32), uint32_t(border[i + 2]));
      }
    }
  }
  EXPECT_GT(allowedChords[0], 0u);
  EXPECT_EQ(allowedChords[0], allowedChords[1]);
}

}  // namespace
}  // namespace vgeo
