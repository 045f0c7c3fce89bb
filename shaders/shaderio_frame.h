// shaderio_frame.h: the renderer's side of the GPU interface, declared once for C++ and GLSL: the
// descriptor bindings, the per-frame constants, the frame's counters, the encodings of its working lists
// (queue items, draw, triangle and patch lists, the worker profile) and the debug modes.
#ifndef VGEO_SHADERIO_FRAME_H
#define VGEO_SHADERIO_FRAME_H

#include "shaderio_scene.h"

VGEO_NAMESPACE_BEGIN

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
#define VGEO_MODE_PYRAMID 12  // the depth pyramid occlusion culling tests against (FrameData.pyramidViewLevel)
#define VGEO_MODE_COUNT 13
// The clear colour (linear RGB): the render pass's, and the resolve's where nothing was drawn.
#define VGEO_BACKGROUND_R 0.02f
#define VGEO_BACKGROUND_G 0.025f
#define VGEO_BACKGROUND_B 0.035f

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
// Specialization constant of resolve.comp: its view (VGEO_MODE_*), one pipeline a view.
#define VGEO_SPEC_VIEW_MODE 1
// Specialization constant of resolve.comp: whether the frame's visibility buffer holds patches.
#define VGEO_SPEC_RESOLVE_PATCHES 2
// Specialization constant of resolve.comp: whether the render pass had no attachments (every pixel is the
// resolve's: the hardware triangles are in the visibility buffer too).
#define VGEO_SPEC_RESOLVE_EVERY_PIXEL 3
// Specialization constant of instance culling and the traversals (occlusion.glsl): false builds them
// without the occlusion tests, for one-pass frames. lavapipe runs the code of a test it skips anyway,
// lane-masked (its atomics a lane at a time): with it, its instance culling and traversal took 1.3-2x.
#define VGEO_SPEC_OCCLUSION 4
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
// instance (workgroups of VGEO_CULL_SERIAL_WORKGROUP) in larger ones, where thousands of workgroups
// reserving queue slots on one counter cost more (bench/README.md, cut selection).
#define VGEO_CULL_INSTANCE_LANES 64
#define VGEO_CULL_SPREAD_WORKGROUP 128
#define VGEO_CULL_SERIAL_WORKGROUP 64
#define VGEO_CULL_SPREAD_INSTANCES 4096

// The renderer's one descriptor set, named once for the host (gpu_renderer.cpp fills it) and the
// shaders (common.glsl and the passes declare their buffers with these). 0 is the frame's constants; the
// scene's arrays (VGEO_SCENE_ARRAYS below) have bindings of their own; the rest are the frame's working
// buffers.
#define VGEO_BINDING_FRAME 0

// The scene's arrays, declared once: X(binding, array, GLSL element type, alignment in bytes, owner).
// The list makes SceneArrays (below), common.glsl's declarations in both shader variants, and the
// renderer's upload table, whose `owner` is `d` for the .vgeo's merged arrays (VgeoData, in the order of
// the file's sections) or `scene` for the two the renderer makes (RenderScene, scene.h): levelClusterRuns,
// a BVH node's run of clusters (first, count) when it is a level's subtree root, what a sweep tests
// instead of walking it; and instanceRoots, an instance's geometry's BVH root as uvec2
// (childCountAndFlags, childOffset) of its BvhNode: instance culling tests the root's children from it
// and the instance record, two loads side by side instead of instance -> geometry -> root in a row.
// Each array is read at its binding, or, in the shaders' VGEO_SCENE_BY_ADDRESS variant (for scenes with
// an array past maxStorageBufferRange, 128 MiB on lavapipe), by its device address in SceneArrays.
#define VGEO_SCENE_ARRAYS(X)               \
  X(1, geometries, Geometry, 16, d)        \
  X(2, instances, Instance, 16, d)         \
  X(3, positions, float, 4, d)             \
  X(4, normals, uint, 4, d)                \
  X(5, clusters, Cluster, 16, d)           \
  X(6, clusterVertices, uint, 4, d)        \
  X(7, clusterTriangles, uint, 4, d)       \
  X(8, groups, Group, 16, d)               \
  X(9, nodes, BvhNode, 16, d)              \
  X(13, clusterCones, ClusterCone, 16, d)  \
  X(15, controlPoints, float, 4, d)        \
  X(16, cageFaces, CageFace, 16, d)        \
  X(17, cageFaceVertices, uint, 4, d)      \
  X(18, patches, Patch, 16, d)             \
  X(19, patchPoints, uint, 4, d)           \
  X(22, levelClusterRuns, uvec2, 8, scene) \
  X(23, instanceRoots, uvec2, 8, scene)

