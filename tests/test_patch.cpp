// test_patch.cpp: B-spline patches of regular cage faces (patch.cpp). At dyadic parameters a regular
// patch must hit the limit points of the mesh subdivided further (exact: limit.cpp's masks, tested in
// test_limit.cpp), with the limit normals; neighbouring patches must meet along their shared edge with
// the same position and normal; and the .vgeo must carry them.
#include <cmath>
#include <map>
#include <unordered_map>

#include "test_util.h"

namespace vgeo {
namespace {

PolygonMesh hornedCube(int levels) {
  PolygonMesh m = loadMeshFile(test::asset("horned_cube.obj")).meshes[0];
  repairMesh(m, "horned_cube.obj");
  for (int l = 0; l < levels; l++) m = subdivideCatmullClark(m);
  return m;
}

float diagonal(const std::vector<glm::vec3>& points) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const auto& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::distance(lo, hi);
}

float degrees(glm::dvec3 a, glm::dvec3 b) {
  return float(std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 57.29577951);
}

// (u, v) of parameter t along edge k of a face (from corner k to corner k + 1).
glm::dvec2 onEdge(int k, double t) {
  switch (k) {
    case 0: return {t, 0.0};
    case 1: return {1.0, t};
    case 2: return {1.0 - t, 1.0};
    default: return {0.0, 1.0 - t};
  }
}

TEST(Patch, RegularPatchesAreTheLimitSurface) {
  PolygonMesh cage = hornedCube(2);
  std::vector<shaderio::BsplinePatch> patches = bsplinePatches(cage);
  ASSERT_EQ(patches.size(), cage.faceCount());
  // Two more rounds: the vertex at (i/4, j/4) of every face, moved to the limit.
  PolygonMesh fine = hornedCube(4);
  std::vector<glm::vec3> fineNormals;
  ASSERT_TRUE(moveToLimit(fine, fineNormals));
  const float d = diagonal(cage.positions), cell = d * 1e-3f;
  std::unordered_map<uint64_t, std::vector<uint32_t>> grid;  // fine limit points by cell
  auto cellOf = [&](glm::vec3 p) { return glm::ivec3(glm::floor(p / cell)); };
  auto key = [](glm::ivec3 c) {
    return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) | (uint32_t(c.z) & 0x1fffff);
  };
  for (uint32_t v = 0; v < fine.positions.size(); v++) grid[key(cellOf(fine.positions[v]))].push_back(v);
  size_t regular = 0;
  float worst = 0.0f, worstNormal = 0.0f;
  for (size_t f = 0; f < patches.size(); f++) {
    if (patches[f].points[0] == VGEO_NO_PATCH) continue;
    regular++;
    glm::vec3 points[16];
    for (int i = 0; i < 16; i++) points[i] = cage.positions[patches[f].points[i]];
    for (int i = 0; i <= 4; i++)
      for (int j = 0; j <= 4; j++) {
        glm::dvec3 du, dv;
        glm::vec3 p(evaluateBspline(points, i / 4.0, j / 4.0, &du, &dv));
        float best = INFINITY;
        uint32_t nearest = 0;
        for (int dx = -1; dx <= 1; dx++)
          for (int dy = -1; dy <= 1; dy++)
            for (int dz = -1; dz <= 1; dz++) {
              auto it = grid.find(key(cellOf(p) + glm::ivec3(dx, dy, dz)));
              if (it == grid.end()) continue;
              for (uint32_t v : it->second)
                if (glm::distance(p, fine.positions[v]) < best) best = glm::distance(p, fine.positions[v]), nearest = v;
            }
        worst = std::max(worst, best / d);
        if (std::isfinite(best)) worstNormal = std::max(worstNormal, degrees(glm::cross(du, dv), glm::dvec3(fineNormals[nearest])));
      }
  }
  EXPECT_GT(regular, patches.size() / 2) << "most faces of a subdivided cage are regular";
  EXPECT_LT(regular, patches.size()) << "faces at the cube's corners (valence 3) are not";
  EXPECT_LT(worst, 1e-6f);
  EXPECT_LT(worstNormal, 0.01f);
}

TEST(Patch, NeighbouringPatchesMeetWithTheSameNormal) {
  PolygonMesh cage = hornedCube(2);
  std::vector<shaderio::BsplinePatch> patches = bsplinePatches(cage);
  const float d = diagonal(cage.positions);
  // Points and normals along every directed edge of a regular face, t from its first corner.
  std::map<std::pair<uint32_t, uint32_t>, std::vector<std::pair<glm::dvec3, glm::dvec3>>> along;
  for (size_t f = 0; f < patches.size(); f++) {
    if (patches[f].points[0] == VGEO_NO_PATCH) continue;
    glm::vec3 points[16];
    for (int i = 0; i < 16; i++) points[i] = cage.positions[patches[f].points[i]];
    for (int k = 0; k < 4; k++) {
      auto& samples = along[{cage.face(f)[k], cage.face(f)[(k + 1) % 4]}];
      for (int s = 0; s <= 8; s++) {
        glm::dvec2 uv = onEdge(k, s / 8.0);
        glm::dvec3 du, dv, p = evaluateBspline(points, uv.x, uv.y, &du, &dv);
        samples.push_back({p, glm::cross(du, dv)});
      }
    }
  }
  size_t shared = 0;
  float worst = 0.0f, worstNormal = 0.0f;
  for (const auto& [edge, samples] : along) {
    auto other = along.find({edge.second, edge.first});
    if (other == along.end()) continue;
    shared++;
    for (int s = 0; s <= 8; s++) {
      const auto &a = samples[size_t(s)], &b = other->second[size_t(8 - s)];
      worst = std::max(worst, float(glm::distance(a.first, b.first)) / d);
      worstNormal = std::max(worstNormal, degrees(a.second, b.second));
    }
  }
  EXPECT_GT(shared, 1000u);
  EXPECT_LT(worst, 1e-6f);
  EXPECT_LT(worstNormal, 0.01f);
}

TEST(Patch, TheVgeoCarriesControlPointsAndPatches) {
  VgeoData data = test::build(test::asset("horned_cube.obj"), 2);
  ASSERT_EQ(data.patches.size(), data.cageFaces.size());
  ASSERT_EQ(data.controlPoints.size(), data.positions.size());
  size_t regular = 0;
  float worst = 0.0f;
  for (size_t f = 0; f < data.patches.size(); f++) {
    const auto& patch = data.patches[f];
    if (patch.points[0] == VGEO_NO_PATCH) continue;
    regular++;
    glm::vec3 points[16];
    for (int i = 0; i < 16; i++) {
      uint32_t v = patch.points[i];
      points[i] = {data.controlPoints[3 * v], data.controlPoints[3 * v + 1], data.controlPoints[3 * v + 2]};
    }
    // The patch's corner (0, 0) is the face's first corner, whose leaf vertex sits at the limit point.
    glm::vec3 corner(evaluateBspline(points, 0.0, 0.0));
    uint32_t v = data.cageFaceVertices[data.cageFaces[f].firstVertex];
    worst = std::max(worst, glm::distance(corner, data.position(v)));
  }
  EXPECT_GT(regular, data.patches.size() / 2);
  EXPECT_LT(worst, 1e-5f);
  VgeoData plain = test::build(test::asset("horned_cube.obj"), 0);  // not subdivided: no patches
  for (const auto& patch : plain.patches) EXPECT_EQ(patch.points[0], VGEO_NO_PATCH);
  EXPECT_EQ(plain.controlPoints, plain.positions);
}

}  // namespace
}  // namespace vgeo
