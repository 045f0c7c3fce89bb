// traverse_common.glsl: one step of the traversal, shared by the persistent, per-level and flat passes,
// so all three produce the same draw list.
//   node item:  test the node's children (nodes or groups) and queue those that may hold drawn clusters
//   group item: test each member cluster with the cut rule and append the drawn ones to the draw list

#include "occlusion.glsl"

// Loop iterations this invocation has run: the persistent traversal leaves before lavapipe's limit.
uint gLoops = 0u;

// Statistics are counted per invocation and added to the global counters once a workgroup (one global
// atomic per workgroup, not per cluster: per-cluster atomics on one address cost the flat traversal
// 14 ms for 200M clusters on an H200).
uint gNodes = 0u, gTested = 0u, gTriangles = 0u;
shared uint sNodes, sTested, sTriangles, sOccludedNodes, sOccludedClusters;
void beginStats() {
  if (gl_LocalInvocationIndex == 0u) {
    sNodes = 0u;
    sTested = 0u;
    sTriangles = 0u;
    sOccludedNodes = 0u;
    sOccludedClusters = 0u;
  }
  barrier();
}
// Every invocation of the workgroup must call it (it has barriers).
void flushStats() {
  if (gNodes != 0u) atomicAdd(sNodes, gNodes);
  if (gTested != 0u) atomicAdd(sTested, gTested);
  if (gTriangles != 0u) atomicAdd(sTriangles, gTriangles);
  if (gOccludedNodes != 0u) atomicAdd(sOccludedNodes, gOccludedNodes);
  if (gOccludedClusters != 0u) atomicAdd(sOccludedClusters, gOccludedClusters);
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    if (sNodes != 0u) atomicAdd(counters.nodesVisited, sNodes);
    if (sTested != 0u) atomicAdd(counters.clustersTested, sTested);
    if (sTriangles != 0u) atomicAdd(counters.triangles, sTriangles);
    if (sOccludedNodes != 0u) atomicAdd(counters.occludedNodes, sOccludedNodes);
    if (sOccludedClusters != 0u) atomicAdd(counters.occludedClusters, sOccludedClusters);
  }
}

uint gQueueEnd = 0u;  // the end of the last slots this invocation reserved (instance culling reports it)
// Reserves `count` queue slots; returns the first. Slots past the capacity are dropped, counted as
// overflow and as done (so the traversal still terminates), and reported to the host.
uint reserveQueue(uint count) {
  uint first = atomicAdd(counters.queueWrite, count);
  gQueueEnd = first + count;
  if (first + count > frame.queueCapacity) {
    uint lost = min(count, first + count - max(first, frame.queueCapacity));
    atomicAdd(counters.queueOverflow, lost);
    atomicAdd(counters.itemsDone, lost);
  }
  return first;
}

// An item is published by two plain stores and taken once both words are seen (each slot is written once
// a frame, and both words are VGEO_INVALID until then), so neither side needs a memory barrier, which
// would sit on every step of the traversal's chain of dependent steps.
// Returns whether the slot exists (false: the item was dropped as overflow).
bool writeQueue(uint slot, uint instance, uint code) {
  if (slot >= frame.queueCapacity) return false;
  queue[2 * slot + 1] = code;
  queue[2 * slot] = instance;
  return true;
}

// Queue slots [first, first + count) that exist (the rest were dropped as overflow).
uint slotsKept(uint first, uint count) { return first >= frame.queueCapacity ? 0u : min(count, frame.queueCapacity - first); }

bool slotWritten(uint slot) {
  return queue[2 * slot] != VGEO_INVALID && queue[2 * slot + 1] != VGEO_INVALID;  // coherent loads
}

// Reads slot `slot` if it has been written; resets it for the next frame.
bool takeQueue(uint slot, out uint instance, out uint code) {
  instance = queue[2 * slot];
  code = queue[2 * slot + 1];
  if (instance == VGEO_INVALID || code == VGEO_INVALID) return false;
  queue[2 * slot + 1] = VGEO_INVALID;
  queue[2 * slot] = VGEO_INVALID;
  return true;
}

// Writes draw-list entry `index` (reserved from counters.drawCount) unless the list is full.
void writeDraw(uint index, uint instance, uint cluster) {
  if (index < frame.drawCapacity) {
    drawList[2 * index] = instance;
    drawList[2 * index + 1] = cluster;
    gTriangles += clusterTriangleCount(clusters[cluster & ~VGEO_DRAW_PATCHES_BIT].counts);
  } else {
    atomicAdd(counters.drawOverflow, 1u);
  }
}