#define VGEO_BINDING_COUNTERS 10
#define VGEO_BINDING_QUEUE 11
#define VGEO_BINDING_DRAW_LIST 12
#define VGEO_BINDING_TRIANGLE_LIST 14
#define VGEO_BINDING_PATCH_LIST 20
#define VGEO_BINDING_WORKER_PROFILE 21
#define VGEO_BINDING_VISIBILITY 24
#define VGEO_BINDING_OVERDRAW 25
#define VGEO_BINDING_COLOR_IMAGE 26         // the frame's colour target as a storage image (resolve.comp writes it)
#define VGEO_BINDING_DEPTH_IMAGE 27         // the hardware draws' depth, sampled (resolve.comp compares with it)
#define VGEO_BINDING_PATCH_ENTRIES 28       // draw-list entries of patch-drawn clusters (cull_triangles.comp)
#define VGEO_BINDING_PATCH_GRID 29          // the compute-rasterized patches' grid points (raster_patches.comp)
#define VGEO_BINDING_PATCH_DRAWS 30         // a VkDrawIndirectCommand a hardware patch slot (patch_grid.vert)
#define VGEO_BINDING_SCENE 31               // SceneArrays (a uniform buffer)
#define VGEO_BINDING_DEPTH_PYRAMID 32       // the depth pyramid (build_depth_pyramid.comp)
#define VGEO_BINDING_DEFERRED_INSTANCES 33  // the instances the early pass left to the late one
#define VGEO_BINDING_DEFERRED_ITEMS 34      // queue items the early pass left to the late one
#define VGEO_BINDING_COUNT 35

// Two-pass occlusion culling (docs/design.md, "Occlusion culling"). Every pass of a frame knows which of
// the two it belongs to from its push constants (PassConstants): VGEO_PASS_ONLY in a frame without
// occlusion culling. VGEO_PASS_EARLY selects as usual but tests instances, nodes, groups and clusters
// against the depth pyramid of the last frame (with that frame's camera): what it hides is not drawn but
// deferred (instances listed, the rest listed as queue items); the early pass draws the rest. Then the
// pyramid is built from what it drew, and VGEO_PASS_LATE takes up the deferred instances and items, tests
// them and everything below them against it (now with this frame's camera), and draws what it does not
// hide. Patches are culled and drawn in the late pass only (the early pass lists their entries).
#define VGEO_PASS_ONLY 0u
#define VGEO_PASS_EARLY 1u
#define VGEO_PASS_LATE 2u
// The depth pyramid: level 0 is the picture's nearest depth a pixel (reversed depth: larger is nearer;
// 0 where nothing was drawn), level k holds for each texel the farthest of its 2x2 texels below, over a
// (width >> k) x (height >> k) grid rounded up; levels one after another in one float buffer
// (FrameData.pyramidOffsets).
#define VGEO_PYRAMID_MAX_LEVELS 16
// FrameData.pyramidSources: where the early pass left its depth.
#define VGEO_PYRAMID_FROM_VISIBILITY 1u   // the visibility buffer (compute rasterizers, bare render pass)
#define VGEO_PYRAMID_FROM_DEPTH_IMAGE 2u  // the render pass's depth target
// FrameData.occlusion
#define VGEO_OCCLUSION_OFF 0u
#define VGEO_OCCLUSION_ON 1u      // two passes, the pyramid built between them
#define VGEO_OCCLUSION_FROZEN 2u  // two passes, both against the pyramid of the camera the cut froze at

struct PassConstants {
  uint pass;  // VGEO_PASS_*
};

