#version 450
// patch.tesc: tessellation factors of one listed patch (a cage face of a leaf cluster drawn as patches).
// Each edge's factor comes from that edge alone: its two corners (leaf vertices, world space), its
// chord error (the same value in both faces' records) and the cull eye, so the two faces of an edge
// always agree and no crack opens (DESIGN.md, leaves). The chord error of a curve falls with the square
// of the segments it is cut into, so an edge needs ceil(sqrt(projected error / tau)) segments. A locked
// edge (a level-0 group border, or a flat neighbour) stays at 1: its other side may be drawn as
// triangles. Inner factors: the larger of the face's own need and its edges'.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(vertices = 1) out;
layout(location = 0) patch out uvec4 pIds;  // face, instance, cluster, level-0 group

const float kMaxFactor = 64.0;

// Segments for an object-space chord error `error` seen from the nearest of `a`, `b` (world space).
// The nearest corner is never nearer than the cluster's sphere, so an edge of a cluster drawn as
// triangles (projected self error <= tau) gets 1 (the 1.001 absorbs rounding).
float segments(float error, float distanceToEye) {
  if (error <= 0.0) return 1.0;
  if (distanceToEye <= frame.znear) return kMaxFactor;
  float projected = error * frame.projScale / distanceToEye;
  return clamp(ceil(sqrt(projected / (frame.tau * 1.001))), 1.0, kMaxFactor);
}

void main() {
  uint packed = patchList[gl_PrimitiveID];
  uint entry = packed >> VGEO_TRIANGLE_BITS, local = packed & ((1u << VGEO_TRIANGLE_BITS) - 1u);
  uint instance = drawList[2u * entry], cluster = drawList[2u * entry + 1u] & ~VGEO_DRAW_PATCHES_BIT;
  Cluster c = clusters[cluster];
  uint face = c.cageFaceOffset + local;
  Instance inst = instances[instance];
  Patch p = patches[face];
  CageFace cf = cageFaces[face];
  float eyeDistance[4];
  for (uint k = 0u; k < 4u; k++)
    eyeDistance[k] = distance(toWorld(inst, vertexPosition(cageFaceVertices[cf.firstVertex + k])), frame.cullEye.xyz);
  float edge[4];
  for (uint k = 0u; k < 4u; k++)
    edge[k] = patchEdgeLocked(p.info, k) ? 1.0 : segments(p.edgeError[k] * inst.maxScale, min(eyeDistance[k], eyeDistance[(k + 1u) % 4u]));
  float inner = segments(p.faceError * inst.maxScale, min(min(eyeDistance[0], eyeDistance[1]), min(eyeDistance[2], eyeDistance[3])));
  // Edge k runs from corner k to k + 1: 0 is v = 0, 1 is u = 1, 2 is v = 1, 3 is u = 0 (outer levels
  // are ordered u = 0, v = 0, u = 1, v = 1).
  gl_TessLevelOuter[0] = edge[3];
  gl_TessLevelOuter[1] = edge[0];
  gl_TessLevelOuter[2] = edge[1];
  gl_TessLevelOuter[3] = edge[2];
  gl_TessLevelInner[0] = max(inner, max(edge[0], edge[2]));
  gl_TessLevelInner[1] = max(inner, max(edge[1], edge[3]));
  pIds = uvec4(face, instance, cluster, c.group);
}
