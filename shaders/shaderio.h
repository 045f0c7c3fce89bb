// shaderio.h: the structs that live in GPU buffers and in .vgeo sections, declared once for C++ and GLSL.
// A .vgeo file's sections are arrays of these structs, byte for byte, so the renderer uploads them as they
// are read. Every struct is a multiple of 16 bytes and uses only vec4, float and uint, so std430 (GLSL) and
// the C++ layout agree without padding rules; the static_asserts below pin the sizes.
#ifndef VGEO_SHADERIO_H
#define VGEO_SHADERIO_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace shaderio {
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using mat4 = glm::mat4;
using uint = uint32_t;
using glm::length;
using glm::dot;
#endif

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
  vec4 selfSphere;      // xyz centre, w radius; encloses the cluster's triangles
  vec4 parentSphere;
  float selfError;      // object-space distance
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
  vec4 sphere;          // encloses the members' self spheres
  float error;          // >= every member's self error; +inf for the root groups
  uint clusterOffset;   // absolute cluster index of the first member
  uint clusterCount;
  uint level;           // the simplification round that formed it
};

// BVH node over groups. Children are contiguous: nodes, or groups when VGEO_NODE_LEAF_BIT is set in
// childCountAndFlags. sphere encloses every group below; maxError is the largest group error below.
struct BvhNode {
  vec4 sphere;
  float maxError;
  uint childOffset;     // absolute node or group index
  uint childCountAndFlags;
  uint level;           // simplification level of the groups below; 0xffffffff for mixed (the root)
};

// A geometry: one mesh's DAG. Offsets are absolute indices into the file's sections.
struct Geometry {
  vec4 boundsSphere;    // encloses every cluster of the geometry
  uint clusterOffset;
  uint clusterCount;
  uint groupOffset;
  uint groupCount;
  uint nodeOffset;      // the BVH root is nodes[nodeOffset]
  uint nodeCount;
  uint vertexOffset;
  uint vertexCount;
  uint cageFaceOffset;  // into the cage-face section (the level-N cage, one entry per face)
  uint cageFaceCount;
  uint levelCount;
  uint flags;           // VGEO_GEOMETRY_CLOSED: the repaired input had no boundary edge and no split vertex
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
  uint flags;           // VGEO_INSTANCE_CONE_CULL: uniform scale of a closed geometry (back-facing clusters may go);
                        // and, set by the renderer (files hold 0), its geometry's BVH root: child count in
                        // bits VGEO_INSTANCE_ROOT_COUNT_SHIFT.., VGEO_INSTANCE_ROOT_LEAF when its children are groups
  uint rootChildOffset; // set by the renderer (files hold 0): the root's first child
};
#define VGEO_INSTANCE_CONE_CULL 1u
// Instance culling tests the root's children straight from the instance record: the root (and the
// geometry before it) were two loads in a row on the way to the first queue item.
#define VGEO_INSTANCE_ROOT_LEAF 2u
#define VGEO_INSTANCE_ROOT_COUNT_SHIFT 8u

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
#ifdef __cplusplus
inline
#endif
bool clusterFacesAway(vec4 cone, vec4 sphere, vec3 eye) {
  if (cone.w < 0.0f) return false;
  vec3 v = vec3(sphere.x, sphere.y, sphere.z) - eye;
  return dot(v, vec3(cone.x, cone.y, cone.z)) >= cone.w * length(v) + sphere.w * (1.0f + cone.w);
}

// A face of the level-N cage: its corner vertices are cageFaceVertices[first .. first+count).
struct CageFace {
  uint firstVertex;
  uint vertexCount;
  uint leafCluster;     // the leaf cluster holding the face
  uint firstTriangle;   // its first triangle within that cluster (a face's triangles are consecutive)
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
  uint firstPoint;      // into the patch-point section: the patch's words
  uint info;            // kind (bits 0-1), ring: corner (bits 2-3), valence (bits 8-15); locked edges (bits 16-19)
  float faceError;      // object-space chord error of the face's leaf triangles against the patch (>= edgeError)
  uint pointBase;       // control point of index 0 in the patch's words (its geometry's first control point)
  uint neighbours[4];   // across edge k: the face's absolute index << 2 | its edge; VGEO_INVALID on a boundary
  vec4 edgeError;       // chord error of edge k's leaf segment against the limit curve, the same on both sides
};
#ifdef __cplusplus
inline
#endif
uint patchKind(uint info) { return info & 3u; }
#ifdef __cplusplus
inline
#endif
uint patchCorner(uint info) { return (info >> 2u) & 3u; }
#ifdef __cplusplus
inline
#endif
uint patchValence(uint info) { return (info >> 8u) & 0xffu; }
#ifdef __cplusplus
inline
#endif
bool patchEdgeLocked(uint info, uint edge) { return ((info >> (16u + edge)) & 1u) != 0u; }
#ifdef __cplusplus
inline
#endif
// Control points of a patch or tree node of this kind (a tree node: its 4 children).
uint patchWordCount(uint info) {
  uint kind = patchKind(info);
  return kind == VGEO_PATCH_REGULAR ? 16u : kind == VGEO_PATCH_RING ? 2u * patchValence(info) + 8u : 4u;
}

