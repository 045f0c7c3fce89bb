// shaderio_scene.h: the .vgeo file's structs, which are also the renderer's scene buffers, declared once
// for C++ and GLSL, with the small functions both sides read them with. A .vgeo file's sections are arrays
// of these structs, byte for byte, so the renderer uploads them as they are read. Every struct is a
// multiple of 16 bytes and uses only vec4, float and uint, so std430 (GLSL) and the C++ layout agree
// without padding rules; the static_asserts pin the sizes.
#ifndef VGEO_SHADERIO_SCENE_H
#define VGEO_SHADERIO_SCENE_H

#include "shaderio_core.h"

VGEO_NAMESPACE_BEGIN

#define VGEO_MAX_CLUSTER_TRIANGLES 128
#define VGEO_MAX_CLUSTER_VERTICES 256
#define VGEO_BVH_WIDTH 8
// A group's cluster count is at most this (the persistent traversal numbers a workgroup's tests in 20 bits).
#define VGEO_MAX_GROUP_CLUSTERS 256
// The root's children are the simplification levels' subtrees (joined under inner nodes of 8 only past
// this many levels). The root is never a queue item: instance culling tests its children, which saves
// the traversal two dependent steps of its chain.
#define VGEO_BVH_ROOT_WIDTH 64
#define VGEO_NODE_LEAF_BIT 0x80000000u
#define VGEO_NO_GROUP 0xffffffffu

// One cluster: <= 128 triangles over <= 256 vertices (8-bit local indices).
// self   = (error, sphere) of the group that produced it (leaves: error 0, the cluster's own sphere);
// parent = (error, sphere) of the group it belongs to (clusters of the last level: error = +inf).
// Draw iff project(self) <= tau < project(parent) (docs/design.md, invariant 4).
struct Cluster {
  vec4 selfSphere;  // xyz centre, w radius; encloses the cluster's triangles
  vec4 parentSphere;
  float selfError;  // object-space distance
  float parentError;
  uint vertexOffset;    // into the cluster-vertex section (absolute vertex indices)
  uint triangleOffset;  // into the cluster-triangle section (one uint per triangle: 3 x 8-bit local indices)
  uint counts;          // packed, see clusterVertexCount() etc.
  uint group;           // the group it belongs to (absolute group index)
  uint producer;        // the group that produced it, VGEO_NO_GROUP for leaves
  uint cageFaceOffset;  // leaves: into the cluster-cage-face section; count in counts
};

// A group: clusters of one level simplified together. Its members are contiguous in the cluster array.
struct Group {
  vec4 sphere;         // encloses the members' self spheres
  float error;         // >= every member's self error; +inf for the root groups
  uint clusterOffset;  // absolute cluster index of the first member
  uint clusterCount;
  uint level;  // the simplification round that formed it
};

// BVH node over groups. Children are contiguous: nodes, or groups when VGEO_NODE_LEAF_BIT is set in
// childCountAndFlags. sphere encloses every group below; maxError is the largest group error below.
struct BvhNode {
  vec4 sphere;
  float maxError;
  uint childOffset;  // absolute node or group index
  uint childCountAndFlags;
  uint level;  // simplification level of the groups below; 0xffffffff for mixed (the root)
};

// A geometry: one mesh's DAG. Offsets are absolute indices into the file's sections.
struct Geometry {
  vec4 boundsSphere;  // encloses every cluster of the geometry
  uint clusterOffset;
  uint clusterCount;
  uint groupOffset;
  uint groupCount;
  uint nodeOffset;  // the BVH root is nodes[nodeOffset]
  uint nodeCount;
  uint vertexOffset;
  uint vertexCount;
  uint cageFaceOffset;  // into the cage-face section (the level-N cage, one entry per face)
  uint cageFaceCount;
  uint levelCount;
  uint flags;  // VGEO_GEOMETRY_CLOSED: the repaired input had no boundary edge and no split vertex
};
#define VGEO_GEOMETRY_CLOSED 1u

// An instance: a row-major 3x4 object-to-world transform and the geometry it shows. maxScale is the
// largest axis scale of the transform: object-space errors and radii times maxScale bound world ones.
struct Instance {
  vec4 row0;
  vec4 row1;
  vec4 row2;
  uint geometry;
  float maxScale;
  uint flags;     // VGEO_INSTANCE_CONE_CULL: uniform scale of a closed geometry (back-facing clusters may go)
  uint reserved;  // 0
};
#define VGEO_INSTANCE_CONE_CULL 1u

