// layout.h: from a built DAG to the .vgeo arrays (layout.cpp).
#pragma once

#include "../common/vgeo_file.h"
#include "builder.h"

namespace vgeo {

// Appends one geometry: the DAG of `leafMesh` (the mesh its leaves were built from, whose faces are the
// level-N cage) with its BVH. `closed` records whether the repaired input had no boundary edge.
void appendGeometry(VgeoData& file, const Dag& dag, const PolygonMesh& leafMesh, const std::vector<glm::vec3>& leafNormals, bool closed);

}  // namespace vgeo
