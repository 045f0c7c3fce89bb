// test_patch.cpp: the limit-surface patches of cage faces (patch.cpp, mesh_patches.cpp,
// shaders/patch_eval.h): regular B-spline patches (interior or with phantom points beyond a boundary),
// rings around extraordinary vertices and trees of locally subdivided faces must be the Catmull-Clark
// limit surface with subdivide.cpp's boundary rules (at dyadic parameters exactly the limit points of the
// mesh subdivided further; anywhere, close to the mesh subdivided 6 more levels), neighbours must meet
// with the same position and normal, chord errors must bound the leaf triangles' distance, and the
// .vgeo must carry all of it.
#include <cmath>
#include <map>
#include <unordered_map>

#include "../renderer/scene.h"
#include "cages.h"
#include "test_util.h"

namespace vgeo {
namespace {

PolygonMesh cage(const std::string& path, int levels) {
  PolygonMesh m = loadMeshFile(path).meshes[0];
  repairMesh(m, path);
  for (int l = 0; l < levels; l++) m = subdivideCatmullClark(m);
  return m;
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
    case 0:
      return {t, 0.0f};
    case 1:
      return {1.0f, t};
    case 2:
      return {1.0f - t, 1.0f};
    default:
      return {0.0f, 1.0f - t};
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
    return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) |
           (uint32_t(c.z) & 0x1fffff);
  }
  const std::vector<glm::vec3>& points_;
  float cell_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

struct Accuracy {
  size_t regular = 0, boundary = 0, ring = 0, tree = 0, none = 0;
  float regularWorst = 0.0f, ringWorst = 0.0f, treeWorst = 0.0f, normalWorst = 0.0f, treeCornerNormalWorst = 0.0f;
};

bool onBoundary(const MeshPatches& patches, uint32_t face) {
  for (uint32_t n : patches.neighbours[face])
    if (n == UINT32_MAX) return true;
  return false;
}

// Every patch of `coarse` at parameters (i / steps, j / steps) against the nearest vertex of `fine`
// (distances relative to the diagonal) and that vertex's normal. At a tree's corners the patch is bilinear
// over its last 1/64 (the renderer shades corners with the leaf normals instead), so there the normal 1/64
// inside stands for it, against a looser bound (treeCornerNormalWorst).
Accuracy compare(const PolygonMesh& coarse, const std::vector<glm::vec3>& fine, std::span<const glm::vec3> fineNormals,
                 int steps) {
  const MeshPatches patches = buildPatches(coarse, coarse.positions, 2);
  const float d = diagonal(coarse.positions);
  PointGrid grid(fine, d * 2e-3f);
  Accuracy a;
  for (uint32_t f = 0; f < coarse.faceCount(); f++) {
    const uint32_t kind = shaderio::patchKind(patches.info[f]);
    if (kind == VGEO_PATCH_NONE) {
      a.none++;
      continue;
    }
    (kind == VGEO_PATCH_TREE   ? a.tree
     : kind == VGEO_PATCH_RING ? a.ring
     : onBoundary(patches, f)  ? a.boundary
                               : a.regular)++;
    float& worst = kind == VGEO_PATCH_REGULAR ? a.regularWorst : kind == VGEO_PATCH_RING ? a.ringWorst : a.treeWorst;
    for (int i = 0; i <= steps; i++)
      for (int j = 0; j <= steps; j++) {
        glm::vec3 normal, p = patches.evaluate(f, float(i) / float(steps), float(j) / float(steps), &normal);
        float distance;
        uint32_t v = grid.nearest(p, distance);
        worst = std::max(worst, distance / d);
        if (!std::isfinite(distance)) continue;
        const bool corner = (i == 0 || i == steps) && (j == 0 || j == steps);
        if (corner && kind == VGEO_PATCH_TREE) {
          const float s = i == 0 ? 1.0f / 64.0f : 63.0f / 64.0f, t = j == 0 ? 1.0f / 64.0f : 63.0f / 64.0f;
          patches.evaluate(f, s, t, &normal);
          a.treeCornerNormalWorst = std::max(a.treeCornerNormalWorst, degrees(normal, fineNormals[v]));
        } else {
          a.normalWorst = std::max(a.normalWorst, degrees(normal, fineNormals[v]));
        }
      }
  }
  return a;
}

// `path` subdivided `levels` times against `more` further levels: against that mesh's limit points
// (`limit`), or its vertices as they are (the issue's bar), with limit normals either way.
Accuracy compareDeeper(const std::string& path, int levels, int more, int steps, bool limit) {
  PolygonMesh coarse = cage(path, levels), fine = cage(path, levels + more), fineLimit = fine;
  FillLaterVector<glm::vec3> fineNormals;
  EXPECT_TRUE(moveToLimit(fineLimit, fineNormals));
  return compare(coarse, limit ? fineLimit.positions : fine.positions, fineNormals, steps);
}

TEST(Patch, PatchesAreTheLimitSurfaceAtDyadicParameters) {
  // Two more rounds: the vertex at (i/4, j/4) of every face, moved to the limit, is exactly a patch point.
  Accuracy a = compareDeeper(test::asset("horned_cube.obj"), 2, 2, 4, true);
  EXPECT_GT(a.regular, 1000u) << "most faces of a subdivided cage are regular";
  EXPECT_GT(a.ring, 0u) << "faces at the cube's corners (valence 3) are rings";
  EXPECT_EQ(a.boundary + a.tree + a.none, 0u)
      << "a closed cage after two rounds has a B-spline or ring patch on every face";
  EXPECT_LT(a.regularWorst, 1e-6f);
  EXPECT_LT(a.ringWorst, 2e-6f);
  EXPECT_LT(a.normalWorst, 0.05f);  // float derivatives shrink towards an extraordinary vertex
}

TEST(Patch, BoundaryAndTreePatchesAreTheLimitSurfaceAtDyadicParameters) {
  // Boundaries (regular, corners, an extraordinary boundary vertex) and faces with two extraordinary
  // corners, against the limit points of two more rounds with subdivide.cpp's boundary rules.
  const std::string dir = test::tempDir();
  Accuracy box = compareDeeper(test::openBox(dir), 2, 2, 4, true),
           sheet = compareDeeper(test::lSheet(dir), 2, 2, 4, true);
  Accuracy fan = compareDeeper(test::triangleFan(dir), 1, 2, 4, true),
           tetra = compareDeeper(test::tetrahedron(dir), 1, 2, 4, true);
  EXPECT_GT(box.boundary, 10u);
  EXPECT_GT(box.ring, 0u);
  EXPECT_EQ(box.tree, 0u) << "a boundary of regular vertices needs no local subdivision";
  EXPECT_GT(sheet.boundary, 10u) << "regular boundary faces and corners";
  EXPECT_EQ(sheet.tree, 3u) << "the three faces at the extraordinary boundary vertex";
  EXPECT_EQ(fan.tree, 15u) << "--subdiv 1 of a triangle mesh: every face has two extraordinary corners";
  EXPECT_EQ(tetra.tree, 12u);
  for (const Accuracy* a : {&box, &sheet, &fan, &tetra}) {
    EXPECT_EQ(a->none, 0u) << "every face of a subdivided cage has a patch";
    EXPECT_LT(a->regularWorst, 1e-6f);
    EXPECT_LT(a->ringWorst, 2e-6f);
    EXPECT_LT(a->treeWorst, 2e-6f);
    EXPECT_LT(a->normalWorst, 0.1f);
    // A sanity bound: the normal turns fastest next to an extraordinary vertex (0.8 deg over the last
    // 1/64 at the L's boundary vertex, 2.2 at the tetrahedron's valence-3 corners). Exactness of the
    // leaf normals themselves is test_limit.cpp's.
    EXPECT_LT(a->treeCornerNormalWorst, 3.0f) << "leaf normals at extraordinary corners are the surface's";
    std::printf("tree corners: normal 1/64 inside within %.3f deg of the leaf normal\n", a->treeCornerNormalWorst);
  }
}

TEST(Patch, TreesFromTheWholeMeshRoundAreTheirOwnRounds) {
  // A tree's first level from one round of the whole mesh (its points shared by every tree) against a
  // round of the face's own neighbourhood: the same surface, in far fewer points. The L-sheet after one
  // round has trees down to the last level at its extraordinary boundary vertex.
  const std::string dir = test::tempDir();
  for (const std::string& path : {test::triangleFan(dir), test::tetrahedron(dir), test::lSheet(dir)}) {
    const PolygonMesh coarse = cage(path, 1);
    const MeshPatches own = buildPatches(coarse, coarse.positions, 2, TreeRounds::Own),
                      shared = buildPatches(coarse, coarse.positions, 2, TreeRounds::Shared),
                      chosen = buildPatches(coarse, coarse.positions, 2);
    auto pointCount = [](const MeshPatches& p) {
      size_t n = p.points.size();
      for (const MeshPatches::Block& b : p.blocks) n += b.points.size();
      return n;
    };
    size_t trees = 0;
    float worst = 0.0f, worstNormal = 0.0f;
    for (uint32_t f = 0; f < coarse.faceCount(); f++) {
      ASSERT_EQ(own.info[f], shared.info[f]) << path;
      ASSERT_EQ(chosen.info[f], shared.info[f]) << path;
      trees += shaderio::patchKind(own.info[f]) == VGEO_PATCH_TREE;
      for (int i = 0; i <= 8; i++)
        for (int j = 0; j <= 8; j++) {
          glm::vec3 na, nb;
          const glm::vec3 a = own.evaluate(f, float(i) / 8.0f, float(j) / 8.0f, &na),
                          b = shared.evaluate(f, float(i) / 8.0f, float(j) / 8.0f, &nb),
                          c = chosen.evaluate(f, float(i) / 8.0f, float(j) / 8.0f, nullptr);
          worst = std::max({worst, glm::distance(a, b), glm::distance(b, c)});
          worstNormal = std::max(worstNormal, degrees(na, nb));
        }
    }
    EXPECT_GT(trees, 2u) << path;
    EXPECT_LT(worst, 1e-6f * diagonal(coarse.positions)) << path;
    EXPECT_LT(worstNormal, 0.1f) << path;  // float's acos near 1 alone gives a few hundredths
    if (trees == coarse.faceCount()) {
      EXPECT_LT(pointCount(shared), pointCount(own)) << path << ": every face a tree, each point stored once";
    }
  }
}

TEST(Patch, PatchesMatchTheCageSubdividedSixLevelsDeeper) {
  // The issue's accuracy bar: within 1e-4 of the diagonal (regular), 1e-3 near extraordinary vertices
  // (valence 3 and 6 here), normals within 1 degree, of the cage subdivided 6 more levels.
  Accuracy a = compareDeeper(test::hexagonalPrism(test::tempDir()), 2, 6, 8, false);
  EXPECT_GT(a.regular, 0u);
  EXPECT_GT(a.ring, 40u);
  EXPECT_EQ(a.none + a.tree + a.boundary, 0u);
  EXPECT_LT(a.regularWorst, 1e-4f);
  EXPECT_LT(a.ringWorst, 1e-3f);
  EXPECT_LT(a.normalWorst, 1.0f);
  std::printf("six levels deeper: regular %.2e, ring %.2e of the diagonal, normals %.3f deg\n", a.regularWorst,
              a.ringWorst, a.normalWorst);
}

TEST(Patch, BoundaryAndTreePatchesMatchTheCageSubdividedSixLevelsDeeper) {
  const std::string dir = test::tempDir();
  for (const auto& [path, levels] : {std::pair{test::lSheet(dir), 2}, std::pair{test::triangleFan(dir), 1}}) {
    Accuracy a = compareDeeper(path, levels, 6, 8, false);
    EXPECT_GT(a.boundary + (levels == 1 ? 1u : 0u), 0u)
        << path << ": regular boundary faces (none at --subdiv 1 of the fan)";
    EXPECT_GT(a.tree, 0u) << path;
    EXPECT_EQ(a.none, 0u) << path;
    EXPECT_LT(a.regularWorst, 1e-4f) << path;
    EXPECT_LT(a.treeWorst, 1e-3f) << path;
    EXPECT_LT(a.normalWorst, 1.0f) << path;
    std::printf("%s six levels deeper: regular %.2e, tree %.2e of the diagonal, normals %.3f deg\n", path.c_str(),
                a.regularWorst, a.treeWorst, a.normalWorst);
  }
}

struct Continuity {
  size_t shared = 0, ringEdges = 0, treeEdges = 0, boundaryEdges = 0;
  float worst = 0.0f, worstNormal = 0.0f;
};

// Both faces of every interior edge, evaluated at 17 points along it.
Continuity continuity(const PolygonMesh& coarse) {
  const MeshPatches patches = buildPatches(coarse, coarse.positions, 2);
  const float d = diagonal(coarse.positions);
  Continuity c;
  for (uint32_t f = 0; f < coarse.faceCount(); f++)
    for (int k = 0; k < 4; k++) {
      uint32_t n = patches.neighbours[f][size_t(k)];
      if (n == UINT32_MAX) {
        c.boundaryEdges++;
        continue;
      }
      EXPECT_EQ(patches.neighbours[n >> 2][n & 3], f << 2 | uint32_t(k)) << "neighbours name each other";
      c.shared++;
      const uint32_t kinds[2] = {shaderio::patchKind(patches.info[f]), shaderio::patchKind(patches.info[n >> 2])};
      if (kinds[0] == VGEO_PATCH_RING || kinds[1] == VGEO_PATCH_RING) c.ringEdges++;
      if (kinds[0] == VGEO_PATCH_TREE || kinds[1] == VGEO_PATCH_TREE) c.treeEdges++;
      for (int s = 0; s <= 16; s++) {
        glm::vec2 a = onEdge(k, float(s) / 16.0f), b = onEdge(int(n & 3), 1.0f - float(s) / 16.0f);
        glm::vec3 na, nb;
        glm::vec3 pa = patches.evaluate(f, a.x, a.y, &na), pb = patches.evaluate(n >> 2, b.x, b.y, &nb);
        c.worst = std::max(c.worst, glm::distance(pa, pb) / d);
        // Normals at the edge's ends are the leaf vertices' in the renderer (see compare()).
        if ((s > 0 && s < 16) || (kinds[0] != VGEO_PATCH_TREE && kinds[1] != VGEO_PATCH_TREE))
          c.worstNormal = std::max(c.worstNormal, degrees(na, nb));
      }
    }
  return c;
}

TEST(Patch, NeighbouringPatchesMeetWithTheSameNormal) {
  Continuity c = continuity(cage(test::asset("horned_cube.obj"), 2));
  EXPECT_GT(c.shared, 1000u);
  EXPECT_GT(c.ringEdges, 10u);
  EXPECT_EQ(c.boundaryEdges, 0u);
  EXPECT_LT(c.worst, 1e-6f);
  EXPECT_LT(c.worstNormal, 0.05f);
  // Boundary patches, and trees against each other and against B-splines and rings.
  const std::string dir = test::tempDir();
  for (const auto& [path, levels] : {std::pair{test::openBox(dir), 2}, std::pair{test::lSheet(dir), 2},
                                     std::pair{test::triangleFan(dir), 1}, std::pair{test::tetrahedron(dir), 1}}) {
    c = continuity(cage(path, levels));
    EXPECT_GT(c.shared, 20u) << path;
    EXPECT_LT(c.worst, 1e-6f) << path;
    EXPECT_LT(c.worstNormal, 0.1f) << path;
    if (path != test::openBox(dir)) {
      EXPECT_GT(c.treeEdges, 5u) << path;
    }
  }
}

TEST(Patch, ChordErrorsBoundTheLeafTriangles) {
  const std::string dir = test::tempDir();
  for (const auto& [path, levels] : {std::pair{test::asset("horned_cube.obj"), 2}, std::pair{test::lSheet(dir), 2},
                                     std::pair{test::triangleFan(dir), 1}}) {
    PolygonMesh coarse = cage(path, levels), limit = coarse;
    FillLaterVector<glm::vec3> normals;
    ASSERT_TRUE(moveToLimit(limit, normals));
    const MeshPatches patches = buildPatches(coarse, coarse.positions, 2);
    PatchErrorList errors = patchChordErrors(limit, patches, 2);
    ASSERT_EQ(errors.size(), limit.faceCount());
    size_t positive = 0;
    double worstRatio = 0.0;
    for (uint32_t f = 0; f < limit.faceCount(); f++) {
      std::vector<uint32_t> tris;
      triangulateFace(limit.positions.data(), limit.face(f), 4, tris);
      // Sampled more finely than the builder does: its estimate (12% slack) must hold within 10%.
      double worst = 0.0;
      for (int i = 0; i <= 16; i++)
        for (int j = 0; j <= 16; j++) {
          glm::dvec3 p(patches.evaluate(f, float(i) / 16.0f, float(j) / 16.0f));
          auto x = [&](int k) { return glm::dvec3(limit.positions[tris[size_t(k)]]); };
          worst = std::max(
              worst, std::min(pointTriangleDistance(p, x(0), x(1), x(2)), pointTriangleDistance(p, x(3), x(4), x(5))));
        }
      if (errors[f].face > 0.0f) positive++;
      worstRatio = std::max(worstRatio, worst / std::max(double(errors[f].face), 1e-30));
      for (int k = 0; k < 4; k++) {
        EXPECT_LE(errors[f].edge[k], errors[f].face);
        uint32_t n = patches.neighbours[f][size_t(k)];
        if (n != UINT32_MAX) {
          EXPECT_EQ(errors[f].edge[k], errors[n >> 2].edge[n & 3]) << "both faces of an edge carry one value";
        }
      }
    }
    EXPECT_EQ(positive, limit.faceCount()) << path;
    EXPECT_LT(worstRatio, 1.1) << path;
  }
}

TEST(Patch, TheVgeoCarriesPatchesAndLeafErrors) {
  VgeoData data = test::build(test::asset("horned_cube.obj"), 2);
  ASSERT_EQ(data.patches.size(), data.cageFaces.size());
  ASSERT_EQ(data.controlPoints.size(), data.positions.size())
      << "a closed cage after two rounds needs no phantom or tree points";
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
    for (uint32_t i = 0; i < shaderio::clusterCageFaceCount(c.counts); i++)
      largest = std::max(largest, data.patches[c.cageFaceOffset + i].faceError);
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
  EXPECT_TRUE(plain.controlPoints.empty()) << "flat faces need no control points";
}

TEST(Patch, ScenesOfSeveralFilesKeepEveryPatch) {
  // A scene of two .vgeo files (a closed cage of B-splines and rings; an open triangle cage of trees
  // with phantom and tree points): merged, every patch still passes through its face's leaf vertices,
  // so its words still find their control points (Patch.pointBase).
  const std::string dir = test::tempDir();
  writeVgeo(test::build(test::asset("horned_cube.obj"), 2), dir + "/a.vgeo");
  writeVgeo(test::build(test::triangleFan(dir), 1), dir + "/b.vgeo");
  test::writeFile(dir, "scene.json",
                  R"({"geometries": ["a.vgeo", "b.vgeo"], "instances": [{"geometry": 1}, {"geometry": 0}]})");
  RenderScene scene = loadRenderScene(dir + "/scene.json");
  const VgeoData& data = scene.data;
  ASSERT_EQ(data.geometries.size(), 2u);
  size_t trees = 0;
  float worst = 0.0f;
  for (uint32_t f = 0; f < data.patches.size(); f++) {
    ASSERT_NE(shaderio::patchKind(data.patches[f].info), VGEO_PATCH_NONE);
    trees += shaderio::patchKind(data.patches[f].info) == VGEO_PATCH_TREE;
    for (int k = 0; k < 4; k++) {
      glm::vec2 corner = onEdge(k, 0.0f);
      uint32_t v = data.cageFaceVertices[data.cageFaces[f].firstVertex + uint32_t(k)];
      worst = std::max(worst, glm::distance(data.evaluatePatch(f, corner.x, corner.y), data.position(v)));
    }
  }
  EXPECT_EQ(trees, 15u);
  EXPECT_LT(worst, 1e-5f);
}

}  // namespace
}  // namespace vgeo
