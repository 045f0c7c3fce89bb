// dag.cpp: the LOD DAG (Nanite's scheme, Karis 2021): leaf clusters, then rounds of
// group -> simplify to half with the group border locked -> split into new clusters, until one cluster is
// left or no group can be halved. Errors and spheres follow DESIGN.md: a group's error is the largest
// self error of its members plus what its simplification added, and its sphere encloses the members'
// self spheres, so both only grow toward the root (monotonic), and the clusters a group produces take
// the group's (error, sphere) as their self pair.
#include <algorithm>
#include <cmath>

#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {
namespace {

uint64_t triangleCount(const std::vector<BuildCluster>& clusters, const std::vector<uint32_t>& ids) {
  uint64_t n = 0;
  for (uint32_t id : ids) n += clusters[id].indices.size() / 3;
  return n;
}

glm::vec4 sphereOfClusterVertices(const BuildCluster& c, const std::vector<glm::vec3>& positions) {
  std::vector<uint32_t> v(c.indices);
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return sphereOfPoints(positions, v.data(), v.size());
}

BuildGroup makeGroup(std::vector<BuildCluster>& clusters, const std::vector<uint32_t>& members, uint32_t id, float addedError,
                     uint32_t level) {
  BuildGroup g;
  g.members = members;
  g.level = level;
  std::vector<glm::vec4> spheres;
  float maxError = 0.0f;
  for (uint32_t m : members) {
    spheres.push_back(clusters[m].selfSphere);
    maxError = std::max(maxError, clusters[m].selfError);
    clusters[m].group = id;
  }
  g.sphere = sphereOfSpheres(spheres.data(), spheres.size());
  g.error = maxError + addedError;
  // Float addition can round down below a member's error only if addedError is negative; guard anyway.
  if (g.error < maxError) g.error = maxError;
  return g;
}

// Every undirected edge of every cluster made so far, as an open-addressing hash set of (min << 32 | max).
class EdgeSet {
 public:
  bool contains(uint64_t key) const {
    if (slots_.empty()) return false;
    for (size_t i = hash(key) & mask_;; i = (i + 1) & mask_) {
      if (slots_[i] == key) return true;
      if (slots_[i] == kEmpty) return false;
    }
  }
  void insertTriangles(const std::vector<uint32_t>& indices) {
    for (size_t t = 0; t + 2 < indices.size(); t += 3)
      for (int k = 0; k < 3; k++) {
        uint32_t a = indices[t + size_t(k)], b = indices[t + size_t((k + 1) % 3)];
        insert(uint64_t(std::min(a, b)) << 32 | std::max(a, b));
      }
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t(0);
  static size_t hash(uint64_t k) { return size_t((k * 0x9e3779b97f4a7c15ull) >> 20); }
  void insert(uint64_t key) {
    if ((count_ + 1) * 2 > slots_.size()) grow();
    for (size_t i = hash(key) & mask_;; i = (i + 1) & mask_) {
      if (slots_[i] == key) return;
      if (slots_[i] == kEmpty) {
        slots_[i] = key;
        count_++;
        return;
      }
    }
  }
  void grow() {
    std::vector<uint64_t> old = std::move(slots_);
    slots_.assign(std::max<size_t>(1024, old.size() * 2), kEmpty);
    mask_ = slots_.size() - 1;
    count_ = 0;
    for (uint64_t k : old)
      if (k != kEmpty) insert(k);
  }
  std::vector<uint64_t> slots_;
  size_t mask_ = 0, count_ = 0;
};

}  // namespace

Dag buildDag(const PolygonMesh& mesh, const BuildOptions& options) {
  Dag dag;
  const auto& positions = mesh.positions;
  auto report = [&](double f, const char* stage) {
    if (options.progress) options.progress(f, stage);
  };
  report(0.0, "clustering");
  dag.clusters = buildLeafClusters(mesh, options.threads);
  parallelFor(dag.clusters.size(), options.threads, [&](size_t i) {
    dag.clusters[i].selfSphere = sphereOfClusterVertices(dag.clusters[i], positions);
  });
  EdgeSet edges;
  for (const BuildCluster& c : dag.clusters) edges.insertTriangles(c.indices);
  std::vector<uint32_t> active(dag.clusters.size());
  for (uint32_t i = 0; i < active.size(); i++) active[i] = i;
  dag.levelClusters.push_back(uint32_t(active.size()));
  dag.levelTriangles.push_back(triangleCount(dag.clusters, active));
  const double totalWork = double(dag.levelTriangles[0]) * 2.0;
  double doneWork = 0.0;

  for (uint32_t round = 1; active.size() > 1; round++) {
    report(doneWork / totalWork, "simplifying");
    std::vector<GroupPlan> plans = groupClusters(dag.clusters, active, options.groupSize);
    struct Outcome {
      SimplifiedGroup simplified;
      std::vector<BuildCluster> produced;
    };
    std::vector<Outcome> outcomes(plans.size());
    // Which groups of this round hold each vertex: a chord (a new edge between two border vertices) is
    // made by at most one group of a round, and never when some cluster already has that edge.
    std::vector<std::pair<uint32_t, uint32_t>> holders;
    for (uint32_t g = 0; g < plans.size(); g++) {
      std::vector<uint32_t> vertices;
      for (uint32_t m : plans[g].clusters) vertices.insert(vertices.end(), dag.clusters[m].indices.begin(), dag.clusters[m].indices.end());
      std::sort(vertices.begin(), vertices.end());
      vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
      for (uint32_t v : vertices) holders.push_back({v, g});
    }
    std::sort(holders.begin(), holders.end());
    auto holdersOf = [&](uint32_t v) {
      auto lo = std::lower_bound(holders.begin(), holders.end(), std::make_pair(v, 0u));
      auto hi = std::lower_bound(lo, holders.end(), std::make_pair(v + 1, 0u));
      return std::make_pair(lo, hi);
    };
    parallelFor(plans.size(), options.threads, [&](size_t g) {
      std::vector<uint32_t> indices;
      for (uint32_t m : plans[g].clusters) indices.insert(indices.end(), dag.clusters[m].indices.begin(), dag.clusters[m].indices.end());
      auto chordAllowed = [&](uint32_t a, uint32_t b) {
        if (edges.contains(uint64_t(std::min(a, b)) << 32 | std::max(a, b))) return false;
        auto [a0, a1] = holdersOf(a);
        auto [b0, b1] = holdersOf(b);
        // Of the groups holding both ends, only the first may make the chord this round.
        for (auto i = a0; i != a1; ++i)
          for (auto j = b0; j != b1; ++j)
            if (i->second == j->second && i->second < g) return false;
        return true;
      };
      outcomes[g].simplified = simplifyGroup(indices, positions, chordAllowed);
      if (outcomes[g].simplified.halved) outcomes[g].produced = splitIntoClusters(outcomes[g].simplified.indices, positions);
    });
    // Merge in group order: ids depend only on the plans, never on thread timing.
    std::vector<uint32_t> next;
    uint32_t producedCount = 0;
    for (size_t g = 0; g < plans.size(); g++) {
      Outcome& o = outcomes[g];
      if (o.simplified.relaxation > 0) dag.relaxedGroups++;
      if (!o.simplified.halved) {
        dag.stuckGroups++;
        next.insert(next.end(), plans[g].clusters.begin(), plans[g].clusters.end());
        continue;
      }
      uint32_t groupId = uint32_t(dag.groups.size());
      dag.groups.push_back(makeGroup(dag.clusters, plans[g].clusters, groupId, o.simplified.error, round - 1));
      const BuildGroup& group = dag.groups.back();
      for (BuildCluster& c : o.produced) {
        edges.insertTriangles(c.indices);
        c.selfSphere = group.sphere;
        c.selfError = group.error;
        c.producer = groupId;
        c.level = round;
        next.push_back(uint32_t(dag.clusters.size()));
        dag.clusters.push_back(std::move(c));
        producedCount++;
      }
      for (uint32_t m : plans[g].clusters) doneWork += double(dag.clusters[m].indices.size() / 3);
    }
    if (producedCount == 0) break;  // no group could be halved: what is left are the roots
    std::sort(next.begin(), next.end());
    active = std::move(next);
    dag.levelClusters.push_back(producedCount);
    dag.levelTriangles.push_back(triangleCount(dag.clusters, active));
  }

  // Root groups: the clusters left at the end, with parent error +inf so that they are always drawn
  // when nothing finer is needed.
  dag.rootClusters = uint32_t(active.size());
  std::vector<GroupPlan> roots;
  if (active.size() <= 32) roots.push_back({active, true});
  else roots = groupClusters(dag.clusters, active, options.groupSize);
  for (const GroupPlan& plan : roots) {
    uint32_t groupId = uint32_t(dag.groups.size());
    dag.groups.push_back(makeGroup(dag.clusters, plan.clusters, groupId, 0.0f, uint32_t(dag.levelClusters.size() - 1)));
    dag.groups.back().error = INFINITY;
  }
  report(1.0, "done");
  return dag;
}

}  // namespace vgeo
