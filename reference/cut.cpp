// cut.cpp: the CPU reference cut. Deliberately the plainest form of the cut rule, one test per cluster
// with no hierarchy, so that it can stand as the reference for the GPU traversals.
#include "cut.h"

namespace vgeo {

std::vector<uint32_t> selectCut(const VgeoData& data, uint32_t geometry, const LodView& view) {
  const shaderio::Geometry& g = data.geometries[geometry];
  std::vector<uint32_t> cut;
  for (uint32_t i = g.clusterOffset; i < g.clusterOffset + g.clusterCount; i++) {
    const shaderio::Cluster& c = data.clusters[i];
    float self = shaderio::projectedError(c.selfSphere, c.selfError, view.eye, view.projScale, view.znear);
    float parent = shaderio::projectedError(c.parentSphere, c.parentError, view.eye, view.projScale, view.znear);
    if (shaderio::inCut(self, parent, view.tau, c.producer == VGEO_NO_GROUP)) cut.push_back(i);
  }
  return cut;
}

}  // namespace vgeo
