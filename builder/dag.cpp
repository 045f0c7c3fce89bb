// dag.cpp: the LOD DAG (Nanite's scheme, Karis 2021): leaf clusters, then rounds of
// group -> simplify to half with the group border locked -> split into new clusters, until one cluster is
// left or no group can be halved. Errors and spheres follow docs/design.md: a group's error is the largest
// of its members' self errors and its own simplification error, and its sphere encloses the members'
// self spheres, so both only grow toward the root (monotonic), and the clusters a group produces take
// the group's (error, sphere) as their self pair.
#include <algorithm>
#include <atomic>
#include <cmath>

#include "../common/bucket_sort.h"
#include "../common/parallel.h"
#include "builder.h"
#include "chord_rule.h"

namespace vgeo {
namespace {

uint64_t triangleCount(const std::vector<BuildCluster>& clusters, const std::vector<uint32_t>& ids) {
  uint64_t n = 0;
  for (uint32_t id : ids) n += clusters[id].indices.size() / 3;
  return n;
}

// The sphere of a cluster's distinct vertices, in ascending order: found by hashing (localIds), so that
// the sort is of its vertices rather than of all its corners (three times as many, most repeated).
glm::vec4 sphereOfClusterVertices(const BuildCluster& c, const std::vector<glm::vec3>& positions) {
  std::vector<uint32_t> v, local;
  localIds(c.indices, v, local);
  std::sort(v.begin(), v.end());
  return sphereOfPoints(positions, v.data(), v.size());
}

// The group of `members`: its sphere encloses their self spheres, and its error is the larger of
// their errors and this simplification's own (a Hausdorff distance to the group's input): monotonic, as
// invariant 3 needs. Summing them instead, an upper bound of the distance to the leaves, tripled the
// triangles drawn at tau = 1 for no visible gain (tests/Render).
BuildGroup groupOf(const std::vector<BuildCluster>& clusters, const std::vector<uint32_t>& members, float addedError,
                   uint32_t level) {
  BuildGroup g;
  g.members = members;
  g.level = level;
  std::vector<glm::vec4> spheres;
  float maxError = 0.0f;
  for (uint32_t m : members) {
    spheres.push_back(clusters[m].selfSphere);
    maxError = std::max(maxError, clusters[m].selfError);
  }
  g.sphere = sphereOfSpheres(spheres.data(), spheres.size());
  g.error = std::max(maxError, addedError);
  return g;
}

// Adds the group to the DAG and names it in its members; returns its id.
uint32_t addGroup(Dag& dag, BuildGroup&& group) {
  const uint32_t id = uint32_t(dag.groups.size());
  for (uint32_t m : group.members) dag.clusters[m].group = id;
  dag.groups.push_back(std::move(group));
  return id;
}

// Repair leaves every edge with at most two faces of opposite orientation, but a face's triangulation
// may still fold onto a neighbour (a quad's diagonal running along another face's edge, faces meeting
// at a sliver): a directed edge held by two leaf triangles could never be covered once by a cut.
void checkNoFold(const std::vector<BuildCluster>& clusters, const std::vector<glm::vec3>& positions, int threads) {
  const FillLaterVector<uint64_t> directed = bucketSorted<uint64_t>(
      clusters.size(), bitsFor(positions.size()), bitsFor(positions.size()), threads,
      [&](size_t i, auto&& emit) {
        const std::vector<uint32_t>& idx = clusters[i].indices;
        for (size_t t = 0; t + 2 < idx.size(); t += 3)
          for (size_t k = 0; k < 3; k++) emit(idx[t + k], uint64_t(idx[t + k]) << 32 | idx[t + (k + 1) % 3]);
      },
      std::less<uint64_t>());
  size_t first = SIZE_MAX;  // the first edge held twice, in sorted order (the same message on any thread count)
  parallelForRanges(directed.size(), threads, [&](size_t begin, size_t end) {
    for (size_t i = std::max<size_t>(begin, 1); i < end; i++)
      if (directed[i] == directed[i - 1]) {
        atomicMin(first, i);
        return;
      }
  });
  if (first == SIZE_MAX) return;
  const glm::vec3 a = positions[directed[first] >> 32], b = positions[directed[first] & 0xffffffffu];
  char text[320];
  std::snprintf(
      text, sizeof text,
      "the surface folds onto itself: two triangles run the same way along the edge (%g, %g, %g)-(%g, %g, %g)",
      double(a.x), double(a.y), double(a.z), double(b.x), double(b.y), double(b.z));
  throw SurfaceError(text);
}

// Leaf clusters of the mesh, with their own spheres and (from the limit surface, when given) errors.
std::vector<BuildCluster> makeLeafClusters(const PolygonMesh& mesh, const BuildOptions& options) {
  std::vector<BuildCluster> clusters = buildLeafClusters(mesh, options.threads, options.shading, options.leafFaces);
  if (!options.leavesAreRepairedFaces) checkNoFold(clusters, mesh.positions, options.threads);
  parallelFor(clusters.size(), options.threads, [&](size_t i) {
    BuildCluster& c = clusters[i];
    c.border = edgesUsedOnce(c.indices);  // for the first round's grouping and chord rule
    c.selfSphere = sphereOfClusterVertices(c, mesh.positions);
    if (options.leafFaceErrors && !options.leafFaceErrors->empty())
      for (uint32_t f : c.cageFaces) c.selfError = std::max(c.selfError, (*options.leafFaceErrors)[f].face);
  });
  return clusters;
}

// What a group of `triangles` is simplified to: the multiple of kClusterFill nearest half of it, so
// that the split can fill every cluster it makes (half of 1,890 triangles, 945, would make eight
// clusters of 118). Held under 52% of the group, below what counts as halved; a group of fewer than
// two clusters' worth goes to half.
size_t simplifyTarget(size_t triangles) {
  constexpr double kMostKept = 0.52;
  size_t clusters = (triangles / 2 + kClusterFill / 2) / kClusterFill;
  if (clusters * kClusterFill > size_t(double(triangles) * kMostKept)) clusters--;
  return clusters > 0 ? clusters * kClusterFill : triangles / 2;
}

struct GroupOutcome {
  SimplifiedGroup simplified;
  BuildGroup group;  // when halved
  std::vector<BuildCluster> produced;
};

// The bounds of the DAG's clusters (ClusterBounds, for the layout), found a few clusters at a time by
// threads that would otherwise wait on a round's last groups, the rest once the rounds are done. The
// clusters made before a round do not change during it; a cluster's bounds do not depend on when or
// where they are found.
class BoundsFinder {
 public:
  BoundsFinder(Dag& dag, const std::vector<glm::vec3>& positions, const ShadingNormals* shading)
      : dag_(dag), positions_(positions), shading_(shading) {}
  // Before a round: the clusters made so far may be taken from now on (the pieces handed out past the
  // last round's are taken back).
  void startRound() {
    dag_.bounds.resize(dag_.clusters.size());
    next_.store(std::min(next_.load(), end_));
    end_ = dag_.clusters.size();
  }
  // During a round, from any thread: finds the bounds of the next few clusters; false when none is left.
  bool findSome() {
    const size_t first = next_.fetch_add(kClustersAPiece, std::memory_order_relaxed);
    if (first >= end_) return false;
    for (size_t id = first; id < std::min(end_, first + kClustersAPiece); id++)
      dag_.bounds[id] = clusterBounds(dag_.clusters[id], positions_, shading_);
    return true;
  }
  // After the rounds: the rest, on the threads.
  void finish(int threads) {
    startRound();
    const size_t first = next_.load();
    parallelFor(end_ - first, threads, [&](size_t i) {
      dag_.bounds[first + i] = clusterBounds(dag_.clusters[first + i], positions_, shading_);
    });
  }