// The cut rule for one cluster of one instance, with frustum culling of its self sphere and cone culling:
// the draw-list code of the cluster (with VGEO_DRAW_PATCHES_BIT when its patches are drawn), or
// VGEO_INVALID. cutCluster loads the records itself; the persistent traversal's preloading rounds load
// them for several tests at once and call the two parts (cutClusterByError, then coneCulled).
uint cutClusterByError(Instance inst, uint cluster, Cluster c) {
  gTested++;
  if (!sphereInFrustum(worldSphere(inst, c.selfSphere))) return VGEO_INVALID;
  float self = projectedErrorWorld(inst, c.selfSphere, c.selfError);
  float parent = projectedErrorWorld(inst, c.parentSphere, c.parentError);
  if (!inCut(self, parent, frame.tau, c.producer == VGEO_NO_GROUP)) return VGEO_INVALID;
  // A leaf too coarse for tau: its patches are drawn (cull_triangles.comp lists them).
  uint patchBit = frame.drawPatches != 0u && c.producer == VGEO_NO_GROUP && self > frame.tau ? VGEO_DRAW_PATCHES_BIT : 0u;
  return cluster | patchBit;
}
// A cluster of the cut that is not drawn now: closed and uniformly scaled with every triangle facing
// away, or hidden by the depth pyramid (deferred by the early pass), tested with its own sphere.
bool clusterHidden(uint instance, uint cluster, Instance inst, Cluster c, ClusterCone cc) {
  if ((inst.flags & VGEO_INSTANCE_CONE_CULL) != 0u) {
    vec3 axis = normalize(vec3(dot(inst.row0.xyz, cc.cone.xyz), dot(inst.row1.xyz, cc.cone.xyz), dot(inst.row2.xyz, cc.cone.xyz)));
    if (clusterFacesAway(vec4(axis, cc.cone.w), worldSphere(inst, cc.sphere), frame.cullEye.xyz)) return true;
  }
  return itemHidden(instance, VGEO_ITEM_RUN_BIT | cluster, inst, cc.sphere, c.selfError);
}
uint cutCluster(uint instance, uint cluster) {
  Instance inst = instances[instance];
  Cluster c = clusters[cluster];
  uint draw = cutClusterByError(inst, cluster, c);
  if (draw == VGEO_INVALID || clusterHidden(instance, cluster, inst, c, clusterCones[cluster])) return VGEO_INVALID;
  return draw;
}

void testCluster(uint instance, uint cluster) {
  uint draw = cutCluster(instance, cluster);
  if (draw != VGEO_INVALID) writeDraw(atomicAdd(counters.drawCount, 1u), instance, draw);
}

// May anything below this (sphere, error) be drawn now? Pruned only when clearly outside the frustum, or
// when even the largest parent error below projects clearly under tau; not now when hidden by the depth
// pyramid (queue item `code` of `instance`: deferred by the early pass).
bool mayHoldDrawn(uint instance, uint code, Instance inst, vec4 sphere, float maxError) {
  vec4 s = worldSphere(inst, sphere);
  s.w *= kPruneSlack;
  if (!sphereInFrustum(s)) return false;
  if (!(projectedErrorWorld(inst, sphere, maxError) * kPruneSlack > frame.tau)) return false;
  return !itemHidden(instance, code, inst, sphere, maxError);
}

// Child `child` of a node, a group when the node is a leaf: may it hold drawn clusters, and its queue item.
uint childItem(uint child, bool leaf) { return leaf ? (child | VGEO_ITEM_GROUP_BIT) : child; }
bool childMayHoldDrawn(uint instance, Instance inst, uint child, bool leaf) {
  return leaf ? mayHoldDrawn(instance, childItem(child, leaf), inst, groups[child].sphere, groups[child].error)
              : mayHoldDrawn(instance, childItem(child, leaf), inst, nodes[child].sphere, nodes[child].maxError);
}
// Returns the node items it queued (for counters.nodesPending: instance culling adds them up once a
// workgroup; the levels traversal does not need them).
uint processItem(uint instance, uint code) {
  gNodes++;
  Instance inst = instances[instance];
  if ((code & VGEO_ITEM_GROUP_BIT) != 0u) {
    Group g = groups[code & ~VGEO_ITEM_GROUP_BIT];
    for (uint i = 0u; i < g.clusterCount; i++) {
      gLoops++;
      testCluster(instance, g.clusterOffset + i);
    }
    return 0u;
  }
  // The children that may hold drawn clusters, as a bit mask (a root has up to VGEO_BVH_ROOT_WIDTH = 64),
  // queued with one reservation.
  BvhNode node = nodes[code];
  uint count = node.childCountAndFlags & ~VGEO_NODE_LEAF_BIT;
  bool leaf = (node.childCountAndFlags & VGEO_NODE_LEAF_BIT) != 0u;
  uvec2 keep = uvec2(0u);
  for (uint i = 0u; i < count; i++) {
    gLoops++;
    if (childMayHoldDrawn(instance, inst, node.childOffset + i, leaf)) keep[i >> 5] |= 1u << (i & 31u);
  }
  uint kept = bitCount(keep.x) + bitCount(keep.y);
  if (kept == 0u) return 0u;
  uint slot = reserveQueue(kept);
  uint queuedNodes = leaf ? 0u : slotsKept(slot, kept);
  for (uint word = 0u; word < 2u; word++) {
    for (uint bits = keep[word]; bits != 0u; bits &= bits - 1u) {
      gLoops++;
      uint child = node.childOffset + 32u * word + uint(findLSB(bits));
      writeQueue(slot++, instance, childItem(child, leaf));
    }
  }
  return queuedNodes;
}
