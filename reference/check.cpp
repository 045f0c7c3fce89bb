// check.cpp: verifies the invariants of docs/design.md on a loaded .vgeo (see cut.h for the list).
// Coverage is checked through the groups, where the DAG decides it: a group is "coarse" for a view when
// its (error, sphere) projects to <= tau; then its members are not drawn and its products stand in for
// them, each of which must in turn be drawn or be replaced by a coarse group of its own, exactly once.
// A leaf is covered once when it is drawn, or its group is coarse and that group's products all cover
// once. Any product that covers its share zero times (a hole) or twice (an overlap) is a violation.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <sstream>

#include "cut.h"

namespace vgeo {
namespace {

std::string str(glm::vec3 v) {
  std::ostringstream s;
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}
bool encloses(glm::vec4 outer, glm::vec4 inner) {
  return glm::distance(glm::dvec3(outer), glm::dvec3(inner)) + double(inner.w) <= double(outer.w);
}
bool sameSphere(glm::vec4 a, glm::vec4 b) { return std::memcmp(&a, &b, sizeof(a)) == 0; }

struct GeometryChecker {
  const VgeoData& d;
  uint32_t gi;
  const shaderio::Geometry& g;
  std::string violation;

  bool fail(const std::string& what) {
    if (violation.empty()) violation = "geometry " + std::to_string(gi) + ": " + what;
    return false;
  }

  bool structure() {
    std::map<uint32_t, uint32_t> firstProduct;
    for (uint32_t i = g.clusterOffset; i < g.clusterOffset + g.clusterCount; i++) {
      const shaderio::Cluster& c = d.clusters[i];
      std::string name = "cluster " + std::to_string(i);
      uint32_t tc = shaderio::clusterTriangleCount(c.counts);
      if (tc == 0 || tc > VGEO_MAX_CLUSTER_TRIANGLES)
        return fail(name + " has " + std::to_string(tc) + " triangles (invariant 1)");
      if (c.group < g.groupOffset || c.group >= g.groupOffset + g.groupCount)
        return fail(name + " belongs to another geometry's group");
      const shaderio::Group& grp = d.groups[c.group];
      if (i < grp.clusterOffset || i >= grp.clusterOffset + grp.clusterCount)
        return fail(name + " lies outside its group's member run");
      if (c.parentError != grp.error || !sameSphere(c.parentSphere, grp.sphere))
        return fail(name + ": parent (error, sphere) differs from its group's (invariant 2)");
      if (c.producer == VGEO_NO_GROUP) {
        // Leaves: the largest chord error of their faces against the limit surface (0 without patches).
        float chord = 0.0f;
        for (uint32_t k = 0; k < shaderio::clusterCageFaceCount(c.counts); k++)
          chord = std::max(chord, d.patches[c.cageFaceOffset + k].faceError);
        if (c.selfError != chord) return fail(name + ": leaf self error is not its faces' largest chord error");
      } else {
        const shaderio::Group& prod = d.groups[c.producer];
        if (c.selfError != prod.error || !sameSphere(c.selfSphere, prod.sphere))
          return fail(name + ": self (error, sphere) differs from its producing group's (invariant 2)");
        firstProduct.emplace(c.producer, i);
      }
      if (!(grp.error >= c.selfError))
        return fail(name + ": its group's error " + std::to_string(grp.error) + " is below its self error " +
                    std::to_string(c.selfError) + " (invariant 3)");
      if (!encloses(grp.sphere, c.selfSphere))
        return fail(name + ": its group's sphere does not enclose its self sphere (invariant 3)");
      for (uint32_t k = 0; k < shaderio::clusterVertexCount(c.counts); k++) {
        glm::vec3 p = d.position(d.clusterVertices[c.vertexOffset + k]);
        if (glm::distance(glm::dvec3(p), glm::dvec3(c.selfSphere)) > double(c.selfSphere.w))
          return fail(name + ": vertex " + str(p) + " lies outside its self sphere");
      }
    }
    // Groups: members are one run and each member names the group.
    for (uint32_t gr = g.groupOffset; gr < g.groupOffset + g.groupCount; gr++) {
      const shaderio::Group& grp = d.groups[gr];
      if (grp.clusterCount == 0) return fail("group " + std::to_string(gr) + " is empty");
      for (uint32_t i = grp.clusterOffset; i < grp.clusterOffset + grp.clusterCount; i++)
        if (d.clusters[i].group != gr)
          return fail("group " + std::to_string(gr) + "'s run holds cluster " + std::to_string(i) +
                      " of another group");
      if (std::isinf(grp.error) && firstProduct.count(gr))
        return fail("root group " + std::to_string(gr) + " produced clusters");
      if (!std::isinf(grp.error) && !firstProduct.count(gr))
        return fail("group " + std::to_string(gr) + " produced no cluster");
    }
    // BVH: spheres enclose, max errors bound, each group reached once.
    std::vector<uint32_t> reached(g.groupCount, 0);
    std::function<bool(uint32_t)> walk = [&](uint32_t n) {
      const shaderio::BvhNode& node = d.nodes[n];
      uint32_t count = node.childCountAndFlags & ~VGEO_NODE_LEAF_BIT;
      for (uint32_t k = 0; k < count; k++) {
        uint32_t child = node.childOffset + k;
        glm::vec4 sphere;
        float error;
        if (node.childCountAndFlags & VGEO_NODE_LEAF_BIT) {
          if (child < g.groupOffset || child >= g.groupOffset + g.groupCount)
            return fail("BVH node " + std::to_string(n) + " holds another geometry's group");
          reached[child - g.groupOffset]++;
          sphere = d.groups[child].sphere;
          error = d.groups[child].error;
        } else {
          if (!walk(child)) return false;
          sphere = d.nodes[child].sphere;
          error = d.nodes[child].maxError;
        }
        if (!encloses(node.sphere, sphere))
          return fail("BVH node " + std::to_string(n) + "'s sphere does not enclose child " + std::to_string(k));
        if (!(node.maxError >= error))
          return fail("BVH node " + std::to_string(n) + "'s max error is below child " + std::to_string(k) + "'s");
      }
      return true;
    };
    if (!walk(g.nodeOffset)) return false;
    for (uint32_t i = 0; i < g.groupCount; i++)
      if (reached[i] != 1)
        return fail("group " + std::to_string(g.groupOffset + i) + " is reached " + std::to_string(reached[i]) +
                    " times by the BVH");
    return true;
  }