// The scene's arrays' device addresses (VGEO_BINDING_SCENE, a uniform block), each as two words (low,
// high), in the order of VGEO_SCENE_ARRAYS; pad makes the count even (std140 rounds to 16 bytes).
#define VGEO_SCENE_ARRAY_ADDRESS(binding, array, type, align, owner) uvec2 array;
struct SceneArrays {
  VGEO_SCENE_ARRAYS(VGEO_SCENE_ARRAY_ADDRESS)
  uvec2 pad;
};

// FrameData.claimMode: how the persistent traversal's workers claim queue slots (traverse_persistent.comp).
#define VGEO_CLAIM_PAST_FRONTIER 0u  // GPUs: a batch of slots, written or not; a lane waits on its slot
#define VGEO_CLAIM_WRITTEN 1u        // lavapipe: only slots already written; nobody waits

// Per-frame constants (a read-only storage buffer, std140-compatible). The cull camera selects the cut and culls; the
// draw camera makes the picture. They differ only with --freeze-camera.
struct FrameData {
  mat4 viewProjection;  // draw camera
  vec4 frustum[6];      // cull camera's planes in world space: dot(xyz, p) + w >= 0 inside
  vec4 cullEye;         // xyz
  vec4 drawEye;         // xyz
  float projScale;      // viewport height / (2 tan(fovY / 2)): object size to pixels at unit distance
  float tau;            // allowed projected error, pixels
  float znear;
  uint mode;
  uint instanceCount;
  uint queueCapacity;     // items in the traversal queue
  uint drawCapacity;      // entries in the draw list
  uint iterationBudget;   // persistent traversal: leave after this many loop iterations (0: never)
  uint maxClusters;       // largest cluster count of a geometry (flat traversal)
  uint claimMode;         // persistent traversal: VGEO_CLAIM_*
  uint triangleCull;      // 1: cull_triangles.comp lists the triangles to draw; 0: every listed cluster's
  uint triangleCapacity;  // entries in the triangle list
  float viewportWidth;    // pixels
  float viewportHeight;
  uint drawPatches;    // 1: leaf clusters whose chord error projects above tau are drawn as patches
  uint patchCapacity;  // entries in the patch list
  uint queueRoots;     // 1 (flat traversal): instance culling queues (instance, root) for each visible
                       // instance; 0: it tests the root's children and queues those
  uint sweepBudget;    // persistent traversal: cluster tests a frame may spend sweeping levels (0: none)
  uint
      firstClaimItems;  // persistent traversal: the last frame's counters.cullItems (0: unknown), sizes the first claim
  uint cullInTraversal;     // persistent traversal: its workers cull the instances first (worker w: instances w,
                            // w + workers, ...) instead of cull_instances.comp; the host starts
                            // counters.nodesPending at frame.instanceCount
  uint patchesPerInstance;  // the patch draw: instances of this many patches (patch.vert), so that no run of
                            // lavapipe's tessellator outputs more vertices than its 16-bit indices address
  uint softwareRaster;      // VGEO_RASTER_*: which listed triangles raster_software.comp draws
  uint softwarePatches;     // 1: patch culling bins patches to raster_patches.comp too (by softwareRaster's rule)
  uint patchGridCapacity;   // points in the patch grid (VGEO_BINDING_PATCH_GRID)
  uint packedCullBelow;     // draw lists whose clusters average fewer triangles are culled by
                            // cull_small_clusters.comp (0: never)
  uint occlusion;           // VGEO_OCCLUSION_*
  uint pyramidSources;      // VGEO_PYRAMID_FROM_*
  uint earlyOcclusion;      // 1: the early pass has a pyramid to test against (not the first frame)
  // The camera the depth pyramid was drawn from, as each pass sees it ([0] early: the last frame's, [1]
  // late: this frame's cull camera, or both the frozen one's): world to view space (looking down -z), the
  // projection's scale along x and y (clip xy = scale * view xy) and its near plane.
  mat4 pyramidViews[2];
  uvec4 pyramidOffsets[VGEO_PYRAMID_MAX_LEVELS / 4];  // first float of each level of the depth pyramid
  vec4 pyramidProjections;                            // early x, y, late x, y
  vec2 pyramidZnear;                                  // early, late
  uint pyramidLevels;
  uint pyramidTileLevels;          // build_depth_pyramid.comp: the levels a workgroup's tile reduces to (1 to 5)
  uint cullInstancesPerWorkgroup;  // cull_instances.comp's variant this frame (begin_late_pass.comp sizes
                                   // the late pass's dispatch over the deferred instances by it)
  uint persistentWorkgroups;       // the persistent traversal's dispatch (begin_late_pass.comp repeats it)
  uint lodLevels;                  // the lod view's scale: the most levels a geometry of the scene has
  uint bgraTarget;                 // 1: the colour target holds B, G, R, A (the viewer copies it to a BGRA window)
  uint pyramidViewLevel;           // VGEO_MODE_PYRAMID: the level shown (1 to pyramidLevels - 1)
  uint framePad0;
  uint framePad1;
  uint framePad2;
  vec4 light;  // xyz: the direction the light comes from, w 1; w 0: the default light
};

