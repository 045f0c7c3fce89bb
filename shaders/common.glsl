// common.glsl: the bindings every renderer pass shares, and the tests of the cut (docs/design.md, invariant 4)
// in world space. Included by the compute passes and the draw shaders.
#extension GL_GOOGLE_include_directive : require
#ifdef VGEO_SCENE_BY_ADDRESS
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#endif
#include "shaderio.h"

// The frame's constants in a storage buffer, not a uniform buffer: lavapipe (Mesa 22.3) inlines uniform
// values that steer branches and compiles the shader again at every dispatch, keeping each copy
// (docs/gpu-notes.md, 23). FrameData's std140 and std430 layouts are the same (no scalar arrays).
layout(set = 0, binding = VGEO_BINDING_FRAME, std430) readonly restrict buffer FrameBlock { FrameData frame; };
// Which pass of the frame this is (VGEO_PASS_*: two with occlusion culling, shaderio_frame.h).
layout(push_constant) uniform PassBlock { PassConstants passConstants; };

// The scene's arrays (shaderio_frame.h, VGEO_SCENE_ARRAYS): each at a binding of its own, or in the
// VGEO_SCENE_BY_ADDRESS variant (scenes with an array past maxStorageBufferRange) by device address
// (SceneArrays), each name then a macro that reads as the array (positions[i]). Bindings are the faster
// on lavapipe (bench/README.md, "What the code's choices rest on").
#ifdef VGEO_SCENE_BY_ADDRESS
layout(set = 0, binding = VGEO_BINDING_SCENE) uniform SceneBlock { SceneArrays sceneArrays; };
#define VGEO_SCENE_ARRAY_TYPE(n, array, T, alignment, owner) \
  layout(buffer_reference, std430, buffer_reference_align = alignment) readonly buffer array##Array { T v[]; };
VGEO_SCENE_ARRAYS(VGEO_SCENE_ARRAY_TYPE)
// GLSL cannot make a macro from a macro: one line an array (a missing one fails the variant's build).
#define VGEO_BY_ADDRESS(array) array##Array(sceneArrays.array).v
#define geometries VGEO_BY_ADDRESS(geometries)
#define instances VGEO_BY_ADDRESS(instances)
#define positions VGEO_BY_ADDRESS(positions)
#define normals VGEO_BY_ADDRESS(normals)
#define clusters VGEO_BY_ADDRESS(clusters)
#define clusterVertices VGEO_BY_ADDRESS(clusterVertices)
#define clusterTriangles VGEO_BY_ADDRESS(clusterTriangles)
#define groups VGEO_BY_ADDRESS(groups)
#define nodes VGEO_BY_ADDRESS(nodes)
#define clusterCones VGEO_BY_ADDRESS(clusterCones)
#define controlPoints VGEO_BY_ADDRESS(controlPoints)
#define cageFaces VGEO_BY_ADDRESS(cageFaces)
#define cageFaceVertices VGEO_BY_ADDRESS(cageFaceVertices)
#define patches VGEO_BY_ADDRESS(patches)
#define patchPoints VGEO_BY_ADDRESS(patchPoints)
#define levelClusterRuns VGEO_BY_ADDRESS(levelClusterRuns)
#define instanceRoots VGEO_BY_ADDRESS(instanceRoots)
#else
#define VGEO_SCENE_ARRAY_BINDING(n, array, T, alignment, owner) \
  layout(set = 0, binding = n, std430) readonly buffer array##Block { T array[]; };
VGEO_SCENE_ARRAYS(VGEO_SCENE_ARRAY_BINDING)
#endif

