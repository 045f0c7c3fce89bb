#version 450
// patch.tesc: tessellation factors of one listed patch (a cage face of a leaf cluster drawn as patches).
// Each edge's factor comes from that edge alone: its two corners (leaf vertices, world space, taken in
// the order of their vertex ids), its chord error (the same value in both faces' records) and the cull
// eye, so the two faces of an edge compute the same bits and no crack opens (DESIGN.md, leaves). The
// error is projected from the point of the edge's segment nearest the eye: a close camera may face the
// middle of a long edge, far nearer than its corners. The chord error of a curve falls with the square
// of the segments it is cut into, so an edge needs ceil(sqrt(projected error / tau)) segments. A locked
// edge (a level-0 group border, or a flat neighbour) stays at 1: its other side may be drawn as
// triangles. Inner factors: the larger of the face's own need and its edges'.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(vertices = 1) out;
layout(location = 0) in uint vPatch[];     // the patch's index in the patch list (patch.vert)
layout(location = 0) patch out uvec4 pIds;  // face, instance, cluster, level-0 group

const float kMaxFactor = 64.0;

// Segments for an object-space chord error `error` seen from `distanceToEye`. The segment of an edge
// lies in its cluster's sphere, so it is never nearer than the sphere and an edge of a cluster drawn as
// triangles (projected self error <= tau) gets 1 (the 1.001 absorbs rounding).
float segments(float error, float distanceToEye) {
  if (error <= 0.0) return 1.0;
  if (distanceToEye <= frame.znear) return kMaxFactor;
  float projected = error * frame.projScale / distanceToEye;
  return clamp(ceil(sqrt(projected / (frame.tau * 1.001))), 1.0, kMaxFactor);
}

void main() {
  uint packed = patchList[vPatch[0]];
  uint entry = packed >> VGEO_TRIANGLE_BITS, local = packed & ((1u << VGEO_TRIANGLE_BITS) - 1u);
  uint instance = drawList[2u * entry], cluster = drawList[2u * entry + 1u] & ~VGEO_DRAW_PATCHES_BIT;
  Cluster c = clusters[cluster];
  uint face = c.cageFaceOffset + local;
  Instance inst = instances[instance];
  Patch p = patches[face];
  CageFace cf = cageFaces[face];
  vec3 corner[4];
  uint vertex[4];
  for (uint k = 0u; k < 4u; k++) {
    vertex[k] = cageFaceVertices[cf.firstVertex + k];
    corner[k] = toWorld(inst, vertexPosition(vertex[k]));
  }
  float edge[4];
  for (uint k = 0u; k < 4u; k++) {
    uint next = (k + 1u) % 4u;
    bool forward = vertex[k] < vertex[next];
    vec3 a = forward ? corner[k] : corner[next], b = forward ? corner[next] : corner[k];
    vec3 ab = b - a;
    float t = clamp(dot(frame.cullEye.xyz - a, ab) / max(dot(ab, ab), 1e-30), 0.0, 1.0);
    edge[k] = patchEdgeLocked(p.info, k) ? 1.0 : segments(p.edgeError[k] * inst.maxScale, distance(a + t * ab, frame.cullEye.xyz));
  }
  // Inside: from the sphere around the corners, which holds the face's triangles.
  vec3 center = 0.25 * (corner[0] + corner[1] + corner[2] + corner[3]);
  float radius = 0.0;
  for (uint k = 0u; k < 4u; k++) radius = max(radius, distance(center, corner[k]));
  float inner = segments(p.faceError * inst.maxScale, distance(center, frame.cullEye.xyz) - radius);
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