// The software rasterizer (raster_software.comp) takes the triangles triangle culling bins to it:
// VGEO_RASTER_SMALL those whose screen box spans at most VGEO_SOFTWARE_RASTER_MAX_PIXELS pixels each way
// (thread-per-triangle setup beats the hardware's for triangles of a few pixels; larger ones keep the
// hardware's parallel coverage), VGEO_RASTER_ALL every triangle it can take (in front of the near plane and
// inside its guard band, with a box of at most VGEO_SOFTWARE_RASTER_MAX_AREA pixels: one invocation
// walks the box, and lavapipe ends a loop past 65,535 iterations, docs/gpu-notes.md 1; tests compare the
// two paths with it), VGEO_RASTER_NONE none.
#define VGEO_RASTER_NONE 0u
#define VGEO_RASTER_SMALL 1u
#define VGEO_RASTER_ALL 2u
#define VGEO_SOFTWARE_RASTER_MAX_PIXELS 8.0f
#define VGEO_SOFTWARE_RASTER_MAX_AREA 32768.0f
// Corners snap to 1/VGEO_SUBPIXEL_SCALE pixel, as the hardware's 8 subpixel bits do, and must stay within
// VGEO_RASTER_GUARD_BAND pixels of the viewport for the software path.
#define VGEO_SUBPIXEL_SCALE 256.0f
#define VGEO_RASTER_GUARD_BAND 16384.0f
// The visibility buffer (VGEO_BINDING_VISIBILITY): one 64-bit word a pixel, the depth's float bits
// (reversed depth in [0, 1]: larger is nearer, and below 2^30) above a VGEO_VISIBILITY_ID_BITS-bit id, so
// that atomicMax keeps the nearest; 0 is empty. The id of a listed triangle is its triangle-list word
// (draw-list entry << VGEO_TRIANGLE_BITS | triangle); that of a patch's micro-triangle (raster_patches.comp)
// is VGEO_VISIBILITY_PATCH_BIT | patch-list slot << VGEO_PATCH_TRIANGLE_BITS | triangle of its grid. The
// overdraw buffer (VGEO_BINDING_OVERDRAW) counts the compute rasterizers' samples a pixel in --mode overdraw.
#define VGEO_VISIBILITY_ID_BITS 34
#define VGEO_VISIBILITY_PATCH_BIT (uint64_t(1) << 33)
#define VGEO_PATCH_TRIANGLE_BITS 13u       // 2 x 64 x 64 triangles at most (patch_factors.glsl, kMaxFactor)
#define VGEO_MAX_PATCH_ENTRIES (1u << 20)  // patch-list slots the id can name
// The compute rasterizer takes a patch (raster_patches.comp) in front of the near plane, within the guard
// band, and, with VGEO_RASTER_SMALL, whose grid cells span at most this many pixels (its bounding
// sphere's projected diameter over its smaller inner factor).
#define VGEO_SOFTWARE_PATCH_MAX_CELL_PIXELS 64.0f
// Grid cells a workgroup of raster_patches.comp evaluates and rasterizes at once (a tile of the patch:
// (n + 1)^2 points in shared memory, 2 n^2 triangles a thread each).
#define VGEO_PATCH_TILE 4u

