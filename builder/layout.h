// layout.h: from a built DAG to the .vgeo arrays (layout.cpp).
#pragma once

#include "../common/section_sink.h"
#include "builder.h"

namespace vgeo {

// Where a geometry's patch words and control points start in the file's sections.
struct PatchBases {
  uint32_t point = 0, word = 0;
};
// Appends the words and control points of `patches` (buildPatches of a subdivided cage) to the file and
// frees them: written before the geometry's DAG is built, they are not held through it.
PatchBases appendPatchPoints(SectionSink& file, MeshPatches& patches);

// Appends one geometry to the file's sections: the DAG of `leafMesh` (the mesh its leaves were built
// from, whose faces are the level-N cage) with its BVH: a vertex a wedge of `shading` (its position and
// shading normal; one a leaf vertex unless the mesh has hard edges), its clusters, groups and BVH, and,
// for a subdivided cage, its cage faces and a patch per cage face: `patches` (buildPatches, whose leaf
// vertices are limit points; its words and control points already in the file at `bases`) with the
// chord errors `patchErrors` (patchChordErrors). Where `patches` is empty (a mesh not subdivided) there
// is no surface below the leaves and the geometry has no cage faces: they would be three quarters of
// its file, never read. `closed` records whether the repaired input had no boundary edge. `last`: no
// geometry follows, so every section but the instances ends with this one's part (SectionSink::
// expectTotal; the caller expects the instances' total first). The clusters' normal cones and spheres
// are made on up to `threads` threads.
void appendGeometry(SectionSink& file, const Dag& dag, const PolygonMesh& leafMesh, const ShadingNormals& shading,
                    const MeshPatches& patches, PatchBases bases, const PatchErrorList& patchErrors, bool closed,
                    bool last, int threads = 1);

}  // namespace vgeo
