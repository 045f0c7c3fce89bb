// test_limit.cpp: limit positions and normals of Catmull-Clark meshes (limit.cpp). The limit point and
// normal of a vertex do not change when the mesh is subdivided further (the vertex keeps its index), so
// masks applied at level 1 and at level 4 must agree to rounding, at every valence, inside and on the
// boundary; and the control points of ever finer meshes must converge to them.
#include <cmath>
#include <set>

#include "test_util.h"

namespace vgeo {
namespace {

PolygonMesh subdivided(PolygonMesh m, int levels) {
  for (int l = 0; l < levels; l++) m = subdivideCatmullClark(m);
  return m;
}

float diagonal(const PolygonMesh& m) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const auto& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::distance(lo, hi);
}

float degrees(glm::vec3 a, glm::vec3 b) { return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f)) * 57.29578f; }

// The shipped cage (valences 3 to 6 after one round) and, for boundaries, the same with a band of faces
// removed; both after one round so that every face is a quad.
PolygonMesh cage(bool open) {
  PolygonMesh m = loadMeshFile(test::asset("horned_cube.obj")).meshes[0];
  repairMesh(m, "horned_cube.obj");
  if (open) {
    PolygonMesh cut;
    cut.positions = m.positions;
    for (size_t f = 0; f < m.faceCount(); f++)
      if (f % 7 != 3) cut.addFace(m.face(f), m.faceSize(f));
    m = cut;
    repairMesh(m, "horned_cube.obj");  // splits vertices where two holes touch
  }
  return subdivided(m, 1);
}

TEST(Limit, PositionsAndNormalsDoNotChangeUnderSubdivision) {
  for (bool open : {false, true}) {
    PolygonMesh coarse = cage(open), fine = subdivided(coarse, 3);
    FillLaterVector<glm::vec3> coarseNormals, fineNormals;
    PolygonMesh coarseLimit = coarse, fineLimit = fine;
    ASSERT_TRUE(moveToLimit(coarseLimit, coarseNormals));
    ASSERT_TRUE(moveToLimit(fineLimit, fineNormals));
    // Faces per vertex (valence inside; boundary vertices have one face fewer than edges).
    std::vector<int> faces(coarse.positions.size(), 0);
    for (uint32_t v : coarse.faceVertices) faces[v]++;
    const float d = diagonal(coarse);
    float worstPosition = 0.0f, worstNormal = 0.0f;
    std::set<int> valences;
    for (size_t v = 0; v < coarse.positions.size(); v++) {
      if (faces[v] == 0) continue;
      valences.insert(faces[v]);
      worstPosition = std::max(worstPosition, glm::distance(coarseLimit.positions[v], fineLimit.positions[v]) / d);
      worstNormal = std::max(worstNormal, degrees(coarseNormals[v], fineNormals[v]));
    }
    EXPECT_LT(worstPosition, 1e-6f) << (open ? "open" : "closed");
    // Exact masks, and at boundary vertices of three or more faces the refined ring (before it, the mean
    // interior neighbour stood in for the cross-boundary tangent: 9-12 degrees off here).
    EXPECT_LT(worstNormal, 0.05f) << (open ? "open" : "closed");
    EXPECT_GE(valences.size(), open ? 5u : 3u);
  }
}

TEST(Limit, ControlPointsConvergeToTheLimit) {
  // Interior control points approach the limit point like the subdominant eigenvalue (1/2 for a regular
  // vertex, up to about 0.6 at the valences of this cage): after 6 more rounds within 2% of their
  // level-1 distance, and the finest faces around a vertex turn to the limit normal.
  PolygonMesh coarse = cage(false);
  PolygonMesh limit = coarse;
  FillLaterVector<glm::vec3> normals;
  ASSERT_TRUE(moveToLimit(limit, normals));
  PolygonMesh fine = subdivided(coarse, 6);
  std::vector<glm::vec3> faceNormalSum(coarse.positions.size(), glm::vec3(0.0f));
  for (size_t f = 0; f < fine.faceCount(); f++)
    for (uint32_t i = 0; i < 4; i++) {
      uint32_t v = fine.face(f)[i];
      if (v >= coarse.positions.size()) continue;
      glm::vec3 p = fine.positions[v], a = fine.positions[fine.face(f)[(i + 1) % 4]],
                b = fine.positions[fine.face(f)[(i + 3) % 4]];
      faceNormalSum[v] += glm::cross(a - p, b - p);
    }
  const float d = diagonal(coarse);
  float worstRatio = 0.0f, worstNormal = 0.0f, worstDistance = 0.0f;
  for (size_t v = 0; v < coarse.positions.size(); v++) {
    float before = glm::distance(coarse.positions[v], limit.positions[v]);
    float after = glm::distance(fine.positions[v], limit.positions[v]);
    worstDistance = std::max(worstDistance, after / d);
    if (before > 1e-4f * d) worstRatio = std::max(worstRatio, after / before);
    worstNormal = std::max(worstNormal, degrees(glm::normalize(faceNormalSum[v]), normals[v]));
  }
  EXPECT_LT(worstRatio, 0.02f);
  EXPECT_LT(worstDistance, 1e-3f);
  EXPECT_LT(worstNormal, 1.0f);
}

TEST(Limit, OnlyQuadMeshesMove) {
  PolygonMesh tetrahedron;
  tetrahedron.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const uint32_t faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (auto& f : faces) tetrahedron.addFace(f, 3);
  PolygonMesh before = tetrahedron;
  FillLaterVector<glm::vec3> normals;
  EXPECT_FALSE(moveToLimit(tetrahedron, normals));
  EXPECT_EQ(tetrahedron.positions, before.positions);
  PolygonMesh quads = subdivideCatmullClark(before);  // after one round: every face a quad
  EXPECT_TRUE(moveToLimit(quads, normals));
  EXPECT_EQ(normals.size(), quads.positions.size());
}

}  // namespace
}  // namespace vgeo
