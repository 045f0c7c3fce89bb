// patch_factors.glsl: tessellation factors of a listed cage face (patch.tesc draws with them;
// cull_triangles.comp draws a face whose factors are all 1 as its leaf triangles instead).
// Each edge's factor comes from that edge alone: its two corners (leaf vertices, world space, taken in
// the order of their vertex ids), its chord error (the same value in both faces' records) and the cull
// eye, so the two faces of an edge compute the same bits and no crack opens (docs/design.md, "Leaves"). The error
// is projected from the point of the edge's segment nearest the eye: a close camera may face the middle
// of a long edge, far nearer than its corners. The chord error of a curve falls with the square of the
// segments it is cut into, so an edge needs ceil(sqrt(projected error / tau)) segments; but no segment
// shorter than kMinSegmentPixels on screen, where the chord of a curve is a small fraction of a pixel
// off it anyway. That bound keeps a tau far below what the leaves reach (1e-9) from asking for every
// patch at factor 64: tessellated triangles stay fewer than the pixels they cover, and a face smaller
// than that on screen needs no tessellation at all. A locked edge (a level-0 group
// border, or a flat neighbour) stays at 1: its other side may be drawn as triangles. Inner factors: the
// larger of the face's own need (bounded by its projected size) and its edges'.

const float kMaxFactor = 64.0;
const float kMinSegmentPixels = 2.0;

// Segments for an object-space chord error `error` seen from `distanceToEye`, at most `pixels` (the
// projected length they divide). The segment of an edge lies in its cluster's sphere, so it is never
// nearer than the sphere and an edge of a cluster drawn as triangles (projected self error <= tau) gets
// 1 (the 1.001 absorbs rounding).
float segments(float error, float distanceToEye, float pixels) {
  if (error <= 0.0) return 1.0;
  float most = clamp(ceil(pixels / kMinSegmentPixels), 1.0, kMaxFactor);
  if (distanceToEye <= frame.znear) return most;
  float projected = error * frame.projScale / distanceToEye;
  return min(clamp(ceil(sqrt(projected / (frame.tau * 1.001))), 1.0, kMaxFactor), most);
}

// Factors of face `face` of instance `inst`: edge k runs from corner k to corner k + 1 (0: v = 0,
// 1: u = 1, 2: v = 1, 3: u = 0); inner[0] along u, inner[1] along v.
void patchFactors(Instance inst, uint face, out float edge[4], out float inner[2]) {
  Patch p = patches[face];
  CageFace cf = cageFaces[face];
  vec3 corner[4];
  uint vertex[4];
  for (uint k = 0u; k < 4u; k++) {
    vertex[k] = cageFaceVertices[cf.firstVertex + k];
    corner[k] = instanceToWorld(inst, vertexPosition(vertex[k]));
  }
  for (uint k = 0u; k < 4u; k++) {
    uint next = (k + 1u) % 4u;
    bool forward = vertex[k] < vertex[next];
    vec3 a = forward ? corner[k] : corner[next], b = forward ? corner[next] : corner[k];
    vec3 ab = b - a;
    float t = clamp(dot(frame.cullEye.xyz - a, ab) / max(dot(ab, ab), 1e-30), 0.0, 1.0);
    float d = distance(a + t * ab, frame.cullEye.xyz);
    float pixels = length(ab) * frame.projScale / max(d, frame.znear);
    edge[k] = patchEdgeLocked(p.info, k) ? 1.0 : segments(p.edgeError[k] * inst.maxScale, d, pixels);
  }
  // Inside: from the sphere around the corners, which holds the face's triangles.
  vec3 center = 0.25 * (corner[0] + corner[1] + corner[2] + corner[3]);
  float radius = 0.0;
  for (uint k = 0u; k < 4u; k++) radius = max(radius, distance(center, corner[k]));
  float d = distance(center, frame.cullEye.xyz) - radius;
  // The corners' sphere has about an edge's length as its diameter over sqrt(2): the face's side.
  float own = segments(p.faceError * inst.maxScale, d, 1.4142 * radius * frame.projScale / max(d, frame.znear));
  inner[0] = max(own, max(edge[0], edge[2]));
  inner[1] = max(own, max(edge[1], edge[3]));
}