 private:
  static constexpr size_t kClustersAPiece = 4;  // tens of microseconds: a round ends at most that late
  Dag& dag_;
  const std::vector<glm::vec3>& positions_;
  const ShadingNormals* shading_;
  std::atomic<size_t> next_{0};
  size_t end_ = 0;
};

// Each planned group's triangles simplified to half with its border locked, then split into clusters;
// the groups of round `round`'s clusters, made at level round - 1. Threads left without a group find
// clusters' bounds meanwhile.
std::vector<GroupOutcome> simplifyGroups(const std::vector<GroupPlan>& plans, const std::vector<BuildCluster>& clusters,
                                         const std::vector<glm::vec3>& positions, const ChordRule& chords,
                                         const std::vector<uint64_t>& openEdges, uint32_t round,
                                         const BuildOptions& options, BoundsFinder& bounds) {
  std::vector<GroupOutcome> outcomes(plans.size());
  // Largest groups first, so that the round does not end waiting on a large one started last.
  std::vector<std::pair<uint64_t, uint32_t>> bySize(plans.size());
  for (uint32_t g = 0; g < plans.size(); g++) bySize[g] = {~triangleCount(clusters, plans[g].clusters), g};
  std::sort(bySize.begin(), bySize.end());
  parallelForInOrder(
      plans.size(), options.threads,
      [&](size_t i) {
        const size_t g = bySize[i].second;
        std::vector<uint32_t> indices;
        for (uint32_t m : plans[g].clusters)
          indices.insert(indices.end(), clusters[m].indices.begin(), clusters[m].indices.end());
        auto chordAllowed = [&](uint32_t a, uint32_t b) { return chords.allowed(uint32_t(g), a, b); };
        outcomes[g].simplified =
            simplifyGroup(indices, positions, chordAllowed, openEdges, simplifyTarget(indices.size() / 3));
        if (outcomes[g].simplified.halved) {
          outcomes[g].group = groupOf(clusters, plans[g].clusters, outcomes[g].simplified.error, round - 1);
          outcomes[g].produced = splitIntoClusters(outcomes[g].simplified, positions, options.shading);
        }
        std::vector<uint32_t>().swap(outcomes[g].simplified.indices);  // held as the clusters now
        std::vector<uint32_t>().swap(outcomes[g].simplified.globals);
      },
      [&] { return bounds.findSome(); });
  return outcomes;
}

// Adds the round's groups and the clusters they produced to the DAG, in group order (ids depend only on
// the plans, never on thread timing); returns the next round's active clusters. A group that could not
// be halved passes its clusters on as they are.
std::vector<uint32_t> addRound(Dag& dag, const std::vector<GroupPlan>& plans, std::vector<GroupOutcome>& outcomes,
                               uint32_t round) {
  std::vector<uint32_t> next;
  for (size_t g = 0; g < plans.size(); g++) {
    GroupOutcome& o = outcomes[g];
    if (o.simplified.relaxation > 0) dag.relaxedGroups++;
    if (!o.simplified.halved) {
      dag.stuckGroups++;
      next.insert(next.end(), plans[g].clusters.begin(), plans[g].clusters.end());
      continue;
    }
    const uint32_t groupId = addGroup(dag, std::move(o.group));
    const BuildGroup& group = dag.groups.back();
    for (BuildCluster& c : o.produced) {
      c.selfSphere = group.sphere;
      c.selfError = group.error;
      c.producer = groupId;
      c.level = round;
      next.push_back(uint32_t(dag.clusters.size()));
      dag.clusters.push_back(std::move(c));
    }
  }
  std::sort(next.begin(), next.end());
  return next;
}

// Root groups: the clusters left at the end, with parent error +inf so that they are always drawn when
// nothing finer is needed.
void addRootGroups(Dag& dag, const std::vector<uint32_t>& active, const std::vector<glm::vec3>& positions,
                   const BuildOptions& options) {
  dag.rootClusters = uint32_t(active.size());
  std::vector<uint32_t> rootIndices;
  for (uint32_t c : active)
    rootIndices.insert(rootIndices.end(), dag.clusters[c].indices.begin(), dag.clusters[c].indices.end());
  dag.roots = surfaceTopology(rootIndices);
  std::vector<GroupPlan> roots;
  if (active.size() <= 32)
    roots.push_back({active, true});
  else
    roots = groupClusters(dag.clusters, active, positions, options.groupSize, options.threads);
  for (const GroupPlan& plan : roots) {
    addGroup(dag, groupOf(dag.clusters, plan.clusters, 0.0f, uint32_t(dag.levelClusters.size() - 1)));
    dag.groups.back().error = INFINITY;
  }
}

// The borders of clusters `ids`, read by their round only.
void freeBorders(std::vector<BuildCluster>& clusters, const std::vector<uint32_t>& ids, int threads) {
  parallelFor(ids.size(), threads, [&](size_t i) { std::vector<uint64_t>().swap(clusters[ids[i]].border); });
}

// A root of at most this many triangles (a far instance draws it): 8, a square-ish shape's fewest, where
// 16 drew 14-triangle roots for armadillos that each cover a few pixels.
constexpr uint64_t kSmallestRoot = 8;  // triangles

}  // namespace

// The build loop: leaves, then rounds of group -> simplify -> split -> add, then the roots, then the
// bounds of the clusters that the rounds' idle threads did not reach.
Dag buildDag(const PolygonMesh& mesh, const BuildOptions& options) {
  auto report = [&](double f, const char* stage) {
    if (options.progress) options.progress(f, stage);
  };
  report(0.0, "clustering");
  Dag dag;
  StageTimes* times = options.times;
  dag.clusters = timed(times, "leaf clusters", [&] { return makeLeafClusters(mesh, options); });
  ChordRule chords = timed(times, "chord rule", [&] { return ChordRule(mesh.positions.size(), options.threads); });
  std::vector<uint32_t> active(dag.clusters.size());
  for (uint32_t i = 0; i < active.size(); i++) active[i] = i;
  dag.levelClusters.push_back(uint32_t(active.size()));
  dag.levelTriangles.push_back(triangleCount(dag.clusters, active));
  const double totalWork = double(dag.levelTriangles[0]) * 2.0;
  double doneWork = 0.0;
  size_t unrecorded = 0;  // the first cluster whose edges are not in the chord rule's set yet
  BoundsFinder bounds(dag, mesh.positions, options.shading);

  // Go on while more than one cluster is left, and then keep halving the last one down to a few
  // triangles: far away, an instance costs only its root, so a small root keeps the triangles drawn
  // in proportion to the pixels covered. A mesh whose leaves fit one cluster (a box) keeps it: it has
  // no coarser level that could look like it.
  for (uint32_t round = 1; active.size() > 1 || (round > 1 && triangleCount(dag.clusters, active) > kSmallestRoot);
       round++) {
    report(doneWork / totalWork, "simplifying");
    // The last round's clusters' edges go into the chord rule's set beside this round's partition into
    // groups, which does not read it: the inserts fill the threads that the grouping leaves idle. The set's
    // room is made first: memory allocated by two threads at once, each in its own malloc arena,
    // raised the peak. The inserts' wall time counts as the chord rule's and as grouping's.
    timed(times, "chord rule",
          [&] { chords.makeRoom(dag.clusters, unrecorded, unrecorded == 0 ? nullptr : &active, options.threads); });
    StageTimes insertTimes;  // its own: the inserts stop their timer on another thread
    auto recordEdges = [&] {
      StageTimer recording(&insertTimes, "chord rule");
      chords.addClusters(dag.clusters, unrecorded, options.threads);
    };
    std::vector<uint64_t> openEdges;
    const std::vector<GroupPlan> plans = timed(times, "grouping", [&] {
      return groupClusters(dag.clusters, active, mesh.positions, options.groupSize, options.threads, &openEdges,
                           recordEdges);
    });
    if (times)
      for (const auto& [stage, seconds] : insertTimes.seconds) times->add(stage, seconds);
    timed(times, "chord rule", [&] {
      chords.startRound(plans, dag.clusters, options.threads);
      freeBorders(dag.clusters, active, options.threads);
    });
    std::vector<GroupOutcome> outcomes = timed(times, "simplify and split", [&] {
      bounds.startRound();
      return simplifyGroups(plans, dag.clusters, mesh.positions, chords, openEdges, round, options, bounds);
    });
    unrecorded = dag.clusters.size();
    std::vector<uint32_t> next = timed(times, "add round", [&] {
      std::vector<uint32_t> added = addRound(dag, plans, outcomes, round);
      for (size_t g = 0; g < plans.size(); g++)
        if (outcomes[g].simplified.halved) doneWork += double(triangleCount(dag.clusters, plans[g].clusters));
      return added;
    });
    const uint32_t producedCount = uint32_t(dag.clusters.size() - unrecorded);
    if (producedCount == 0) break;  // no group could be halved: what is left are the roots
    active = std::move(next);
    dag.levelClusters.push_back(producedCount);
    dag.levelTriangles.push_back(triangleCount(dag.clusters, active));
  }
  timed(times, "root groups", [&] {
    addRootGroups(dag, active, mesh.positions, options);
    freeBorders(dag.clusters, active, options.threads);
  });
  timed(times, "cluster bounds", [&] { bounds.finish(options.threads); });
  report(1.0, "done");
  return dag;
}

}  // namespace vgeo
