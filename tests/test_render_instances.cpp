// test_render_instances.cpp: how instance transforms reach the picture, on lavapipe (or any device) with
// the validation layer. A mirror (negative scale, or a matrix of negative determinant, in a scene file or
// a glTF node) reverses the triangles' winding: the mirrored instance must look like the unmirrored one
// mirrored, lit from its outside, with its triangles and its patches, and cone and triangle culling may
// not drop what faces the eye.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "../renderer/gpu_renderer.h"
#include "../renderer/image.h"
#include "render_util.h"
#include "gltf_writer.h"
#include "test_util.h"

namespace vgeo {
namespace {

constexpr uint32_t kW = 320, kH = 240;

class RenderInstances : public test::GpuSuite {
 protected:
  static void SetUpTestSuite() { openSuite("vgeo_render_instance_tests"); }
  static void TearDownTestSuite() { closeSuite(); }

  static FrameResult render(const std::string& path, const Camera& camera, float tau, bool patches,
                            Raster raster = Raster::Auto) {
    RenderScene scene = loadRenderScene(path);
    GpuRenderer renderer(*vk, scene, kW, kH);
    FrameSettings s = test::frameSettings(scene, camera, tau, kW, kH);
    s.patches = patches;
    s.raster = raster;
    s.mode = VGEO_MODE_NORMAL;
    FrameResult r = renderer.renderFrame(s);
    EXPECT_TRUE(r.complete);
    return r;
  }

  // `mirrored` (an image of the scene mirrored in the plane x = 0, seen from a camera on that plane)
  // against `plain` flipped left to right, in the normal view (colour = n / 2 + 1 / 2, so a mirrored
  // normal has red 255 - red). Returns the mean channel difference over pixels covered in both; expects
  // the coverage to be the mirror image within `coverageSlack` of the covered pixels.
  static double mirrorDifference(const FrameResult& mirrored, const FrameResult& plain, double coverageSlack) {
    uint64_t both = 0, onlyOne = 0, covered = 0;
    double difference = 0.0;
    for (uint32_t y = 0; y < kH; y++)
      for (uint32_t x = 0; x < kW; x++) {
        const uint8_t* a = &mirrored.rgba[4 * (y * kW + x)];
        const uint8_t* b = &plain.rgba[4 * (y * kW + (kW - 1 - x))];
        bool ca = isCovered(a), cb = isCovered(b);
        covered += cb;
        if (ca != cb) onlyOne++;
        if (!(ca && cb)) continue;
        both++;
        difference +=
            std::abs(int(a[0]) - (255 - int(b[0]))) + std::abs(int(a[1]) - int(b[1])) + std::abs(int(a[2]) - int(b[2]));
      }
    EXPECT_GT(covered, uint64_t(kW * kH / 20)) << "the object is in view";
    EXPECT_LE(double(onlyOne), coverageSlack * double(covered)) << "covered pixels that are not the mirror image";
    return both ? difference / double(3 * both) : 1e9;
  }

  static std::string scene(const std::string& name, const std::string& vgeo, const std::string& placement) {
    return test::writeFile(*dir, name,
                           "{\"geometries\": [\"" + vgeo + "\"], \"instances\": [{\"geometry\": 0" + placement + "}]}");
  }
};

// A camera on the plane x = 0 looking at a point of it, at `distance` from it.
Camera onMirrorPlane(float y, float z, float distance) {
  Camera c;
  c.target = {0.0f, y, z};
  c.eye = c.target + glm::vec3(0.0f, 0.3f * distance, 0.95f * distance);
  return c;
}

TEST_F(RenderInstances, MirroredInstancesLookLikeTheirMirrorImage) {
  // CGAL's cow (not symmetric in any plane) as triangles and, after one round, close up as patches.
  writeVgeo(test::build(test::cgalMesh("cow.off"), 0), *dir + "/cow0.vgeo");
  writeVgeo(test::build(test::cgalMesh("cow.off"), 1), *dir + "/cow1.vgeo");
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), 0.6f, glm::vec3(1.0f, 0.0f, 0.0f));  // keeps the plane x = 0
  const glm::mat4 mirror = turn * glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
  auto matrix = [](const glm::mat4& m) {
    std::string s = ", \"matrix\": [";
    for (int i = 0; i < 16; i++) {
      if (i) s += ",";
      s += std::to_string(m[i / 4][i % 4]);
    }
    return s + "]";
  };
  struct Case {
    const char* what;
    std::string vgeo, plain, mirrored;
    Camera camera;
    float tau;
    bool patches;
    Raster raster = Raster::Auto;
  };
  const std::vector<Case> cases = {
      {"scale [-1, 1, 1]", "cow0.vgeo", "", ", \"scale\": [-1, 1, 1]", onMirrorPlane(0.0f, 0.0f, 1.3f), 1.0f, false},
      {"a turned mirror matrix", "cow0.vgeo", matrix(turn), matrix(mirror), onMirrorPlane(0.0f, 0.0f, 1.3f), 1.0f,
       false},
      {"patches, scale [-1, 1, 1]", "cow1.vgeo", "", ", \"scale\": [-1, 1, 1]", onMirrorPlane(0.1f, 0.0f, 0.45f), 0.5f,
       true},
      // The same with the patches tessellated and rasterized in compute, shaded by the resolve.
      {"patches in compute, scale [-1, 1, 1]", "cow1.vgeo", "", ", \"scale\": [-1, 1, 1]",
       onMirrorPlane(0.1f, 0.0f, 0.45f), 0.5f, true, Raster::Software},
  };
  for (const Case& c : cases) {
    FrameResult plain = render(scene("plain.json", c.vgeo, c.plain), c.camera, c.tau, c.patches, c.raster);
    FrameResult mirrored = render(scene("mirrored.json", c.vgeo, c.mirrored), c.camera, c.tau, c.patches, c.raster);
    if (c.patches) {
      EXPECT_GT(mirrored.patchesDrawn, 200u) << c.what;
    }
    if (c.raster == Raster::Software) {
      EXPECT_GT(mirrored.softwarePatches, 200u) << c.what;
    }
    EXPECT_EQ(plain.counters.drawCount, mirrored.counters.drawCount)
        << c.what << ": the mirrored cut has as many clusters";
    EXPECT_LT(mirrorDifference(mirrored, plain, 0.01), 4.0) << c.what << ": mean channel difference of the normal view";
  }

  // The same through a glTF node: the builder keeps the mirrored node's transform.
  SourceScene cow = loadMeshFile(test::cgalMesh("cow.off"));
  writeVgeo(test::build(test::gltfOf(*dir, "plain.gltf", cow.meshes[0], ""), 0), *dir + "/plain_gltf.vgeo");
  writeVgeo(test::build(test::gltfOf(*dir, "mirrored.gltf", cow.meshes[0], R"(, "scale": [-1, 1, 1])"), 0),
            *dir + "/mirrored_gltf.vgeo");
  FrameResult plain = render(*dir + "/plain_gltf.vgeo", onMirrorPlane(0.0f, 0.0f, 1.3f), 1.0f, false);
  FrameResult mirrored = render(*dir + "/mirrored_gltf.vgeo", onMirrorPlane(0.0f, 0.0f, 1.3f), 1.0f, false);
  EXPECT_LT(mirrorDifference(mirrored, plain, 0.01), 4.0) << "glTF node scale [-1, 1, 1]";
}

}  // namespace
}  // namespace vgeo
