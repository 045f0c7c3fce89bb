// test_patch.cpp: the limit-surface patches of cage faces (patch.cpp, shaders/patch_eval.h): regular
// B-spline patches and rings around extraordinary vertices must be the Catmull-Clark limit surface (at
// dyadic parameters exactly the limit points of the mesh subdivided further; anywhere, close to the
// mesh subdivided 6 more levels), neighbours must meet with the same position and normal, chord errors
// must bound the leaf triangles' distance, and the .vgeo must carry all of it.
#include <cmath>
#include <map>
#include <unordered_map>

#include "test_util.h"

namespace vgeo {
namespace {

PolygonMesh cage(const std::string& path, int levels) {
  PolygonMesh m = loadMeshFile(path).meshes[0];
  repairMesh(m, path);
  for (int l = 0; l < levels; l++) m = subdivideCatmullClark(m);
  return m;
}

// A hexagonal prism of two hexagons and six quads: after one round its hexagons' face points have
// valence 6 and its corners valence 3.
std::string hexagonalPrism(const std::string& dir) {
  std::string obj;
  for (int z = 0; z < 2; z++)
    for (int i = 0; i < 6; i++)
      obj += "v " + std::to_string(std::cos(i * 1.0471976)) + " " + std::to_string(std::sin(i * 1.0471976)) + " " + std::to_string(z * 1.3) + "\n";
  obj += "f 6 5 4 3 2 1\nf 7 8 9 10 11 12\n";
  for (int i = 0; i < 6; i++) {
    int a = i + 1, b = (i + 1) % 6 + 1;
    obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(b + 6) + " " + std::to_string(a + 6) + "\n";
  }
  return test::writeFile(dir, "hexagonal_prism.obj", obj);
}

float diagonal(const std::vector<glm::vec3>& points) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const auto& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::distance(lo, hi);
}

float degrees(glm::vec3 a, glm::vec3 b) {
  return float(std::acos(std::clamp(double(glm::dot(glm::normalize(a), glm::normalize(b))), -1.0, 1.0)) * 57.29577951);
}

// Face parameters of t along edge k (from corner k to corner k + 1).
glm::vec2 onEdge(int k, float t) {
  switch (k) {
    case 0: return {t, 0.0f};
    case 1: return {1.0f, t};
    case 2: return {1.0f - t, 1.0f};
    default: return {0.0f, 1.0f - t};
  }
}

// Nearest vertex lookups in a uniform grid.
struct PointGrid {
  PointGrid(const std::vector<glm::vec3>& points, float cell) : points_(points), cell_(cell) {
    for (uint32_t v = 0; v < points.size(); v++) cells_[key(cellOf(points[v]))].push_back(v);
  }
  uint32_t nearest(glm::vec3 p, float& distance) const {
    distance = INFINITY;
    uint32_t best = 0;
    for (int dx = -1; dx <= 1; dx++)
      for (int dy = -1; dy <= 1; dy++)
        for (int dz = -1; dz <= 1; dz++) {
          auto it = cells_.find(key(cellOf(p) + glm::ivec3(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (uint32_t v : it->second)
            if (glm::distance(p, points_[v]) < distance) distance = glm::distance(p, points_[v]), best = v;
        }
    return best;
  }

 private:
  glm::ivec3 cellOf(glm::vec3 p) const { return glm::ivec3(glm::floor(p / cell_)); }
  static uint64_t key(glm::ivec3 c) {
    return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) | (uint32_t(c.z) & 0x1fffff);
  }
  const std::vector<glm::vec3>& points_;
  float cell_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

struct Accuracy {
  size_t regular = 0, ring = 0, none = 0;
  float regularWorst = 0.0f, ringWorst = 0.0f, normalWorst = 0.0f;
};

// Every patch of `coarse` at parameters (i / steps, j / steps) against the nearest vertex of `fine`
// (distances relative to the diagonal) and that vertex's normal.
Accuracy compare(const PolygonMesh& coarse, const std::vector<glm::vec3>& fine, const std::vector<glm::vec3>& fineNormals, int steps) {
  Patcher patcher(coarse);
  const float d = diagonal(coarse.positions);
  PointGrid grid(fine, d * 2e-3f);
  Accuracy a;
  for (uint32_t f = 0; f < coarse.faceCount(); f++) {
    FacePatch patch = patcher.patch(f);
    if (patch.kind == VGEO_PATCH_NONE) {
      a.none++;
      continue;
    }
    (patch.kind == VGEO_PATCH_REGULAR ? a.regular : a.ring)++;
    float& worst = patch.kind == VGEO_PATCH_REGULAR ? a.regularWorst : a.ringWorst;
    for (int i = 0; i <= steps; i++)
      for (int j = 0; j <= steps; j++) {
        glm::vec3 normal, p = evaluateFacePatch(patch, coarse.positions, float(i) / float(steps), float(j) / float(steps), &normal);
        float distance;
        uint32_t v = grid.nearest(p, distance);
        worst = std::max(worst, distance / d);
        if (std::isfinite(distance)) a.normalWorst = std::max(a.normalWorst, degrees(normal, fineNormals[v]));
      }
  }
  return a;
}

TEST(Patch, PatchesAreTheLimitSurfaceAtDyadicParameters) {
  // Two more rounds: the vertex at (i/4, j/4) of every face, moved to the limit, is exactly a patch point.
  PolygonMesh coarse = cage(test::asset("horned_cube.obj"), 2), fine = cage(test::asset("horned_cube.obj"), 4);
  std::vector<glm::vec3> fineNormals;
  ASSERT_TRUE(moveToLimit(fine, fineNormals));
  Accuracy a = compare(coarse, fine.positions, fineNormals, 4);
  EXPECT_GT(a.regular, coarse.faceCount() / 2) << "most faces of a subdivided cage are regular";
  EXPECT_GT(a.ring, 0u) << "faces at the cube's corners (valence 3) are rings";
  EXPECT_EQ(a.none, 0u) << "a closed cage after two rounds has a patch on every face";
  EXPECT_LT(a.regularWorst, 1e-6f);
  EXPECT_LT(a.ringWorst, 2e-6f);
  EXPECT_LT(a.normalWorst, 0.05f);  // float derivatives shrink towards an extraordinary vertex
}

TEST(Patch, PatchesMatchTheCageSubdividedSixLevelsDeeper) {
  // The accuracy bar: within 1e-4 of the diagonal (regular), 1e-3 near extraordinary vertices
  // (valence 3 and 6 here), normals within 1 degree, of the cage subdivided 6 more levels.
  std::string path = hexagonalPrism(test::tempDir());
  PolygonMesh coarse = cage(path, 2), deep = cage(path, 8), deepLimit = deep;
  std::vector<glm::vec3> deepNormals;
  ASSERT_TRUE(moveToLimit(deepLimit, deepNormals));
  Accuracy a = compare(coarse, deep.positions, deepNormals, 8);
  EXPECT_GT(a.regular, 0u);
  EXPECT_GT(a.ring, 40u);
  EXPECT_EQ(a.none, 0u);
  EXPECT_LT(a.regularWorst, 1e-4f);
  EXPECT_LT(a.ringWorst, 1e-3f);
  EXPECT_LT(a.normalWorst, 1.0f);
  std::printf("six levels deeper: regular %.2e, ring %.2e of the diagonal, normals %.3f deg\n", a.regularWorst, a.ringWorst, a.normalWorst);
}

TEST(Patch, NeighbouringPatchesMeetWithTheSameNormal) {
  PolygonMesh coarse = cage(test::asset("horned_cube.obj"), 2);
  Patcher patcher(coarse);
  const float d = diagonal(coarse.positions);
  size_t shared = 0, ringEdges = 0;
  float worst = 0.0f, worstNormal = 0.0f;
  for (uint32_t f = 0; f < coarse.faceCount(); f++) {
    FacePatch patch = patcher.patch(f);
    for (int k = 0; k < 4; k++) {
      uint32_t n = patch.neighbours[k];
      ASSERT_NE(n, UINT32_MAX);
      FacePatch other = patcher.patch(n >> 2);
      ASSERT_EQ(other.neighbours[n & 3], f << 2 | uint32_t(k)) << "neighbours name each other";
      shared++;
      if (patch.kind == VGEO_PATCH_RING || other.kind == VGEO_PATCH_RING) ringEdges++;
      for (int s = 0; s <= 16; s++) {
        glm::vec2 a = onEdge(k, float(s) / 16.0f), b = onEdge(int(n & 3), 1.0f - float(s) / 16.0f);
        glm::vec3 na, nb;
        glm::vec3 pa = evaluateFacePatch(patch, coarse.positions, a.x, a.y, &na), pb = evaluateFacePatch(other, coarse.positions, b.x, b.y, &nb);
        worst = std::max(worst, glm::distance(pa, pb) / d);
        worstNormal = std::max(worstNormal, degrees(na, nb));
      }
    }
  }
  EXPECT_GT(shared, 1000u);
  EXPECT_GT(ringEdges, 10u);
  EXPECT_LT(worst, 1e-6f);
  EXPECT_LT(worstNormal, 0.05f);
}

TEST(Patch, ChordErrorsBoundTheLeafTriangles) {
  PolygonMesh coarse = cage(test::asset("horned_cube.obj"), 2), limit = coarse;
  std::vector<glm::vec3> normals;
  ASSERT_TRUE(moveToLimit(limit, normals));
  std::vector<PatchErrors> errors = patchChordErrors(limit, coarse.positions, 2);
  ASSERT_EQ(errors.size(), limit.faceCount());
  Patcher patcher(limit);
  size_t positive = 0;
  double worstRatio = 0.0;
  for (uint32_t f = 0; f < limit.faceCount(); f++) {
    FacePatch patch = patcher.patch(f);
    std::vector<uint32_t> tris;
    triangulateFace(limit.positions.data(), limit.face(f), 4, tris);
    // Sampled more finely than the builder does: its estimate (5% slack) must hold within 10%.
    double worst = 0.0;
    for (int i = 0; i <= 16; i++)
      for (int j = 0; j <= 16; j++) {
        glm::dvec3 p(evaluateFacePatch(patch, coarse.positions, float(i) / 16.0f, float(j) / 16.0f));
        auto x = [&](int k) { return glm::dvec3(limit.positions[tris[size_t(k)]]); };
        worst = std::max(worst, std::min(pointTriangleDistance(p, x(0), x(1), x(2)), pointTriangleDistance(p, x(3), x(4), x(5))));
      }
    if (errors[f].face > 0.0f) positive++;
    worstRatio = std::max(worstRatio, worst / std::max(double(errors[f].face), 1e-30));
    for (int k = 0; k < 4; k++) {
      EXPECT_LE(errors[f].edge[k], errors[f].face);
      uint32_t n = patch.neighbours[k];
      EXPECT_EQ(errors[f].edge[k], errors[n >> 2].edge[n & 3]) << "both faces of an edge carry one value";
    }
  }
  EXPECT_EQ(positive, limit.faceCount());
  EXPECT_LT(worstRatio, 1.1);
}

TEST(Patch, TheVgeoCarriesPatchesAndLeafErrors) {
  VgeoData data = test::build(test::asset("horned_cube.obj"), 2);
  ASSERT_EQ(data.patches.size(), data.cageFaces.size());
  ASSERT_EQ(data.controlPoints.size(), data.positions.size());
  float worst = 0.0f;
  size_t locked = 0;
  for (uint32_t f = 0; f < data.patches.size(); f++) {
    ASSERT_NE(shaderio::patchKind(data.patches[f].info), VGEO_PATCH_NONE);
    for (int k = 0; k < 4; k++) {
      // Every corner of the patch is its face's leaf vertex (a limit point).
      glm::vec2 corner = onEdge(k, 0.0f);
      uint32_t v = data.cageFaceVertices[data.cageFaces[f].firstVertex + uint32_t(k)];
      worst = std::max(worst, glm::distance(data.evaluatePatch(f, corner.x, corner.y), data.position(v)));
      locked += shaderio::patchEdgeLocked(data.patches[f].info, uint32_t(k));
    }
  }
  EXPECT_LT(worst, 1e-5f);
  EXPECT_GT(locked, 0u) << "level-0 group borders are locked";
  EXPECT_LT(locked, 2 * data.patches.size()) << "but most edges are inside groups";
  // Leaf clusters' self error is their largest face chord error, and their groups' error covers it.
  for (const auto& c : data.clusters) {
    if (c.producer != VGEO_NO_GROUP) continue;
    float largest = 0.0f;
    for (uint32_t i = 0; i < shaderio::clusterCageFaceCount(c.counts); i++) largest = std::max(largest, data.patches[c.cageFaceOffset + i].faceError);
    EXPECT_EQ(c.selfError, largest);
    EXPECT_GT(c.selfError, 0.0f);
    EXPECT_GE(c.parentError, c.selfError);
  }
  VgeoData plain = test::build(test::asset("horned_cube.obj"), 0);  // not subdivided: flat faces, leaves exact
  for (const auto& patch : plain.patches) EXPECT_EQ(shaderio::patchKind(patch.info), VGEO_PATCH_NONE);
  for (const auto& c : plain.clusters)
    if (c.producer == VGEO_NO_GROUP) {
      EXPECT_EQ(c.selfError, 0.0f);
    }
  EXPECT_EQ(plain.controlPoints, plain.positions);
}

}  // namespace
}  // namespace vgeo
