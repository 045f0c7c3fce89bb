// build_scene.cpp: the builder's data flow for one input file (docs/design.md):
// load + validate -> repair -> Catmull-Clark N levels -> DAG -> layout. Sizes are checked before any
// subdivision so that a request too large for 32-bit indices is an error, not an out-of-memory.
#include "build_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include "../common/free_pages.h"
#include "../common/parallel.h"
#include "layout.h"

namespace vgeo {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void add(RepairReport& sum, const RepairReport& r) {
  sum.weldedVertices += r.weldedVertices;
  sum.degenerateFaces += r.degenerateFaces;
  sum.duplicateFaces += r.duplicateFaces;
  sum.nonManifoldEdges += r.nonManifoldEdges;
  sum.splitVertices += r.splitVertices;
  sum.boundaryEdges += r.boundaryEdges;
  sum.unusedVertices += r.unusedVertices;
  sum.flippedFaces += r.flippedFaces;
  sum.dissolvedVertices += r.dissolvedVertices;
  sum.components += r.components;
  sum.nonOrientableComponents += r.nonOrientableComponents;
}

// The mesh's triangles, counted a range of faces at a time on the threads.
size_t triangleCount(const PolygonMesh& mesh, int threads) {
  std::vector<size_t> rangeTriangles(parallelRangeCount(mesh.faceCount()), 0);
  parallelForRanges(mesh.faceCount(), threads, [&](size_t begin, size_t end) {
    rangeTriangles[begin / kParallelRange] = mesh.triangleCount(begin, end);
  });
  size_t n = 0;
  for (size_t t : rangeTriangles) n += t;
  return n;
}

// Vertices and triangles after `levels` rounds, exactly: V' = V + E + F, E' = 2E + C, F' = C, C' = 4C.
void predictSize(const PolygonMesh& mesh, size_t boundaryEdges, int levels, int threads, double& vertices,
                 double& triangles) {
  double v = double(mesh.positions.size()), c = double(mesh.faceVertices.size()), f = double(mesh.faceCount());
  double e = (c + double(boundaryEdges)) / 2.0;
  for (int l = 0; l < levels; l++) {
    double v2 = v + e + f, e2 = 2.0 * e + c, f2 = c, c2 = 4.0 * c;
    v = v2, e = e2, f = f2, c = c2;
  }
  vertices = v;
  triangles = levels > 0 ? 2.0 * f : double(triangleCount(mesh, threads));
}

// Six times the signed volume enclosed by the faces (fanned from their first corner), summed a fixed
// range of faces at a time and the ranges in order: the same sum on any number of threads.
double signedVolume(const PolygonMesh& mesh, int threads) {
  std::vector<double> rangeVolume(parallelRangeCount(mesh.faceCount()), 0.0);
  parallelForRanges(mesh.faceCount(), threads, [&](size_t begin, size_t end) {
    double volume = 0.0;
    for (size_t f = begin; f < end; f++) {
      const uint32_t* c = mesh.face(f);
      glm::dvec3 a(mesh.positions[c[0]]);
      for (uint32_t k = 1; k + 1 < mesh.faceSize(f); k++)
        volume += glm::dot(a, glm::cross(glm::dvec3(mesh.positions[c[k]]), glm::dvec3(mesh.positions[c[k + 1]])));
    }
    rangeVolume[begin / kParallelRange] = volume;
  });
  double volume = 0.0;
  for (const double v : rangeVolume) volume += v;
  return volume;
}

// The scene's instances of its meshes, each flagged by whether its mesh is `closed`; those of zero scale,
// which show nothing (glTF hides nodes so), left out and counted in `dropped`. An instance whose mesh
// (every vertex within `reach[mesh]` of its origin) could land past kMaxWorldExtent, half of it for the
// bounding sphere's slack, is the file's fault: the renderer could not place it in float.
std::vector<shaderio::Instance> sceneInstances(const std::string& path, const SourceScene& scene,
                                               const std::vector<bool>& closed, const std::vector<double>& reach,
                                               uint32_t& dropped) {
  std::vector<shaderio::Instance> instances;
  dropped = 0;
  for (const SourceInstance& inst : scene.instances) {
    shaderio::Instance out = makeInstance(inst.transform, inst.mesh, closed[inst.mesh]);
    const glm::dvec3 t(out.row0.w, out.row1.w, out.row2.w);
    const double far = glm::length(t) + 2.0 * double(out.maxScale) * reach[inst.mesh];
    const std::string mesh = scene.meshNames[inst.mesh];
    if (!std::isfinite(out.maxScale) || !(far <= double(kMaxWorldExtent)))
      throw InputError(path, "an instance of mesh '" + mesh + "' is placed past +-1e15 by its transform (scale " +
                                 std::to_string(out.maxScale) + "): too far or too large for float");
    if (out.maxScale > 0.0f)
      instances.push_back(out);
    else
      dropped++;
  }
  if (instances.empty() && !scene.instances.empty())
    throw InputError(path, "every instance has a zero scale: nothing to draw");
  return instances;
}

// Why a DAG kept more than one root per component: a topology-preserving simplifier cannot remove a
// handle or close a boundary loop, so a surface of genus g keeps about 4g triangles and each loop at
// least three edges; otherwise the last groups could not be halved within the simplifier's rules.
std::string unreducedReason(const SurfaceTopology& t) {
  if (t.genus > 0 || t.boundaryLoops > t.components)
    return "genus " + std::to_string(t.genus) + " and " + std::to_string(t.boundaryLoops) +
           " boundary loops; simplification keeps every handle and hole";
  return "no group could be halved without moving a locked group border or folding the surface";
}

// How errors name mesh m: the file, and the mesh's name where the file holds several.
std::string meshWhere(const std::string& path, const SourceScene& scene, size_t m) {
  return scene.meshes.size() > 1 ? path + " (mesh '" + scene.meshNames[m] + "')" : path;
}

// What repair finds of each mesh that later steps need.
struct RepairedMeshes {
  std::vector<bool> closed;   // closed and facing out: its instances may drop back faces
  std::vector<double> reach;  // the farthest vertex from the mesh's origin (instances' placement check)
};

// Repairs every mesh in place and checks that its subdivision fits the format's 32-bit indices before
// any is made.
RepairedMeshes repairMeshes(const std::string& path, SourceScene& scene, const SceneBuildOptions& options,
                            SceneBuildStats& stats) {
  RepairedMeshes r{std::vector<bool>(scene.meshes.size()), std::vector<double>(scene.meshes.size(), 0.0)};
  for (size_t m = 0; m < scene.meshes.size(); m++) {
    PolygonMesh& mesh = scene.meshes[m];
    for (const glm::vec3& p : mesh.positions) r.reach[m] = std::max(r.reach[m], glm::length(glm::dvec3(p)));
    stats.inputTriangles += triangleCount(mesh, options.threads);
    const std::string where = meshWhere(path, scene, m);
    const RepairReport report =
        timed(&stats.stages, "repair", [&] { return repairMesh(mesh, where, options.threads); });
    add(stats.repair, report);
    // Closed: no boundary edge, no vertex split by repair (so positions identify vertices), and facing
    // out (positive signed volume): the renderer drops back faces of closed instances, which would drop
    // the visible side of a mesh that is inside out.
    r.closed[m] = report.boundaryEdges == 0 && report.splitVertices == 0 && signedVolume(mesh, options.threads) > 0.0;
    double vertices = 0, triangles = 0;
    predictSize(mesh, report.boundaryEdges, options.subdivisionLevels, options.threads, vertices, triangles);
    // Cluster triangles over all levels (~2x the leaves) and vertices must stay addressable by uint32.
    if (vertices > double(UINT32_MAX) || triangles * 2.0 > double(INT32_MAX))
      throw InputError(where, "too large for the format's 32-bit indices: --subdiv " +
                                  std::to_string(options.subdivisionLevels) + " would make " +
                                  std::to_string(uint64_t(triangles)) + " triangles over " +
                                  std::to_string(uint64_t(vertices)) + " vertices (limit about 1 billion triangles)");
  }
  return r;
}

// A mesh's finest level, as the DAG takes it.
struct LeafMesh {
  PolygonMesh faces;                   // subdivided, at the limit, large faces in strips
  FillLaterVector<glm::vec3> normals;  // limit normals of a subdivided cage
  MeshPatches patches;                 // and its limit-surface patches
  PatchErrorList patchErrors;          // with the chord errors of their faces
  bool trianglesOnly = false;          // every leaf face a triangle before the strips: repaired faces
  bool positionsDistinct = true;       // no two limit positions rounded together
};

// Subdivides a cage `levels` times; a subdivided cage's leaves then sample the limit surface: its
// patches, limit positions and normals (limit.cpp) and the faces' chord errors against the patches.
LeafMesh makeLeaves(PolygonMesh mesh, const SceneBuildOptions& options, SceneBuildStats& stats,
                    const std::function<void(const char*)>& progress) {
  LeafMesh leaves;
  leaves.faces = timed(&stats.stages, "subdivide", [&] {
    for (int l = 0; l < options.subdivisionLevels; l++) {
      progress("subdividing");
      mesh = subdivideCatmullClark(mesh, options.threads);
    }
    return std::move(mesh);
  });
  PolygonMesh& faces = leaves.faces;
  if (options.subdivisionLevels >= 1) {
    const uint32_t threads = uint32_t(std::max(options.threads, 1));
    const Patcher patcher(faces, options.threads);  // its corners serve the limit too
    leaves.patches =
        timed(&stats.stages, "patches", [&] { return buildPatches(faces, faces.positions, patcher, threads); });
    timed(&stats.stages, "limit", [&] {
      moveToLimit(faces, leaves.normals, options.threads, &patcher.corners());
      leaves.positionsDistinct = positionsDistinct(faces.positions, options.threads);
    });
    leaves.patchErrors =
        timed(&stats.stages, "patch chord errors", [&] { return patchChordErrors(faces, leaves.patches, threads); });
  }
  leaves.trianglesOnly = faces.faceVertices.size() == 3 * faces.faceCount();  // before any strip
  timed(&stats.stages, "fans", [&] {
    triangulateLargeFaces(faces, options.threads);
    stats.leafTriangles += triangleCount(faces, options.threads);
  });
  return leaves;
}

// The built DAG's counts, added to the scene's.
void addDagStats(SceneBuildStats& stats, const Dag& dag, const std::string& name) {
  stats.clusters += dag.clusters.size();
  stats.leafClusters += dag.levelClusters[0];
  for (const auto& c : dag.clusters) stats.clusterTriangles += c.indices.size() / 3;
  stats.levels = std::max<uint32_t>(stats.levels, uint32_t(dag.levelClusters.size()));
  stats.levelClusters.resize(stats.levels, 0);
  stats.levelTriangles.resize(stats.levels, 0);
  for (size_t l = 0; l < dag.levelClusters.size(); l++) {
    stats.levelClusters[l] += dag.levelClusters[l];
    stats.levelTriangles[l] += dag.levelTriangles[l];
  }
  stats.rootClusters += dag.rootClusters;
  if (dag.rootClusters > dag.roots.components)
    stats.unreduced.push_back({name, dag.rootClusters, dag.roots, unreducedReason(dag.roots)});
  stats.relaxedGroups += dag.relaxedGroups;
  stats.stuckGroups += dag.stuckGroups;
}

}  // namespace

