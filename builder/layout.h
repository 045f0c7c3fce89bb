// layout.h: from a built DAG to the .vgeo arrays (layout.cpp).
#pragma once

#include "../common/vgeo_file.h"
#include "builder.h"

namespace vgeo {

// Appends one geometry: the DAG of `leafMesh` (the mesh its leaves were built from, whose faces are the
// level-N cage) with its BVH. `closed` records whether the repaired input had no boundary edge.
// Appends one geometry: its leaf vertices (with `leafNormals` when given, else face-weighted normals), its
// clusters, groups and BVH, its cage faces and, when `controlPoints` is given (a subdivided cage, whose
// leaf vertices are limit points), the control points and a B-spline patch per regular cage face.
void appendGeometry(VgeoData& file, const Dag& dag, const PolygonMesh& leafMesh, const std::vector<glm::vec3>& leafNormals,
                    const std::vector<glm::vec3>& controlPoints, bool closed);

}  // namespace vgeo