// ---- Renderer -------------------------------------------------------------------------------------

// Debug shading modes (--mode).
#define VGEO_MODE_LIT 0
#define VGEO_MODE_NORMAL 1
#define VGEO_MODE_CLUSTER 2
#define VGEO_MODE_GROUP 3
#define VGEO_MODE_LOD 4
#define VGEO_MODE_TRIANGLE 5
#define VGEO_MODE_INSTANCE 6
#define VGEO_MODE_ERROR 7
#define VGEO_MODE_WIRE 8
#define VGEO_MODE_OVERDRAW 9
#define VGEO_MODE_FROZEN_DIFF 10
#define VGEO_MODE_PATCH 11

#define VGEO_INVALID 0xffffffffu
#define VGEO_ITEM_GROUP_BIT 0x80000000u  // queue item names a group, not a BVH node
// Sweep run (persistent traversal): the item's code is VGEO_ITEM_RUN_BIT | first cluster, and its instance
// word carries (run length - 1) << VGEO_RUN_INSTANCE_BITS above the instance index: up to VGEO_SWEEP_RUN
// clusters of one simplification level, tested without walking its subtree. Instances are 64 bytes, so a
// storage buffer (maxStorageBufferRange <= 2^32) holds fewer than 2^26 of them.
#define VGEO_ITEM_RUN_BIT 0x40000000u
// A slot reserved for a sweep run that was not granted (cull_instances.comp): taken and skipped.
#define VGEO_ITEM_SKIP (VGEO_ITEM_GROUP_BIT | VGEO_ITEM_RUN_BIT)
#define VGEO_RUN_INSTANCE_BITS 26u
#define VGEO_SWEEP_RUN 64u
#define VGEO_TRAVERSAL_WORKGROUP 64
// Specialization constant of traverse_persistent.comp: cluster tests a lane runs between draw-list atomics.
#define VGEO_SPEC_LANE_TESTS 0
// Worker profile (traverse_persistent.comp built with VGEO_PROFILE, binding 21; vgeo bench cut
// --profile-workers): per workgroup VGEO_PROFILE_WORKER_WORDS words. Header: [0] working iterations
// recorded, [1] iterations, [2] iterations without an item, [3] their summed clock ticks, [4,5] begin,
// [6,7] exit (64-bit device clock, low word first). Then up to VGEO_PROFILE_ITERATIONS records of the
// iterations that took items, VGEO_PROFILE_ITERATION_WORDS each: [0,1] start, [2,3] claimed (after the
// claim), [4,5] taken (the items read and their entries made), [6,7] end (after both rounds), [8] items,
// [9] round-1 tests, [10] round-2 tests, [11] slots claimed that iteration.
#define VGEO_PROFILE_ITERATIONS 48
#define VGEO_PROFILE_ITERATION_WORDS 12
#define VGEO_PROFILE_HEADER_WORDS 8
#define VGEO_PROFILE_WORKER_WORDS (VGEO_PROFILE_HEADER_WORDS + VGEO_PROFILE_ITERATIONS * VGEO_PROFILE_ITERATION_WORDS)
// cull_instances.comp: VGEO_CULL_INSTANCE_LANES lanes an instance in scenes of up to
// VGEO_CULL_SPREAD_INSTANCES instances, in workgroups of VGEO_CULL_SPREAD_WORKGROUP (2 instances each), so
// that the runs of a close view's few instances are written by many lanes side by side; one lane an
// instance (workgroups of 64) in larger ones, where thousands of workgroups reserving queue slots on one
// counter cost more (bench/README.md, cut selection).
#define VGEO_CULL_INSTANCE_LANES 64
#define VGEO_CULL_SPREAD_WORKGROUP 128
#define VGEO_CULL_SPREAD_INSTANCES 4096

