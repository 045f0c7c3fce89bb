// test_check.cpp: the checker finds each kind of violation it promises to find (so a passing check
// means something).
#include <cmath>

#include "test_util.h"

namespace vgeo {
namespace {

VgeoData scene() { return test::build(test::cgalMesh("torus_quad.off"), 3); }

void expectViolation(const VgeoData& data, const std::string& what) {
  CheckResult r = checkVgeo(data, {32, 11});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.firstViolation.find(what), std::string::npos) << "got: " << r.firstViolation;
}

TEST(Check, PassesOnAGoodFile) { EXPECT_TRUE(checkVgeo(scene(), {16, 1}).ok); }

TEST(Check, FindsALeafVertexOffItsPatch) {
  VgeoData data = scene();
  CheckResult good = checkVgeo(data, {1, 1});
  ASSERT_TRUE(good.ok) << good.firstViolation;
  EXPECT_GT(good.checkedPatches, data.patches.size() / 2);  // a subdivided quad torus: nearly all regular
  for (const auto& patch : data.patches)
    if (shaderio::patchKind(patch.info) == VGEO_PATCH_REGULAR) {
      data.controlPoints[3 * (patch.pointBase + data.patchPoints[patch.firstPoint + 5])] +=
          0.01f * data.geometries[0].boundsSphere.w;
      break;
    }
  expectViolation(data, "is not its leaf vertex");
}

TEST(Check, FindsNeighboursThatDisagreeOnAnEdge) {
  VgeoData data = scene();
  data.patches[3].edgeError[1] *= 1.5f;
  expectViolation(data, "disagree on its chord error");
  data = scene();
  data.patches[5].info ^= 1u << 17;  // lock or unlock edge 1 on one side only
  expectViolation(data, "disagree on whether it is locked");
}

TEST(Check, FindsAReversedTriangle) {
  VgeoData data = scene();
  uint32_t& tri = data.clusterTriangles[data.clusters[data.geometries[0].clusterOffset].triangleOffset];
  tri = (tri & 0xff) << 8 | ((tri >> 8) & 0xff) | (tri & 0xff0000);  // swap two corners
  expectViolation(data, "invariant 5");
}

TEST(Check, FindsAGroupErrorBelowAMember) {
  VgeoData data = scene();
  for (auto& c : data.clusters)
    if (c.producer != VGEO_NO_GROUP && !std::isinf(c.parentError)) {
      data.groups[c.group].error = c.selfError * 0.5f;
      for (auto& m : data.clusters)
        if (m.group == c.group) m.parentError = data.groups[c.group].error;
      break;
    }
  expectViolation(data, "invariant 3");
}

TEST(Check, FindsASphereThatDoesNotEnclose) {
  VgeoData data = scene();
  auto& c = data.clusters[data.geometries[0].clusterOffset];
  data.groups[c.group].sphere.w *= 0.5f;
  for (auto& m : data.clusters)
    if (m.group == c.group) m.parentSphere = data.groups[c.group].sphere;
  expectViolation(data, "sphere");
}

TEST(Check, FindsAnUnsharedParent) {
  VgeoData data = scene();
  data.clusters[data.geometries[0].clusterOffset].parentError += 1.0f;
  expectViolation(data, "invariant 2");
}

TEST(Check, FindsOverlapWhenAParentStaysDrawn) {
  // A cluster whose parent error is raised to +inf stays drawn when its group is replaced by coarser
  // clusters: its area is covered twice.
  VgeoData data = scene();
  for (uint32_t g = 0; g < data.groups.size(); g++)
    if (!std::isinf(data.groups[g].error) && data.groups[g].level == 0) {
      data.groups[g].error = INFINITY;
      for (auto& m : data.clusters)
        if (m.group == g) m.parentError = INFINITY;
      for (auto& n : data.nodes) n.maxError = INFINITY;
      break;
    }
  expectViolation(data, "");
}

}  // namespace
}  // namespace vgeo