// Triangle culling of draw lists whose clusters average fewer than frame.packedCullBelow triangles goes
// through VGEO_PACKED_CULL_ENTRIES entries a workgroup (cull_small_clusters.comp).
#define VGEO_PACKED_CULL_ENTRIES 64u

// GPU counters of one frame, and the indirect arguments built from them. The counters the persistent
// traversal's workers hit all the time each have a 128-byte line of their own (atomics on one line are
// served one after another at the L2).
#define VGEO_COUNTER_LINE_PAD 31
struct Counters {
  uint queueWrite;  // items reserved in the traversal queue
  uint linePad0[VGEO_COUNTER_LINE_PAD];
  uint queueRead;  // items claimed by persistent workers
  uint linePad1[VGEO_COUNTER_LINE_PAD];
  uint drawCount;  // draw list entries requested (may exceed the capacity: see drawOverflow)
  // Two passes (begin_late_pass.glsl): the late pass's first draw-list entry (the early pass's listed
  // clusters). Read by every workgroup of triangle culling: not on a line that its atomics hit.
  uint drawBase;
  uint linePad2[VGEO_COUNTER_LINE_PAD - 1];
  uint nodesPending;  // node items queued and not yet finished: only they produce items, so at 0 the
                      // queue is final (persistent traversal termination)
  uint linePad3[VGEO_COUNTER_LINE_PAD];
  uint itemsDone;      // items processed (or dropped by overflow)
  uint queueOverflow;  // items that did not fit the queue
  uint drawOverflow;   // clusters that did not fit the draw list
  uint nodesVisited;   // BVH nodes and groups processed
  uint clustersTested;
  uint visibleInstances;
  uint triangles;   // triangles of the listed clusters
  uint levelStart;  // levels traversal: the window of the queue processed by one dispatch
  uint levelEnd;
  uint queueHighWater;         // largest queueWrite seen
  uint workgroupsExited;       // persistent traversal: workers that left
  uint budgetExits;            // of those, left on the iteration budget (lavapipe)
  uint dispatch[4];            // indirect dispatch arguments (x, y, z): levels and flat traversal, triangle culling
  uint packedCullDispatch[4];  // the dispatch of cull_small_clusters.comp (0 workgroups when the frame takes the other)
  uint draw[4];                // VkDrawIndirectCommand
  uint trianglesDrawn;         // triangles that survived triangle culling (requested; see triangleOverflow)
  uint triangleOverflow;       // triangles that did not fit the triangle list
  uint patchesDrawn;           // patches listed for the tessellated draw (requested; see patchOverflow)
  uint patchOverflow;          // patches that did not fit the patch list
  uint patchClusters;          // draw-list entries drawn as patches
  uint patchDraw[4];           // VkDrawIndirectCommand of the patch draw (one vertex a patch)
  uint sweepTests;             // cluster tests claimed for sweeps (may pass frame.sweepBudget: then not swept)
  uint sweptTests;             // of those, swept
  uint cullItems;              // queue items instance culling wrote: sizes the next frame's first claim
  uint hardwareTriangles;      // of trianglesDrawn, those for the hardware draw, listed from the triangle list's start
  uint softwareTriangles;      // of trianglesDrawn, those for the software rasterizer, listed from its end
  uint rasterDispatch[4];      // indirect dispatch of raster_software.comp
  uint patchEntries;           // draw-list entries drawn as patches, listed for cull_patches.comp
  uint patchCullDispatch[4];   // its indirect dispatch
  uint hardwarePatches;        // of patchesDrawn, those for the tessellated draw, listed from the patch list's start
  uint softwarePatches;        // of patchesDrawn, those for raster_patches.comp, listed from its end
  uint patchRasterDispatch[4];  // indirect dispatch of raster_patches.comp, a workgroup a patch
  uint softwarePatchTriangles;  // triangles of the grids raster_patches.comp drew
  uint patchGridPoints;         // grid points patch culling asked for (past patchGridCapacity: tessellator)
  // Two passes (begin_late_pass.glsl): the late pass lists its clusters after the early pass's (drawBase)
  // and its queue items after them too; what the host reads as the frame's totals is summed from these.
  uint queueBase;                 // the pass's first queue slot (the flat traversal's visible instances)
  uint earlyVisibleInstances;     // visibleInstances of the early pass
  uint earlySoftwareTriangles;    // softwareTriangles of the early pass
  uint earlyBudgetExits;          // budgetExits of the early pass
  uint earlyPackedCull;           // packedCullDispatch[0] of the early pass
  uint deferredItems;             // early pass: queue items left to the late pass (past the queue's capacity:
                                  // overflow, counted in queueOverflow)
  uint deferredInstances;         // early pass: instances left to the late pass (listed)
  uint lateCullDispatch[4];       // the late pass's instance culling over them (begin_late_pass.comp)
  uint lateTraversalDispatch[4];  // the late pass's persistent traversal: no workers when nothing was deferred
  uint occludedInstances;         // late pass: instances hidden by the pyramid
  uint occludedNodes;             // late pass: BVH nodes and groups hidden by it
  uint occludedClusters;          // late pass: clusters of the cut hidden by it
  uint pyramidTilesDone;          // build_depth_pyramid.comp: its workgroups that finished their tile
};