// Load and repair every mesh, then one mesh at a time from subdivision to layout, each array freed once
// used: the build's peak memory is one mesh's. Between steps the threads' free pages go back to the
// kernel (free_pages.h): the file's text and repair's sorts, the rounds' meshes, the DAG's scratch.
void buildScene(const std::string& path, const SceneBuildOptions& options, SceneBuildStats& stats, SectionSink& data) {
  auto start = std::chrono::steady_clock::now();
  SourceScene scene = timed(&stats.stages, "load", [&] { return loadMeshFile(path, options.threads); });
  stats.loadSeconds = secondsSince(start);
  if (options.subdivisionLevels < 0) throw InputError(path, "--subdiv must be >= 0");
  RepairedMeshes repaired = repairMeshes(path, scene, options, stats);
  returnFreePages(options.threads, &stats.stages);

  std::vector<shaderio::Instance> instances;
  const size_t meshes = scene.meshes.size();
  for (size_t m = 0; m < meshes; m++) {
    const std::string name = meshes > 1 ? scene.meshNames[m] : path;
    const std::string where = meshWhere(path, scene, m);
    auto progress = [&, m](double f, const char* stage) {
      if (options.progress) options.progress((double(m) + f) / double(meshes), stage);
    };
    auto subdivideStart = std::chrono::steady_clock::now();
    LeafMesh leaves =
        makeLeaves(std::move(scene.meshes[m]), options, stats, [&](const char* stage) { progress(0.0, stage); });
    repaired.closed[m] = repaired.closed[m] && leaves.positionsDistinct;
    stats.subdivideSeconds += secondsSince(subdivideStart);

    auto buildStart = std::chrono::steady_clock::now();
    // The patches' words and control points go to the file now: nothing before the layout reads them.
    const PatchBases patchBases =
        timed(&stats.stages, "patch points", [&] { return appendPatchPoints(data, leaves.patches); });
    if (options.subdivisionLevels >= 1) returnFreePages(options.threads, &stats.stages);
    VertexFaces leafFaces;  // made by the normals' sums on threads, then the leaf clusters' dual graph
    const ShadingNormals shading = timed(&stats.stages, "shading normals", [&] {
      return shadingNormals(leaves.faces, leaves.normals, options.creaseAngleDegrees, options.threads, &leafFaces);
    });
    FillLaterVector<glm::vec3>().swap(leaves.normals);
    BuildOptions bo;
    bo.threads = options.threads;
    bo.groupSize = options.groupSize;
    bo.leafFaceErrors = &leaves.patchErrors;
    bo.leavesAreRepairedFaces = leaves.trianglesOnly;
    bo.times = &stats.stages;
    bo.shading = &shading;
    bo.leafFaces = &leafFaces;
    if (options.progress) bo.progress = progress;
    Dag dag;
    try {
      dag = buildDag(leaves.faces, bo);
    } catch (const SurfaceError& e) {
      throw InputError(where, e.what());
    }
    returnFreePages(options.threads, &stats.stages);  // the layout's arrays are allocated on this thread
    timed(&stats.stages, "layout", [&] {
      const bool last = m + 1 == meshes;
      if (last) {  // every mesh's closedness is known: the instances' total too
        instances = sceneInstances(path, scene, repaired.closed, repaired.reach, stats.zeroScaleInstances);
        data.expectTotal(Section::Instances, data.count(Section::Instances) + instances.size());
      }
      appendGeometry(data, dag, leaves.faces, shading, leaves.patches, patchBases, leaves.patchErrors,
                     repaired.closed[m], last, options.threads);
    });
    addDagStats(stats, dag, name);
    stats.buildSeconds += secondsSince(buildStart);
  }
  if (meshes == 0) instances = sceneInstances(path, scene, repaired.closed, repaired.reach, stats.zeroScaleInstances);
  data.append(Section::Instances, instances);
  stats.geometries = uint32_t(data.count(Section::Geometries));
  stats.instances = uint32_t(data.count(Section::Instances));
}

VgeoData buildScene(const std::string& path, const SceneBuildOptions& options, SceneBuildStats& stats) {
  VgeoData data;
  VgeoDataSink sink(data);
  buildScene(path, options, stats, sink);
  return data;
}

}  // namespace vgeo
