// common.glsl: the bindings every renderer pass shares, and the tests of the cut (DESIGN.md, invariant 4)
// in world space. Included by the compute passes and the draw shaders.
#extension GL_GOOGLE_include_directive : require
#include "shaderio.h"

layout(set = 0, binding = 0) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = 1, std430) readonly buffer GeometryBuffer { Geometry geometries[]; };
layout(set = 0, binding = 2, std430) readonly buffer InstanceBuffer { Instance instances[]; };
layout(set = 0, binding = 3, std430) readonly buffer PositionBuffer { float positions[]; };
layout(set = 0, binding = 4, std430) readonly buffer NormalBuffer { uint normals[]; };
layout(set = 0, binding = 5, std430) readonly buffer ClusterBuffer { Cluster clusters[]; };
layout(set = 0, binding = 6, std430) readonly buffer ClusterVertexBuffer { uint clusterVertices[]; };
layout(set = 0, binding = 7, std430) readonly buffer ClusterTriangleBuffer { uint clusterTriangles[]; };
layout(set = 0, binding = 8, std430) readonly buffer GroupBuffer { Group groups[]; };
layout(set = 0, binding = 9, std430) readonly buffer NodeBuffer { BvhNode nodes[]; };
layout(set = 0, binding = 10, std430) coherent buffer CounterBuffer { Counters counters; };
// Traversal queue: item i is (instance, node or group | VGEO_ITEM_GROUP_BIT) in queue[2i], queue[2i+1];
// an unwritten slot holds VGEO_INVALID in its first word. Consumers reset slots after reading, so the
// queue is clean for the next frame.
layout(set = 0, binding = 11, std430) coherent buffer QueueBuffer { uint queue[]; };
// Draw list: entry i is (instance, cluster) in drawList[2i], drawList[2i+1].
layout(set = 0, binding = 12, std430) buffer DrawListBuffer { uint drawList[]; };
layout(set = 0, binding = 13, std430) readonly buffer ClusterConeBuffer { ClusterCone clusterCones[]; };
// Triangle list (cull_triangles.comp): entry i is (draw-list entry << VGEO_TRIANGLE_BITS | triangle).
layout(set = 0, binding = 14, std430) buffer TriangleListBuffer { uint triangleList[]; };

vec3 toWorld(Instance inst, vec3 p) {
  vec4 h = vec4(p, 1.0);
  return vec3(dot(inst.row0, h), dot(inst.row1, h), dot(inst.row2, h));
}

vec4 worldSphere(Instance inst, vec4 sphere) {
  return vec4(toWorld(inst, sphere.xyz), sphere.w * inst.maxScale);
}

// Outside when wholly behind one plane of the cull camera's frustum (conservative). Written without a
// loop: lavapipe counts every loop iteration against its per-invocation limit (GPU-NOTES 1).
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