// Triangle list entry: draw-list entry << 7 | triangle within its cluster. Patch list entry: two words,
// draw-list entry << 7 | cage face within its (leaf) cluster, then for a patch of the compute rasterizer
// its grid: the offset of its first point in the patch grid (VGEO_PATCH_GRID_OFFSET_BITS) and its
// inner factors less one, 6 bits each (along u, then v). The patch grid holds a point a vec4: the
// object-space position, and the octahedral normal (as the normals section's) in w's bits; point (i, j)
// of a grid of (nu, nv) cells at offset + j (nu + 1) + i.
#define VGEO_TRIANGLE_BITS 7u
#define VGEO_PATCH_GRID_OFFSET_BITS 20u
// Draw-list cluster word: set when the leaf cluster is drawn as patches (its chord error projects above tau).
#define VGEO_DRAW_PATCHES_BIT 0x80000000u
#define VGEO_MAX_DRAW_ENTRIES (1u << 25)

#ifdef __cplusplus
static_assert(sizeof(FrameData) == 576, "FrameData layout (std140)");
static_assert(offsetof(FrameData, pyramidViews) % 16 == 0 && offsetof(FrameData, pyramidProjections) % 16 == 0 &&
                  offsetof(FrameData, light) % 16 == 0,
              "FrameData: std140 alignment");
static_assert(sizeof(Counters) == 5 * 128 + 96 + 72, "Counters layout");
// The scene arrays' bindings: each below VGEO_BINDING_COUNT and none taken twice (the renderer's
// descriptor table also refuses a binding without a buffer).
#define VGEO_SCENE_ARRAY_BIT(binding, array, type, align, owner) | (uint64_t(1) << (binding))
#define VGEO_SCENE_ARRAY_ONE(binding, array, type, align, owner) +1
constexpr uint32_t kSceneArrayCount = 0 VGEO_SCENE_ARRAYS(VGEO_SCENE_ARRAY_ONE);
constexpr uint64_t kSceneArrayBindings = 0 VGEO_SCENE_ARRAYS(VGEO_SCENE_ARRAY_BIT);
static_assert(std::popcount(kSceneArrayBindings) == int(kSceneArrayCount) &&
                  kSceneArrayBindings >> VGEO_BINDING_COUNT == 0,
              "VGEO_SCENE_ARRAYS: bindings distinct and below VGEO_BINDING_COUNT");
static_assert(kSceneArrayCount % 2 == 1 && sizeof(SceneArrays) == (kSceneArrayCount + 1) * 8,
              "SceneArrays: with its pad an even count of addresses (std140)");
static_assert(offsetof(Counters, itemsDone) == 4 * 128, "Counters: the hot words on lines of their own");
#endif

VGEO_NAMESPACE_END

#endif
