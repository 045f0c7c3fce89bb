// test_repair.cpp: welding, degenerate and duplicate faces, non-manifold edges and vertices.
#include <algorithm>
#include <map>

#include "test_util.h"

namespace vgeo {
namespace {

// Every edge has at most two faces, of opposite orientation; every vertex one fan.
void expectManifold(const PolygonMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t f = 0; f < m.faceCount(); f++)
    for (uint32_t i = 0; i < m.faceSize(f); i++) directed[{m.face(f)[i], m.face(f)[(i + 1) % m.faceSize(f)]}]++;
  for (auto& [e, n] : directed) EXPECT_EQ(n, 1) << "directed edge " << e.first << "-" << e.second << " used " << n << " times";
}

TEST(Repair, SplitsANonManifoldEdgeOfThreeFaces) {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  const uint32_t t[3][3] = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};  // three "pages" on edge 0-1
  for (auto& f : t) m.addFace(f, 3);
  RepairReport r = repairMesh(m, "book");
  EXPECT_EQ(r.nonManifoldEdges, 1u);
  EXPECT_GE(r.splitVertices, 2u);
  EXPECT_EQ(m.faceCount(), 3u);
  expectManifold(m);
}

TEST(Repair, SplitsANonManifoldVertex) {
  // Two triangles touching at vertex 0 only (a bowtie).
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  const uint32_t t[2][3] = {{0, 1, 2}, {0, 3, 4}};
  for (auto& f : t) m.addFace(f, 3);
  RepairReport r = repairMesh(m, "bowtie");
  EXPECT_EQ(r.splitVertices, 1u);
  EXPECT_EQ(m.positions.size(), 6u);
  expectManifold(m);
}

TEST(Repair, DropsDegenerateAndDuplicateFacesAndWelds) {
  PolygonMesh m;
  // A quad split into triangles with its vertices duplicated (as glTF does at seams).
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const uint32_t t[5][3] = {{0, 1, 2}, {3, 4, 5}, {0, 1, 1}, {2, 0, 1}, {0, 3, 4}};
  for (auto& f : t) m.addFace(f, 3);
  RepairReport r = repairMesh(m, "seams");
  EXPECT_EQ(r.weldedVertices, 2u);
  EXPECT_EQ(r.degenerateFaces, 2u);  // {0,1,1} and {0,3,4} = {0,0,2} after welding
  EXPECT_EQ(r.duplicateFaces, 1u);   // {2,0,1} repeats {0,1,2}
  EXPECT_EQ(m.faceCount(), 2u);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(r.boundaryEdges, 4u);
  expectManifold(m);
}

TEST(Repair, RejectsNonFinitePositions) {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}};
  const uint32_t t[3] = {0, 1, 2};
  m.addFace(t, 3);
  try {
    repairMesh(m, "nan.obj");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nan.obj: vertex 2 has a non-finite position"), std::string::npos) << e.what();
  }
}

TEST(Repair, NonManifoldInputsBuildAndCheck) {
  // Two cubes sharing one edge (a non-manifold edge of four faces) through the whole pipeline.
  std::string dir = test::tempDir();
  std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "v 2 1 0\nv 2 2 0\nv 1 2 0\nv 2 1 1\nv 2 2 1\nv 1 2 1\n"
      "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
      "f 3 11 10 9\nf 7 12 13 14\nf 3 9 12 7\nf 9 10 13 12\nf 10 11 14 13\nf 11 3 7 14\n";
  std::string path = test::writeFile(dir, "two_cubes.obj", obj);
  SceneBuildStats stats;
  VgeoData data = test::build(path, 2, 2, &stats);
  EXPECT_EQ(stats.repair.nonManifoldEdges, 1u);
  CheckResult result = checkVgeo(data, {16, 3});
  EXPECT_TRUE(result.ok) << result.firstViolation;
}

}  // namespace
}  // namespace vgeo
