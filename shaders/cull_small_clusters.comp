#version 450
// cull_small_clusters.comp: triangle culling (cull_triangles.comp's rules, cull_triangles.glsl) for
// draw lists of small clusters. A workgroup takes VGEO_PACKED_CULL_ENTRIES consecutive draw-list entries
// and goes through their triangles side by side, 128 at a time: a 100,000-instance far view lists
// 13-triangle roots, which one workgroup an entry left 90% of the lanes idle (and on lavapipe each
// workgroup and each pass of its lanes costs microseconds, busy or not). Its lanes read their entry's
// instance and cluster from shared memory, each its own: slower than cull_triangles.comp's one entry
// for all when clusters are full. draw_arguments.glsl picks one of the two for the frame; both list the
// same triangles.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "raster_setup.glsl"
layout(local_size_x = VGEO_MAX_CLUSTER_TRIANGLES) in;
#include "cull_triangles.glsl"

// The workgroup's entries, loaded once by a lane each: their triangles counted from the first entry's
// (sFirstTriangle[k], up to sFirstTriangle[entries] in all; a patch-drawn entry has none here), and
// what binTriangle reads of their instance and cluster.
shared uint sCount[VGEO_PACKED_CULL_ENTRIES];
shared uint sFirstTriangle[VGEO_PACKED_CULL_ENTRIES + 1u];
shared vec4 sRow[VGEO_PACKED_CULL_ENTRIES][3];
shared uint sFlags[VGEO_PACKED_CULL_ENTRIES];
shared uvec2 sOffsets[VGEO_PACKED_CULL_ENTRIES];  // the cluster's vertex and triangle offsets

// Loads entry firstEntry + k into the shared arrays; a patch-drawn entry joins the patch-entry list.
void loadEntry(uint firstEntry, uint k) {
  uint entry = firstEntry + k, cluster = drawList[2u * entry + 1u];
  if ((cluster & VGEO_DRAW_PATCHES_BIT) != 0u) {
    patchEntries[atomicAdd(counters.patchEntries, 1u)] = entry;
    sCount[k] = 0u;
    return;
  }
  Instance inst = instances[drawList[2u * entry]];
  Cluster c = clusters[cluster];
  sCount[k] = clusterTriangleCount(c.counts);
  sRow[k] = vec4[3](inst.row0, inst.row1, inst.row2);
  sFlags[k] = inst.flags;
  sOffsets[k] = uvec2(c.vertexOffset, c.triangleOffset);
}

void main() {
  uint listed = min(counters.drawCount, frame.drawCapacity);
  uint firstEntry = counters.drawBase + (gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x) * VGEO_PACKED_CULL_ENTRIES;
  if (firstEntry >= listed) return;  // the whole workgroup
  uint lane = gl_LocalInvocationIndex;
  uint entries = min(VGEO_PACKED_CULL_ENTRIES, listed - firstEntry);
  if (lane < entries) loadEntry(firstEntry, lane);
  barrier();
  if (lane == 0u) {
    uint total = 0u;
    for (uint k = 0u; k < entries; k++) {
      sFirstTriangle[k] = total;
      total += sCount[k];
    }
    for (uint k = entries; k <= VGEO_PACKED_CULL_ENTRIES; k++) sFirstTriangle[k] = k == entries ? total : 0xffffffffu;
  }
  barrier();
  uint total = sFirstTriangle[entries];
  for (uint start = 0u; start < total; start += VGEO_MAX_CLUSTER_TRIANGLES) {  // the same for the whole workgroup
    if (lane == 0u) {
      sKeptTriangles = 0u;
      sSoftware = 0u;
    }
    barrier();
    // This lane's entry: the last that starts at or before its triangle (entries without triangles
    // start where the next does), by a binary search.
    uint at = start + lane, k = 0u;
    for (uint step = VGEO_PACKED_CULL_ENTRIES / 2u; step > 0u; step /= 2u) k += sFirstTriangle[k + step] <= at ? step : 0u;
    uint triangle = at - sFirstTriangle[k], bin = kCulled;
    if (at < total) {
      Instance inst = Instance(sRow[k][0], sRow[k][1], sRow[k][2], 0u, 0.0, sFlags[k], 0u);
      Cluster c = Cluster(vec4(0.0), vec4(0.0), 0.0, 0.0, sOffsets[k].x, sOffsets[k].y, 0u, 0u, 0u, 0u);
      bin = binTriangle(inst, c, triangle);
    }
    uint bins[2] = uint[2](bin, kCulled);
    listTriangles(firstEntry + k, triangle, bins);
    barrier();  // the next turn resets the counts
  }
}
