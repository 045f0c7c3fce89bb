// test_normals.cpp: shading normals from the input to the picture. Normals a file gives (glTF NORMAL,
// OBJ vn, PLY nx ny nz) are kept, so hard edges stay hard; a glTF without normals is flat, as its
// specification asks; `--crease-angle` gives inputs without normals hard edges; coarser levels keep them;
// a subdivided cage keeps the limit surface's smooth normals. Checked on the .vgeo's own data and, for
// BoxTextured, in a frame drawn on lavapipe (or any device) with the validation layer.
#include <cmath>
#include <cstring>
#include <set>

#include "../renderer/gpu_renderer.h"
#include "../renderer/image.h"
#include "gltf_writer.h"
#include "render_util.h"
#include "test_util.h"

namespace vgeo {
namespace {

struct Corner {
  glm::vec3 shading;  // the vertex's normal in the file
  glm::vec3 face;     // the triangle's unit normal
  uint32_t level;
};

// Every corner of every triangle of every cluster, with its shading normal and its face's normal.
std::vector<Corner> corners(const VgeoData& d) {
  std::vector<Corner> out;
  for (const shaderio::Cluster& c : d.clusters)
    for (uint32_t t = 0; t < shaderio::clusterTriangleCount(c.counts); t++) {
      const uint32_t packed = d.clusterTriangles[c.triangleOffset + t];
      uint32_t v[3];
      for (int k = 0; k < 3; k++) v[k] = d.clusterVertices[c.vertexOffset + ((packed >> (8 * k)) & 0xffu)];
      glm::vec3 n = glm::cross(d.position(v[1]) - d.position(v[0]), d.position(v[2]) - d.position(v[0]));
      if (glm::length(n) == 0.0f) continue;
      n = glm::normalize(n);
      for (int k = 0; k < 3; k++)
        out.push_back({shaderio::decodeNormal(d.normals[v[k]]), n, shaderio::clusterLevel(c.counts)});
    }
  return out;
}

// Fraction of corners (of level `level`, or all when negative) whose shading normal is more than
// `degrees` from their face's normal.
double fractionBent(const VgeoData& d, float degrees, int level = -1) {
  size_t bent = 0, total = 0;
  for (const Corner& c : corners(d)) {
    if (level >= 0 && c.level != uint32_t(level)) continue;
    total++;
    bent += glm::dot(c.shading, c.face) < std::cos(glm::radians(degrees));
  }
  return total ? double(bent) / double(total) : 0.0;
}

VgeoData buildWithCrease(const std::string& path, float crease, int subdiv = 0) {
  SceneBuildOptions options;
  options.subdivisionLevels = subdiv;
  options.threads = 2;
  options.creaseAngleDegrees = crease;
  SceneBuildStats stats;
  return buildScene(path, options, stats);
}

TEST(Normals, GltfFaceNormalsStayFlatAndTheBoxIsDrawnWithSharpEdges) {
  // BoxTextured: 24 vertices with a normal a face; welded by position into 8 corners of 3 normals each.
  const std::string box = test::assimpModel("BoxTextured-glTF-Binary/BoxTextured.glb");
  VgeoData d = test::build(box, 0);
  EXPECT_EQ(d.vertexCount(), 24u);
  EXPECT_EQ(fractionBent(d, 1.0f), 0.0) << "every corner shades like its face";
  EXPECT_EQ(d.clusters.size(), 1u);

  // Drawn in the normal view from a corner: three faces, three flat colours (a smooth blob had hundreds).
  VulkanContext vk({"", true});
  const std::string path = test::tempDir() + "/box.vgeo";
  writeVgeo(d, path);
  RenderScene scene = loadRenderScene(path);
  GpuRenderer renderer(vk, scene, 256, 192);
  FrameSettings s = test::frameSettings(scene, test::orbit(scene, 0.7f, 0.5f, 3.0f), 1.0f, 256, 192);
  s.mode = VGEO_MODE_NORMAL;
  FrameResult r = renderer.renderFrame(s);
  std::set<uint32_t> colours;
  size_t covered = 0;
  for (size_t i = 0; i < r.rgba.size() / 4; i++)
    if (isCovered(&r.rgba[4 * i])) {
      covered++;
      colours.insert(uint32_t(r.rgba[4 * i]) | uint32_t(r.rgba[4 * i + 1]) << 8 | uint32_t(r.rgba[4 * i + 2]) << 16);
    }
  EXPECT_GT(covered, 2000u);
  EXPECT_GE(colours.size(), 2u);
  EXPECT_LE(colours.size(), 3u) << "flat faces";
  EXPECT_EQ(vk.validationMessages(), 0u);
}

TEST(Normals, ObjAndPlyNormalsAreKept) {
  const std::string dir = test::tempDir();
  // A cube whose faces name one vn each (hard edges), and a PLY tetrahedron with radial vertex normals.
  std::string obj =
      "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
      "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 1 0 0\nvn 0 1 0\nvn -1 0 0\n"
      "f 1//1 4//1 3//1 2//1\nf 5//2 6//2 7//2 8//2\nf 1//3 2//3 6//3 5//3\nf 2//4 3//4 7//4 6//4\nf 3//5 4//5 8//5 "
      "7//5\nf 4//6 1//6 5//6 8//6\n";
  VgeoData cube = test::build(test::writeFile(dir, "cube.obj", obj), 0);
  EXPECT_EQ(cube.vertexCount(), 24u);
  EXPECT_EQ(fractionBent(cube, 1.0f), 0.0);
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\nelement face 4\nproperty list uchar int "
      "vertex_indices\nend_header\n"
      "1 1 1 0.57735 0.57735 0.57735\n1 -1 -1 0.57735 -0.57735 -0.57735\n-1 1 -1 -0.57735 0.57735 -0.57735\n-1 -1 1 "
      "-0.57735 -0.57735 0.57735\n"
      "3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n";
  VgeoData tetra = test::build(test::writeFile(dir, "tetra.ply", ply), 0);
  ASSERT_EQ(tetra.vertexCount(), 4u);
  for (uint32_t v = 0; v < 4; v++)
    EXPECT_GT(glm::dot(shaderio::decodeNormal(tetra.normals[v]), glm::normalize(tetra.position(v))), 0.9999f)
        << "vertex " << v;
}

TEST(Normals, GltfWithoutNormalsIsFlatAndWithThemSmooth) {
  const std::string dir = test::tempDir();
  SourceScene cow = loadMeshFile(test::cgalMesh("cow.off"));
  VgeoData flat = test::build(test::gltfOf(dir, "cow.gltf", cow.meshes[0], ""), 0);
  EXPECT_EQ(fractionBent(flat, 1.0f, 0), 0.0) << "no NORMAL: flat, as the glTF specification asks";
  // The same cow with smooth normals given per corner (a vertex's normal at all of its corners).
  VgeoData smoothOff = test::build(test::cgalMesh("cow.off"), 0);
  PolygonMesh withNormals = cow.meshes[0];
  std::vector<glm::vec3> vertexNormal(withNormals.positions.size(), glm::vec3(0.0f));
  for (size_t f = 0; f < withNormals.faceCount(); f++) {
    const uint32_t* c = withNormals.face(f);
    glm::vec3 n = glm::cross(withNormals.positions[c[1]] - withNormals.positions[c[0]],
                             withNormals.positions[c[2]] - withNormals.positions[c[0]]);
    for (uint32_t k = 0; k < withNormals.faceSize(f); k++) vertexNormal[c[k]] += n;
  }
  for (uint32_t v : withNormals.faceVertices) withNormals.cornerNormals.push_back(glm::normalize(vertexNormal[v]));
  VgeoData smooth = test::build(test::gltfOf(dir, "cow_normals.gltf", withNormals, ""), 0);
  EXPECT_EQ(smooth.vertexCount(), smoothOff.vertexCount()) << "one normal a vertex: welded back into one vertex each";
  EXPECT_GT(fractionBent(smooth, 10.0f, 0), 0.05);
}

TEST(Normals, WedgesAreTheSameOnAnyThreadCount) {
  // Smooth normals are summed by a walk over the faces on a few threads and through each vertex's
  // faces on more; creases and given normals go through parallel sorts and unions: the same bits.
  SourceScene bunny = loadMeshFile(test::cgalMesh("bunny00.off"));
  PolygonMesh& mesh = bunny.meshes[0];
  for (float crease : {180.0f, 30.0f}) {
    const ShadingNormals one = shadingNormals(mesh, {}, crease, 1), many = shadingNormals(mesh, {}, crease, 8);
    ASSERT_EQ(one.wedgeNormal.size(), many.wedgeNormal.size()) << crease;
    EXPECT_EQ(std::memcmp(one.wedgeNormal.data(), many.wedgeNormal.data(), one.wedgeNormal.size() * sizeof(glm::vec3)),
              0)
        << crease;
    EXPECT_EQ(one.cornerWedge, many.cornerWedge) << crease;
    EXPECT_EQ(one.wedgeVertex, many.wedgeVertex) << crease;
  }
}

TEST(Normals, CreaseAngleGivesCadEdgesAtEveryLevel) {
  // fandisk (CAD, no normals): smoothed everywhere, corners along its 90-degree edges bend ~45 degrees
  // from their faces; with a 40-degree crease angle they do not, at the leaves nor at coarser levels
  // (whose corners take the wedge nearest their own face).
  const std::string fandisk = test::cgalMesh("fandisk.off");
  VgeoData smooth = buildWithCrease(fandisk, 180.0f), creased = buildWithCrease(fandisk, 40.0f);
  EXPECT_EQ(smooth.vertexCount(), 6475u);
  EXPECT_GT(creased.vertexCount(), smooth.vertexCount() + 500);
  EXPECT_GT(fractionBent(smooth, 40.0f, 0), 0.05);
  EXPECT_LT(fractionBent(creased, 40.0f, 0), 0.002);
  uint32_t levels = 0;
  for (const auto& c : creased.clusters) levels = std::max(levels, shaderio::clusterLevel(c.counts) + 1);
  ASSERT_GE(levels, 7u);
  for (uint32_t level = 1; level <= 6; level++) {  // down to ~200 triangles; the last few levels have 12 to 100
    // Level 6 has about 600 corners: a few bend where a coarse triangle spans the crease (5 to 7 of
    // them, as the clusters fall), against two thirds of them when smoothed.
    EXPECT_LT(fractionBent(creased, 40.0f, int(level)), level < 6 ? 0.01 : 0.02) << "level " << level;
    EXPECT_GT(fractionBent(smooth, 40.0f, int(level)), 0.1) << "level " << level;
  }
  // Every file still passes its checks (the vertex limit counts wedges).
  CheckResult check = checkVgeo(creased, {16, 5});
  EXPECT_TRUE(check.ok) << check.firstViolation;
  // A subdivided cage keeps the limit surface's normals whatever the crease angle.
  VgeoData cage = buildWithCrease(test::asset("horned_cube.obj"), 10.0f, 2),
           cageSmooth = buildWithCrease(test::asset("horned_cube.obj"), 180.0f, 2);
  EXPECT_EQ(serializeVgeo(cage), serializeVgeo(cageSmooth));
}

}  // namespace
}  // namespace vgeo