  // Leaves on the limit surface: every patch passes through its four corners' leaf vertices. Crack-free
  // tessellation: neighbours name each other across the same edge, agree on its chord error and on
  // whether it is locked, and an edge with a flat face on either side is locked.
  bool patches(uint64_t& checked) {
    static const float kCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    // Relative to the geometry's size, but never below what float arithmetic resolves at its
    // coordinates: a small part far from the origin (CGAL's fold.off: 0.4 wide at x = 43) evaluates
    // its patches to within a few units in the last place of those coordinates, not of its size.
    const double magnitude = glm::length(glm::dvec3(g.boundsSphere)) + double(g.boundsSphere.w);
    const double tolerance =
        std::max(1e-5 * std::max(double(g.boundsSphere.w), 1e-6), 16.0 * double(FLT_EPSILON) * magnitude);
    for (uint32_t f = g.cageFaceOffset; f < g.cageFaceOffset + g.cageFaceCount; f++) {
      const shaderio::Patch& patch = d.patches[f];
      const std::string what = "cage face " + std::to_string(f);
      const uint32_t kind = shaderio::patchKind(patch.info);
      for (uint32_t k = 0; k < 4; k++) {
        uint32_t n = patch.neighbours[k];
        if (n == VGEO_INVALID) continue;
        const shaderio::Patch& other = d.patches[n >> 2];
        if (other.neighbours[n & 3] != (f << 2 | k))
          return fail(what + ": its neighbour across edge " + std::to_string(k) + " does not name it back");
        if (other.edgeError[n & 3] != patch.edgeError[k])
          return fail(what + ": the two faces of edge " + std::to_string(k) + " disagree on its chord error");
        if (shaderio::patchEdgeLocked(other.info, n & 3) != shaderio::patchEdgeLocked(patch.info, k))
          return fail(what + ": the two faces of edge " + std::to_string(k) + " disagree on whether it is locked");
        if ((kind == VGEO_PATCH_NONE || shaderio::patchKind(other.info) == VGEO_PATCH_NONE) &&
            !shaderio::patchEdgeLocked(patch.info, k))
          return fail(what + ": edge " + std::to_string(k) + " touches a flat face but is not locked");
      }
      if (kind == VGEO_PATCH_NONE) continue;
      const shaderio::CageFace& face = d.cageFaces[f];
      checked++;
      for (int k = 0; k < 4; k++) {
        glm::vec3 limit = d.evaluatePatch(f, kCorner[k][0], kCorner[k][1]);
        glm::vec3 corner = d.position(d.cageFaceVertices[face.firstVertex + uint32_t(k)]);
        if (glm::distance(glm::dvec3(limit), glm::dvec3(corner)) > tolerance)
          return fail(what + ": its patch's corner " + str(limit) + " is not its leaf vertex " + str(corner));
      }
    }
    return true;
  }