// Cluster normal cone (its own section): xyz the unit axis, w = sin of the cone's half angle (every
// triangle normal is within it), or -1 when the normals spread over 90 degrees; and the cluster's own
// tight bounding sphere (self spheres are their whole group's). A cluster in sphere (c, r) faces wholly
// away from an eye e when, with v = c - e,
//   dot(v, axis) >= w |v| + r (1 + w)
// (conservative: every point of the sphere then sees every normal of the cone from behind).
struct ClusterCone {
  vec4 cone;
  vec4 sphere;
};
VGEO_INLINE bool clusterFacesAway(vec4 cone, vec4 sphere, vec3 eye) {
  if (cone.w < 0.0f) return false;
  vec3 v = vec3(sphere.x, sphere.y, sphere.z) - eye;
  return dot(v, vec3(cone.x, cone.y, cone.z)) >= cone.w * length(v) + sphere.w * (1.0f + cone.w);
}

// A face of the level-N cage: its corner vertices are cageFaceVertices[first .. first+count).
struct CageFace {
  uint firstVertex;
  uint vertexCount;
  uint leafCluster;    // the leaf cluster holding the face
  uint firstTriangle;  // its first triangle within that cluster (a face's triangles are consecutive)
};

// The limit-surface patch of a face of the level-N cage (patch_eval.h evaluates it), one per cage face.
// Face parameters (s, t): corner 0 at (0, 0), 1 at (1, 0), 2 at (1, 1), 3 at (0, 1); edge k runs from
// corner k to corner k + 1.
//   VGEO_PATCH_REGULAR: a bicubic B-spline patch, 16 control points row by row, the face the middle cell
//     (corners points 5, 6, 10, 9): four corners of valence 4, or on a boundary of 2 faces (1 face: a
//     corner), the points beyond a boundary mirrored across it (phantom points, 2 b - a).
//   VGEO_PATCH_RING: one extraordinary interior corner (corner(), valence()): its 2N + 8 control points
//     in Stam's order (patch_eval.h).
//   VGEO_PATCH_TREE: anything else (two extraordinary corners, an extraordinary corner on a boundary, a
//     valence above VGEO_MAX_VALENCE): the face subdivided locally, a quadtree of at most
//     VGEO_MAX_PATCH_DEPTH levels whose leaves are patches of the kinds above (feature-adaptive
//     subdivision); the last level's quadrant at the irregular corner is bilinear between its corners'
//     limit points, smaller than the finest tessellation step (1 / 64), so only its corners are evaluated.
//   VGEO_PATCH_NONE: no patch (a cage that was not subdivided, or topology no rule covers): drawn flat
//     (its leaf triangles), every edge at factor 1.
// A patch's words start at patchPoints[firstPoint]: the control-point indices of a REGULAR or RING patch
// (relative to pointBase); for a TREE the four child offsets (relative to firstPoint) of the quadrants at
// corners 0..3, each child a node: one info word (kind, corner, valence as in Patch.info) followed by its
// own words; a NONE node holds the 4 points it is bilinear between.
// Tessellation factors come from each edge alone (its corners and edgeError), so the two faces of an
// edge agree; a locked edge stays at factor 1 (the border of a level-0 group, whose other side may be a
// coarser cluster, or an edge of a flat face). Edge points are evaluated on the face of the lower index
// (neighbours), so both sides compute the same vertices bit for bit.
#define VGEO_PATCH_NONE 0u
#define VGEO_PATCH_REGULAR 1u
#define VGEO_PATCH_RING 2u
#define VGEO_PATCH_TREE 3u
#define VGEO_MAX_PATCH_DEPTH 6
struct Patch {
  uint firstPoint;     // into the patch-point section: the patch's words
  uint info;           // kind (bits 0-1), ring: corner (bits 2-3), valence (bits 8-15); locked edges (bits 16-19)
  float faceError;     // object-space chord error of the face's leaf triangles against the patch (>= edgeError)
  uint pointBase;      // control point of index 0 in the patch's words (its geometry's first control point)
  uint neighbours[4];  // across edge k: the face's absolute index << 2 | its edge; VGEO_INVALID on a boundary
  vec4 edgeError;      // chord error of edge k's leaf segment against the limit curve, the same on both sides
};
VGEO_INLINE uint patchKind(uint info) { return info & 3u; }
VGEO_INLINE uint patchCorner(uint info) { return (info >> 2u) & 3u; }
VGEO_INLINE uint patchValence(uint info) { return (info >> 8u) & 0xffu; }
VGEO_INLINE bool patchEdgeLocked(uint info, uint edge) { return ((info >> (16u + edge)) & 1u) != 0u; }
VGEO_INLINE  // Control points of a patch or tree node of this kind (a tree node: its 4 children).
    uint
    patchWordCount(uint info) {
  uint kind = patchKind(info);
  return kind == VGEO_PATCH_REGULAR ? 16u : kind == VGEO_PATCH_RING ? 2u * patchValence(info) + 8u : 4u;
}