// The renderer's one descriptor set, named once for the host (gpu_renderer.cpp fills it) and the
// shaders (common.glsl and the passes declare their buffers with these). 0 is the frame's uniform
// buffer; the scene's arrays come from the .vgeo (and the renderer's per-level cluster runs); the rest
// are the frame's working buffers.
#define VGEO_BINDING_FRAME 0
#define VGEO_BINDING_GEOMETRIES 1
#define VGEO_BINDING_INSTANCES 2
#define VGEO_BINDING_POSITIONS 3
#define VGEO_BINDING_NORMALS 4
#define VGEO_BINDING_CLUSTERS 5
#define VGEO_BINDING_CLUSTER_VERTICES 6
#define VGEO_BINDING_CLUSTER_TRIANGLES 7
#define VGEO_BINDING_GROUPS 8
#define VGEO_BINDING_NODES 9
#define VGEO_BINDING_COUNTERS 10
#define VGEO_BINDING_QUEUE 11
#define VGEO_BINDING_DRAW_LIST 12
#define VGEO_BINDING_CLUSTER_CONES 13
#define VGEO_BINDING_TRIANGLE_LIST 14
#define VGEO_BINDING_CONTROL_POINTS 15
#define VGEO_BINDING_CAGE_FACES 16
#define VGEO_BINDING_CAGE_FACE_VERTICES 17
#define VGEO_BINDING_PATCHES 18
#define VGEO_BINDING_PATCH_POINTS 19
#define VGEO_BINDING_PATCH_LIST 20
#define VGEO_BINDING_WORKER_PROFILE 21
#define VGEO_BINDING_LEVEL_CLUSTER_RUNS 22
#define VGEO_BINDING_COUNT 23

// Per-frame constants (a uniform buffer). The cull camera selects the cut and culls; the draw camera
// makes the picture. They differ only with --freeze-camera.
struct FrameData {
  mat4 viewProjection;   // draw camera
  vec4 frustum[6];       // cull camera's planes in world space: dot(xyz, p) + w >= 0 inside
  vec4 cullEye;          // xyz
  vec4 drawEye;          // xyz
  float projScale;       // viewport height / (2 tan(fovY / 2)): object size to pixels at unit distance
  float tau;             // allowed projected error, pixels
  float znear;
  uint mode;
  uint instanceCount;
  uint queueCapacity;    // items in the traversal queue
  uint drawCapacity;     // entries in the draw list
  uint iterationBudget;  // persistent traversal: leave after this many loop iterations (0: never)
  uint maxClusters;      // largest cluster count of a geometry (flat traversal)
  uint claimMode;        // persistent traversal: 0 claim past the frontier, 1 claim only reserved items
  uint triangleCull;     // 1: cull_triangles.comp lists the triangles to draw; 0: every listed cluster's
  uint triangleCapacity; // entries in the triangle list
  float viewportWidth;   // pixels
  float viewportHeight;
  uint patches;          // 1: leaf clusters whose chord error projects above tau are drawn as patches
  uint patchCapacity;    // entries in the patch list
  uint queueRoots;       // 1 (flat traversal): instance culling queues (instance, root) for each visible
                         // instance; 0: it tests the root's children and queues those
  uint sweepBudget;      // persistent traversal: cluster tests a frame may spend sweeping levels (0: none)
  uint firstClaimItems;  // persistent traversal: the last frame's counters.cullItems (0: unknown), sizes the first claim
  uint cullInTraversal;  // persistent traversal: its workers cull the instances first (worker w: instances w,
                         // w + workers, ...) instead of cull_instances.comp; the host starts
                         // counters.nodesPending at frame.instanceCount
  uint patchesPerInstance; // the patch draw: instances of this many patches (patch.vert), so that no run of
                           // lavapipe's tessellator outputs more vertices than its 16-bit indices address
  uint framePad[3];
};

// GPU counters of one frame, and the indirect arguments built from them. The counters the persistent
// traversal's workers hit all the time each have a 128-byte line of their own (atomics on one line are
// served one after another at the L2; the cut benchmark on an H100 was ~1% faster this way).
#define VGEO_COUNTER_LINE_PAD 31
struct Counters {
  uint queueWrite;       // items reserved in the traversal queue
  uint linePad0[VGEO_COUNTER_LINE_PAD];
  uint queueRead;        // items claimed by persistent workers
  uint linePad1[VGEO_COUNTER_LINE_PAD];
  uint drawCount;        // draw list entries requested (may exceed the capacity: see drawOverflow)
  uint linePad2[VGEO_COUNTER_LINE_PAD];
  uint nodesPending;     // node items queued and not yet finished: only they produce items, so at 0 the
                         // queue is final (persistent traversal termination)
  uint linePad3[VGEO_COUNTER_LINE_PAD];
  uint itemsDone;        // items processed (or dropped by overflow)
  uint queueOverflow;    // items that did not fit the queue
  uint drawOverflow;     // clusters that did not fit the draw list
  uint nodesVisited;     // BVH nodes and groups processed
  uint clustersTested;
  uint visibleInstances;
  uint triangles;        // triangles of the listed clusters
  uint levelStart;       // levels traversal: the window of the queue processed by one dispatch
  uint levelEnd;
  uint queueHighWater;   // largest queueWrite seen
  uint workgroupsExited; // persistent traversal: workers that left
  uint budgetExits;      // of those, left on the iteration budget (lavapipe)
  uint dispatch[4];      // indirect dispatch arguments (x, y, z): levels and flat traversal, triangle culling
  uint draw[4];          // VkDrawIndirectCommand
  uint trianglesDrawn;   // triangles that survived triangle culling (requested; see triangleOverflow)
  uint triangleOverflow; // triangles that did not fit the triangle list
  uint patchesDrawn;     // patches listed for the tessellated draw (requested; see patchOverflow)
  uint patchOverflow;    // patches that did not fit the patch list
  uint patchClusters;    // draw-list entries drawn as patches
  uint patchDraw[4];     // VkDrawIndirectCommand of the patch draw (one vertex a patch)
  uint sweepTests;       // cluster tests claimed for sweeps (may pass frame.sweepBudget: then not swept)
  uint sweptTests;       // of those, swept
  uint cullItems;        // queue items instance culling wrote: sizes the next frame's first claim
};