  // Vertex ids matched by position for closed geometries (copies at one position count as one vertex).
  // Open ones are matched by id: their repair may have split non-manifold edges into coincident
  // borders, which matched by position would look like overlaps already at the finest level.
  std::vector<uint32_t> canonical;
  std::vector<std::vector<uint32_t>> products;  // per group (relative), the clusters it produced
  void prepare() {
    std::map<std::array<uint32_t, 3>, uint32_t> byPosition;
    canonical.resize(g.vertexCount);
    for (uint32_t v = 0; v < g.vertexCount; v++) {
      glm::vec3 p = d.position(g.vertexOffset + v);
      std::array<uint32_t, 3> key;
      std::memcpy(key.data(), &p, 12);
      canonical[v] = (g.flags & VGEO_GEOMETRY_CLOSED) ? byPosition.emplace(key, v).first->second : v;
    }
    products.assign(g.groupCount, {});
    for (uint32_t i = g.clusterOffset; i < g.clusterOffset + g.clusterCount; i++)
      if (d.clusters[i].producer != VGEO_NO_GROUP) products[d.clusters[i].producer - g.groupOffset].push_back(i);
  }

  bool cut(const LodView& view, const std::string& name, uint64_t& clusters, uint64_t& triangles) {
    std::vector<uint32_t> drawn = selectCut(d, gi, view);
    std::vector<uint8_t> isDrawn(g.clusterCount, 0);
    for (uint32_t c : drawn) isDrawn[c - g.clusterOffset] = 1;
    clusters += drawn.size();
    // Watertight: directed edges by canonical vertex.
    std::vector<uint64_t> edges;
    for (uint32_t ci : drawn) {
      const shaderio::Cluster& c = d.clusters[ci];
      for (uint32_t t = 0; t < shaderio::clusterTriangleCount(c.counts); t++) {
        uint32_t tri = d.clusterTriangles[c.triangleOffset + t], v[3];
        for (int k = 0; k < 3; k++)
          v[k] = canonical[d.clusterVertices[c.vertexOffset + ((tri >> (8 * k)) & 0xff)] - g.vertexOffset];
        for (int k = 0; k < 3; k++) edges.push_back(uint64_t(v[k]) << 32 | v[(k + 1) % 3]);
        triangles++;
      }
    }
    std::sort(edges.begin(), edges.end());
    const bool closed = g.flags & VGEO_GEOMETRY_CLOSED;
    auto edgeName = [&](uint64_t e) {
      return "edge " + str(d.position(g.vertexOffset + uint32_t(e >> 32))) + "-" +
             str(d.position(g.vertexOffset + uint32_t(e)));
    };
    for (size_t i = 0; i < edges.size(); i++) {
      if (i + 1 < edges.size() && edges[i] == edges[i + 1])
        return fail(name + ": " + edgeName(edges[i]) + " is covered twice in one direction (overlap, invariant 5)");
      uint64_t reverse = (edges[i] << 32) | (edges[i] >> 32);
      if (closed && !std::binary_search(edges.begin(), edges.end(), reverse))
        return fail(name + ": " + edgeName(edges[i]) + " has one triangle (crack, invariant 5)");
    }
    // Coverage through the groups.
    auto coarse = [&](uint32_t group) {
      const shaderio::Group& grp = d.groups[group];
      return shaderio::projectedError(grp.sphere, grp.error, view.eye, view.projScale, view.znear) <= view.tau;
    };
    // How many times a coarse group's region is covered from its products up; kUneven when its
    // products disagree (then part of the region has a hole or an overlap).
    constexpr int kUnknown = -1, kUneven = -2;
    std::vector<int> memo(g.groupCount, kUnknown);
    std::function<int(uint32_t)> coverAbove = [&](uint32_t group) -> int {
      int& m = memo[group - g.groupOffset];
      if (m != kUnknown) return m;
      int value = kUnknown;
      for (uint32_t p : products[group - g.groupOffset]) {
        int v = isDrawn[p - g.clusterOffset];
        if (coarse(d.clusters[p].group)) {
          int above = coverAbove(d.clusters[p].group);
          v = above == kUneven ? kUneven : v + above;
        }
        if (v == kUneven || (value != kUnknown && v != value)) {
          value = kUneven;
          break;
        }
        value = v;
      }
      return m = value;
    };
    for (uint32_t i = g.clusterOffset; i < g.clusterOffset + g.clusterCount; i++) {
      const shaderio::Cluster& c = d.clusters[i];
      if (c.producer != VGEO_NO_GROUP) continue;
      int count = isDrawn[i - g.clusterOffset];
      if (coarse(c.group)) {
        int above = coverAbove(c.group);
        count = above == kUneven ? kUneven : count + above;
      }
      if (count != 1)
        return fail(name + ": leaf cluster " + std::to_string(i) + " is covered " +
                    (count == 0         ? std::string("zero times (hole)")
                     : count == kUneven ? std::string("unevenly (a hole or overlap above it)")
                                        : std::to_string(count) + " times (overlap)"));
    }
    return true;
  }
};

}  // namespace

CheckResult checkVgeo(const VgeoData& data, const CheckOptions& options) {
  CheckResult result;
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  uint64_t totalClusters = 0, totalGroups = 0, checkedCuts = 0;
  uint32_t maxLevels = 0;
  for (uint32_t gi = 0; gi < data.geometries.size(); gi++) {
    const shaderio::Geometry& g = data.geometries[gi];
    GeometryChecker checker{data, gi, g, {}, {}, {}};
    totalClusters += g.clusterCount;
    totalGroups += g.groupCount;
    maxLevels = std::max(maxLevels, g.levelCount);
    for (uint32_t i = g.clusterOffset; i < g.clusterOffset + g.clusterCount; i++)
      if (std::isinf(data.clusters[i].parentError)) result.rootClusters++;
    if (checker.structure() && checker.patches(result.checkedPatches)) {
      checker.prepare();
      glm::vec3 center(g.boundsSphere);
      float radius = std::max(g.boundsSphere.w, 1e-6f);
      for (uint32_t k = 0; k < options.cuts && checker.violation.empty(); k++) {
        // Directions uniform on the sphere, distances from inside the bounds to 30 radii, tau 0.5..32 px.
        float z = 2.0f * unit(rng) - 1.0f, a = 6.2831853f * unit(rng);
        glm::vec3 dir(std::sqrt(1.0f - z * z) * std::cos(a), std::sqrt(1.0f - z * z) * std::sin(a), z);
        LodView view;
        view.eye = center + dir * radius * std::pow(10.0f, -1.0f + 2.5f * unit(rng));
        view.projScale = 1080.0f / (2.0f * std::tan(0.5f * 1.0471976f));
        view.znear = radius * 1e-4f;
        view.tau = std::pow(2.0f, -1.0f + 6.0f * unit(rng));
        std::ostringstream name;
        name << "cut " << k << " (eye " << str(view.eye) << ", tau " << view.tau << ")";
        checker.cut(view, name.str(), result.cutClusters, result.cutTriangles);
        checkedCuts++;
      }
    }
    if (!checker.violation.empty()) {
      result.ok = false;
      result.firstViolation = checker.violation;
      return result;
    }
  }
  std::ostringstream s;
  s << "ok: " << data.geometries.size() << " geometries, " << data.instances.size() << " instances, " << totalClusters
    << " clusters, " << totalGroups << " groups, up to " << maxLevels << " levels, " << result.rootClusters
    << " root clusters, " << result.checkedPatches << " patches through their leaf vertices; " << checkedCuts
    << " random cuts watertight and covering every leaf once (mean "
    << (checkedCuts ? result.cutClusters / checkedCuts : 0) << " clusters, "
    << (checkedCuts ? result.cutTriangles / checkedCuts : 0) << " triangles)";
  result.summary = s.str();
  return result;
}

}  // namespace vgeo