// Packing of Cluster.counts: vertex count (9 bits), triangle count (8), level (7), cage face count (8).
VGEO_INLINE uint packClusterCounts(uint vertexCount, uint triangleCount, uint level, uint cageFaceCount) {
  return vertexCount | (triangleCount << 9) | (level << 17) | (cageFaceCount << 24);
}
VGEO_INLINE uint clusterVertexCount(uint counts) { return counts & 0x1ffu; }
VGEO_INLINE uint clusterTriangleCount(uint counts) { return (counts >> 9) & 0xffu; }
VGEO_INLINE uint clusterLevel(uint counts) { return (counts >> 17) & 0x7fu; }
VGEO_INLINE uint clusterCageFaceCount(uint counts) { return counts >> 24; }

// Projected error in pixels of an (error, sphere) pair seen from `eye`: error * projScale / distance to
// the sphere, with projScale = viewport height / (2 tan(fovY / 2)). A camera within znear of the sphere
// sees an unbounded error (it needs the finest level there); zero error projects to zero. The same
// function decides the cut on the GPU and in the CPU reference, so the two agree up to rounding.
// Monotonic: a larger error in an enclosing sphere never projects smaller (docs/design.md, invariant 3).
VGEO_INLINE float projectedError(vec4 sphere, float error, vec3 eye, float projScale, float znear) {
  if (error == 0.0f) return 0.0f;
  float d = length(vec3(sphere.x, sphere.y, sphere.z) - eye) - sphere.w;
  if (d <= znear) return uintBitsToFloat(0x7f800000u);
  return error * projScale / d;
}

// The cut rule (invariant 4) with its one exception: a leaf (no producer) has nothing finer below it, so
// it is drawn whenever its parent is too coarse, whatever its own error (its chord error against the limit
// surface); with self > tau the renderer draws its patches instead of its triangles (docs/design.md, leaves).
VGEO_INLINE bool inCut(float self, float parent, float tau, bool leaf) { return (self <= tau || leaf) && tau < parent; }

// An instance's object-to-world transform of a point, and of a bounding sphere (radius times maxScale).
VGEO_INLINE vec3 instanceToWorld(Instance inst, vec3 p) {
  vec4 h = vec4(p.x, p.y, p.z, 1.0f);
  return vec3(dot(inst.row0, h), dot(inst.row1, h), dot(inst.row2, h));
}
VGEO_INLINE vec4 worldSphere(Instance inst, vec4 sphere) {
  vec3 c = instanceToWorld(inst, vec3(sphere.x, sphere.y, sphere.z));
  return vec4(c.x, c.y, c.z, sphere.w * inst.maxScale);
}

// A vertex normal of the normals section: octahedral, 2 x snorm16, x low (vgeo_file.h, encodeNormal).
VGEO_INLINE vec3 decodeNormal(uint packed) {
  float x = float(int(packed << 16u) >> 16) / 32767.0f, y = float(int(packed) >> 16) / 32767.0f;
  float z = 1.0f - abs(x) - abs(y);
  if (z < 0.0f) {
    float fx = (1.0f - abs(y)) * (x >= 0.0f ? 1.0f : -1.0f), fy = (1.0f - abs(x)) * (y >= 0.0f ? 1.0f : -1.0f);
    x = fx;
    y = fy;
  }
  return normalize(vec3(x, y, z));
}

#ifdef __cplusplus
static_assert(sizeof(Cluster) == 64, "Cluster layout");
static_assert(sizeof(Group) == 32, "Group layout");
static_assert(sizeof(BvhNode) == 32, "BvhNode layout");
static_assert(sizeof(Geometry) == 64, "Geometry layout");
static_assert(sizeof(Instance) == 64, "Instance layout");
static_assert(sizeof(CageFace) == 16, "CageFace layout");
static_assert(sizeof(ClusterCone) == 32, "ClusterCone layout");
static_assert(sizeof(Patch) == 48, "Patch layout");
#endif

VGEO_NAMESPACE_END

#endif