layout(set = 0, binding = VGEO_BINDING_COUNTERS, std430) coherent buffer CounterBuffer { Counters counters; };
// Traversal queue: item i is (instance, node or group | VGEO_ITEM_GROUP_BIT) in queue[2i], queue[2i+1];
// an unwritten slot holds VGEO_INVALID in both words. Consumers reset slots after reading, so the
// queue is clean for the next frame.
layout(set = 0, binding = VGEO_BINDING_QUEUE, std430) coherent buffer QueueBuffer { uint queue[]; };
// Draw list: entry i is (instance, cluster) in drawList[2i], drawList[2i+1].
layout(set = 0, binding = VGEO_BINDING_DRAW_LIST, std430) buffer DrawListBuffer { uint drawList[]; };
// Triangle list (cull_triangles.comp): entry i is (draw-list entry << VGEO_TRIANGLE_BITS | triangle).
layout(set = 0, binding = VGEO_BINDING_TRIANGLE_LIST, std430) buffer TriangleListBuffer { uint triangleList[]; };
// Patch list (cull_patches.comp): entry i is patchList[2i] = (draw-list entry << VGEO_TRIANGLE_BITS | cage
// face in its cluster) and patchList[2i + 1] its grid, for a compute-rasterized patch (shaderio_frame.h).
layout(set = 0, binding = VGEO_BINDING_PATCH_LIST, std430) buffer PatchListBuffer { uint patchList[]; };
// Patch grid (raster_patches.comp): the compute-rasterized patches' points, for the resolve.
layout(set = 0, binding = VGEO_BINDING_PATCH_GRID, std430) buffer PatchGridBuffer { vec4 patchGrid[]; };
// Patch draws (raster_patches.comp): for slot i of the patch list's hardware part, with patches in
// compute, the VkDrawIndirectCommand of its grid's triangles (patch_grid.vert, first instance = slot).
layout(set = 0, binding = VGEO_BINDING_PATCH_DRAWS, std430) buffer PatchDrawBuffer { uvec4 patchDraws[]; };
// Patch-entry list (cull_triangles.comp): the draw-list entries of patch-drawn clusters, for cull_patches.comp.
layout(set = 0, binding = VGEO_BINDING_PATCH_ENTRIES, std430) buffer PatchEntryBuffer { uint patchEntries[]; };

// A normal to world space by the cofactor matrix of the instance's linear part (det(M) M^-T): right under
// non-uniform scale, and under a mirror (det < 0) it turns with the winding, so the fragment shader's
// "flip the normal of a back face" still yields the outward normal of the mirrored surface.
vec3 normalToWorld(Instance inst, vec3 n) {
  vec3 r0 = inst.row0.xyz, r1 = inst.row1.xyz, r2 = inst.row2.xyz;
  return normalize(vec3(dot(cross(r1, r2), n), dot(cross(r2, r0), n), dot(cross(r0, r1), n)));
}

vec3 vertexPosition(uint vertex) { return vec3(positions[3u * vertex], positions[3u * vertex + 1u], positions[3u * vertex + 2u]); }

// Clip position of an object-space point: the triangle and patch draws compute shared corners with this
// one expression, and `precise` forbids fused multiply-adds that a compiler could place differently in
// the two shaders, so both give the same bits. (`invariant gl_Position` would say the same, but Debian
// 12's glslang decorates a struct member with it, which the validation layer reports.)
vec4 clipPosition(Instance inst, vec3 p) {
  precise vec3 world = instanceToWorld(inst, p);
  precise vec4 clip = frame.viewProjection * vec4(world, 1.0);
  return clip;
}

// Outside when wholly behind one plane of the cull camera's frustum (conservative). Written without a
// loop: lavapipe counts every loop iteration against its per-invocation limit (docs/gpu-notes.md, 1).
bool sphereInFrustum(vec4 s) {
  return dot(frame.frustum[0].xyz, s.xyz) + frame.frustum[0].w >= -s.w && dot(frame.frustum[1].xyz, s.xyz) + frame.frustum[1].w >= -s.w &&
         dot(frame.frustum[2].xyz, s.xyz) + frame.frustum[2].w >= -s.w && dot(frame.frustum[3].xyz, s.xyz) + frame.frustum[3].w >= -s.w &&
         dot(frame.frustum[4].xyz, s.xyz) + frame.frustum[4].w >= -s.w && dot(frame.frustum[5].xyz, s.xyz) + frame.frustum[5].w >= -s.w;
}

float projectedErrorWorld(Instance inst, vec4 sphere, float error) {
  return projectedError(worldSphere(inst, sphere), error * inst.maxScale, frame.cullEye.xyz, frame.projScale, frame.znear);
}

// Slack for the conservative tests of the hierarchy: a node or group is pruned only when it is clearly
// outside or clearly fine enough, so float rounding never prunes what the cluster test would draw.
const float kPruneSlack = 1.0001;
