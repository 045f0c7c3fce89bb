// frame_counters.cpp: the fields every frame record shares (`render --stats`, `bench cut`, `bench frame`),
// written in one place so that the three commands name the same quantity the same way.
#include <algorithm>

#include "commands.h"

namespace vgeo {

void addFrameCounters(nlohmann::ordered_json& r, const FrameResult& f, const GpuRenderer& renderer,
                      const VulkanContext& vk) {
  const auto& c = f.counters;
  r["device"] = vk.deviceName();
  r["driver"] = vk.driverName();
  r["timing"] = f.timing;  // gpu-timestamps or host-per-submission
  r["instance_culling"] =
      f.culledInTraversal ? "traversal" : "pass";  // traversal: instance_cull_ms is the counter reset
  r["instances_visible"] = c.visibleInstances;
  r["nodes_visited"] = c.nodesVisited;
  r["clusters_tested"] = c.clustersTested;
  r["visible_clusters"] = std::min(c.drawCount, renderer.drawCapacity());
  r["queue_high_water"] = c.queueHighWater;
  // triangles: of the listed clusters (the cut); triangles_drawn: sent to the rasterizer, after triangle
  // culling dropped those that cannot make a fragment (equal to triangles without triangle culling).
  r["triangles"] = c.triangles;
  r["triangles_drawn"] = f.trianglesDrawn;
  r["software_triangles"] = f.softwareTriangles;  // of those, drawn by the software rasterizer
  // Triangle culling took many listed clusters a workgroup (cull_small_clusters.comp).
  r["packed_triangle_cull"] = c.packedCullDispatch[0] != 0u || c.earlyPackedCull != 0u;  // either pass
  // Leaves too coarse for tau drawn as tessellated patches: clusters, faces (patches) and the triangles
  // the tessellator made (pipeline statistics; -1 where the device has none).
  r["patch_clusters"] = c.patchClusters;
  r["patches_drawn"] = f.patchesDrawn;
  r["software_patches"] = f.softwarePatches;  // of those, tessellated and drawn by the compute rasterizer
  // "visibility": the hardware's triangles went into the visibility buffer too (no depth target);
  // "depth": the render pass drew with depth (patches for the tessellator, or no compute rasterizer).
  r["render_pass"] = f.drewIntoVisibility ? "visibility" : "depth";
  r["patch_triangles"] = f.patchTriangles;
  // Two-pass occlusion culling: the clusters the early pass drew (those of last frame's visible instances)
  // and what the late pass found hidden behind them.
  r["occlusion"] = f.occlusion;
  r["early_clusters"] = c.drawBase;
  r["occluded_instances"] = c.occludedInstances;
  r["occluded_nodes"] = c.occludedNodes;
  r["occluded_clusters"] = c.occludedClusters;
}

}  // namespace vgeo
