// test_subdivide.cpp: Catmull-Clark rules against hand-computed values, and the interior rules against
// OpenMesh's implementation on a closed mesh.
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>

#include "test_util.h"

namespace vgeo {
namespace {

PolygonMesh cubeMesh() {
  PolygonMesh m;
  for (int i = 0; i < 8; i++) m.positions.push_back({i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f});
  const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (auto& f : faces) m.addFace(f, 4);
  return m;
}

bool hasPoint(const PolygonMesh& m, glm::vec3 p, float tolerance = 1e-6f) {
  for (const auto& q : m.positions)
    if (glm::distance(p, q) <= tolerance) return true;
  return false;
}

TEST(CatmullClark, CubeRulesMatchHandComputedValues) {
  PolygonMesh out = subdivideCatmullClark(cubeMesh());
  ASSERT_EQ(out.positions.size(), 26u);  // 8 vertices + 12 edges + 6 faces
  ASSERT_EQ(out.faceCount(), 24u);
  for (size_t f = 0; f < out.faceCount(); f++) EXPECT_EQ(out.faceSize(f), 4u);
  // Vertex rule, valence 3: (Q + 2R + (n-3)V)/n = ((1/3) + 2(2/3))/3 = 5/9 per coordinate.
  EXPECT_NEAR(out.positions[7].x, 5.0f / 9.0f, 1e-6f);
  EXPECT_NEAR(out.positions[7].y, 5.0f / 9.0f, 1e-6f);
  EXPECT_NEAR(out.positions[7].z, 5.0f / 9.0f, 1e-6f);
  EXPECT_NEAR(out.positions[0].x, -5.0f / 9.0f, 1e-6f);
  // Edge rule: (a + b + f1 + f2)/4 for the edge (1,1,-1)-(1,1,1) = (0.75, 0.75, 0).
  EXPECT_TRUE(hasPoint(out, {0.75f, 0.75f, 0.0f}));
  EXPECT_TRUE(hasPoint(out, {-0.75f, 0.0f, 0.75f}));
  // Face rule: the centroid, (1,0,0) for the face x = +1.
  EXPECT_TRUE(hasPoint(out, {1.0f, 0.0f, 0.0f}));
  EXPECT_TRUE(hasPoint(out, {0.0f, 0.0f, -1.0f}));
  EXPECT_EQ(subdividedFaceCount(cubeMesh(), 1), 24u);
  EXPECT_EQ(subdividedFaceCount(cubeMesh(), 3), 384u);
}

TEST(CatmullClark, BoundaryRulesAreCubicBSpline) {
  // Two quads in a strip; the middle bottom vertex is pulled down. Boundary vertex with two faces:
  // 3/4 V + 1/8 (A + B); corners (one face) stay; boundary edge points are midpoints.
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, -0.5f, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
  const uint32_t a[4] = {0, 1, 4, 3}, b[4] = {1, 2, 5, 4};
  m.addFace(a, 4);
  m.addFace(b, 4);
  PolygonMesh out = subdivideCatmullClark(m);
  EXPECT_NEAR(out.positions[1].x, 1.0f, 1e-6f);
  EXPECT_NEAR(out.positions[1].y, -0.375f, 1e-6f);
  EXPECT_EQ(out.positions[0], glm::vec3(0, 0, 0));
  EXPECT_EQ(out.positions[5], glm::vec3(2, 1, 0));
  EXPECT_TRUE(hasPoint(out, {0.5f, -0.25f, 0.0f}));  // midpoint of the boundary edge 0-1
}

TEST(CatmullClark, InteriorRulesAgreeWithOpenMeshOnAClosedMesh) {
  SourceScene scene = loadOff(test::cgalMesh("torus_quad.off"));
  PolygonMesh mesh = scene.meshes[0];
  repairMesh(mesh, "torus_quad.off");
  PolygonMesh ours = subdivideCatmullClark(mesh);

  using OMesh = OpenMesh::PolyMesh_ArrayKernelT<>;
  OMesh om;
  std::vector<OMesh::VertexHandle> handles;
  for (auto& p : mesh.positions) handles.push_back(om.add_vertex(OMesh::Point(p.x, p.y, p.z)));
  for (size_t f = 0; f < mesh.faceCount(); f++) {
    std::vector<OMesh::VertexHandle> face;
    for (uint32_t i = 0; i < mesh.faceSize(f); i++) face.push_back(handles[mesh.face(f)[i]]);
    om.add_face(face);
  }
  OpenMesh::Subdivider::Uniform::CatmullClarkT<OMesh> subdivider;
  subdivider.attach(om);
  subdivider(1);
  subdivider.detach();
  ASSERT_EQ(size_t(om.n_vertices()), ours.positions.size());
  ASSERT_EQ(size_t(om.n_faces()), ours.faceCount());
  float scale = 0.0f;
  for (auto& p : ours.positions) scale = std::max(scale, glm::length(p));
  for (auto v : om.vertices()) {
    auto p = om.point(v);
    EXPECT_TRUE(hasPoint(ours, {p[0], p[1], p[2]}, 1e-5f * scale)) << "OpenMesh vertex " << v.idx() << " has no match";
  }
}

}  // namespace
}  // namespace vgeo
