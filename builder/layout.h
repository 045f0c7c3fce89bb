// layout.h: from a built DAG to the .vgeo arrays (layout.cpp).
#pragma once

#include "../common/vgeo_file.h"
#include "builder.h"

namespace vgeo {

// Appends one geometry: the DAG of `leafMesh` (the mesh its leaves were built from, whose faces are the
// level-N cage) with its BVH: a vertex a wedge of `shading` (its position and shading normal; one a leaf
// vertex unless the mesh has hard edges), its clusters, groups and BVH, its cage faces and a patch per
// cage face: `patches` (buildPatches of a subdivided cage, whose leaf vertices are limit points; their
// words and control points move to the file) with the chord errors `patchErrors` (patchChordErrors), or
// flat ones where `patches` is empty. `closed` records whether the repaired input had no boundary edge.
// The clusters' normal cones and spheres are made on up to `threads` threads.
void appendGeometry(VgeoData& file, const Dag& dag, const PolygonMesh& leafMesh, const ShadingNormals& shading,
                    MeshPatches&& patches, const std::vector<PatchErrors>& patchErrors, bool closed, int threads = 1);

}  // namespace vgeo