// Triangle list entry: draw-list entry << 7 | triangle within its cluster. Patch list entry: draw-list
// entry << 7 | cage face within its (leaf) cluster.
#define VGEO_TRIANGLE_BITS 7u
// Draw-list cluster word: set when the leaf cluster is drawn as patches (its chord error projects above tau).
#define VGEO_DRAW_PATCHES_BIT 0x80000000u
#define VGEO_MAX_DRAW_ENTRIES (1u << 25)

// Packing of Cluster.counts: vertex count (9 bits), triangle count (8), level (7), cage face count (8).
#ifdef __cplusplus
inline
#endif
uint packClusterCounts(uint vertexCount, uint triangleCount, uint level, uint cageFaceCount) {
  return vertexCount | (triangleCount << 9) | (level << 17) | (cageFaceCount << 24);
}
#ifdef __cplusplus
inline
#endif
uint clusterVertexCount(uint counts) { return counts & 0x1ffu; }
#ifdef __cplusplus
inline
#endif
uint clusterTriangleCount(uint counts) { return (counts >> 9) & 0xffu; }
#ifdef __cplusplus
inline
#endif
uint clusterLevel(uint counts) { return (counts >> 17) & 0x7fu; }
#ifdef __cplusplus
inline
#endif
uint clusterCageFaceCount(uint counts) { return counts >> 24; }

// Projected error in pixels of an (error, sphere) pair seen from `eye`: error * projScale / distance to
// the sphere, with projScale = viewport height / (2 tan(fovY / 2)). A camera within znear of the sphere
// sees an unbounded error (it needs the finest level there); zero error projects to zero. The same
// function decides the cut on the GPU and in the CPU reference, so the two agree up to rounding.
// Monotonic: a larger error in an enclosing sphere never projects smaller (docs/design.md, invariant 3).
#ifdef __cplusplus
inline float uintBitsToFloat(uint bits) {
  float f;
  static_assert(sizeof(f) == sizeof(bits), "float size");
  __builtin_memcpy(&f, &bits, 4);
  return f;
}
inline
#endif
float projectedError(vec4 sphere, float error, vec3 eye, float projScale, float znear) {
  if (error == 0.0f) return 0.0f;
  float d = length(vec3(sphere.x, sphere.y, sphere.z) - eye) - sphere.w;
  if (d <= znear) return uintBitsToFloat(0x7f800000u);
  return error * projScale / d;
}

// The cut rule (invariant 4) with its one exception: a leaf (no producer) has nothing finer below it, so
// it is drawn whenever its parent is too coarse, whatever its own error (its chord error against the limit
// surface); with self > tau the renderer draws its patches instead of its triangles (docs/design.md, leaves).
#ifdef __cplusplus
inline
#endif
bool inCut(float self, float parent, float tau, bool leaf) { return (self <= tau || leaf) && tau < parent; }

#ifdef __cplusplus
static_assert(sizeof(Cluster) == 64, "Cluster layout");
static_assert(sizeof(Group) == 32, "Group layout");
static_assert(sizeof(BvhNode) == 32, "BvhNode layout");
static_assert(sizeof(Geometry) == 64, "Geometry layout");
static_assert(sizeof(Instance) == 64, "Instance layout");
static_assert(sizeof(CageFace) == 16, "CageFace layout");
static_assert(sizeof(ClusterCone) == 32, "ClusterCone layout");
static_assert(sizeof(Patch) == 48, "Patch layout");
static_assert(sizeof(FrameData) == 64 + 96 + 32 + 96, "FrameData layout");
static_assert(sizeof(Counters) == 5 * 128, "Counters layout");
static_assert(offsetof(Counters, itemsDone) == 4 * 128, "Counters: the hot words on lines of their own");
}  // namespace shaderio
#endif

#endif
