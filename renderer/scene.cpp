// scene.cpp: loading .vgeo files and scene files into one RenderScene.
//
// Scene file (JSON):
//   { "geometries": ["a.vgeo", {"path": "b.vgeo"}],
//     "instances": [ {"geometry": 0, "translation": [x, y, z], "rotation": [x, y, z, w], "scale": s | [sx, sy, sz]},
//                    {"geometry": 1, "matrix": [16 numbers, column-major]} ] }
// Paths are relative to the scene file. An instance places all of its file's instances (a glTF scene
// built into one .vgeo keeps its own layout); without "instances", each file is placed once as it is.
#include "scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "../common/input_error.h"

namespace vgeo {

uint32_t appendVgeo(VgeoData& dst, const VgeoData& src) {
  const uint32_t geometryBase = uint32_t(dst.geometries.size()), vertexBase = uint32_t(dst.vertexCount()),
                 clusterBase = uint32_t(dst.clusters.size()), groupBase = uint32_t(dst.groups.size()),
                 nodeBase = uint32_t(dst.nodes.size()), clusterVertexBase = uint32_t(dst.clusterVertices.size()),
                 clusterTriangleBase = uint32_t(dst.clusterTriangles.size()), cageBase = uint32_t(dst.cageFaces.size()),
                 cageVertexBase = uint32_t(dst.cageFaceVertices.size()), patchPointBase = uint32_t(dst.patchPoints.size()),
                 controlPointBase = uint32_t(dst.controlPoints.size() / 3);
  for (auto g : src.geometries) {
    g.clusterOffset += clusterBase;
    g.groupOffset += groupBase;
    g.nodeOffset += nodeBase;
    g.vertexOffset += vertexBase;
    g.cageFaceOffset += cageBase;
    dst.geometries.push_back(g);
  }
  for (auto inst : src.instances) {
    inst.geometry += geometryBase;
    dst.instances.push_back(inst);
  }
  dst.positions.insert(dst.positions.end(), src.positions.begin(), src.positions.end());
  dst.normals.insert(dst.normals.end(), src.normals.begin(), src.normals.end());
  for (auto c : src.clusters) {
    c.vertexOffset += clusterVertexBase;
    c.triangleOffset += clusterTriangleBase;
    c.group += groupBase;
    if (c.producer != VGEO_NO_GROUP) c.producer += groupBase;
    c.cageFaceOffset += cageBase;
    dst.clusters.push_back(c);
  }
  for (uint32_t v : src.clusterVertices) dst.clusterVertices.push_back(v + vertexBase);
  dst.clusterTriangles.insert(dst.clusterTriangles.end(), src.clusterTriangles.begin(), src.clusterTriangles.end());
  for (auto g : src.groups) {
    g.clusterOffset += clusterBase;
    dst.groups.push_back(g);
  }
  for (auto n : src.nodes) {
    n.childOffset += (n.childCountAndFlags & VGEO_NODE_LEAF_BIT) ? groupBase : nodeBase;
    dst.nodes.push_back(n);
  }
  for (auto f : src.cageFaces) {
    f.firstVertex += cageVertexBase;
    f.leafCluster += clusterBase;
    dst.cageFaces.push_back(f);
  }
  for (uint32_t v : src.cageFaceVertices) dst.cageFaceVertices.push_back(v + vertexBase);
  dst.clusterCones.insert(dst.clusterCones.end(), src.clusterCones.begin(), src.clusterCones.end());
  dst.controlPoints.insert(dst.controlPoints.end(), src.controlPoints.begin(), src.controlPoints.end());
  for (auto p : src.patches) {
    p.firstPoint += patchPointBase;
    p.pointBase += controlPointBase;
    for (uint32_t& n : p.neighbours)
      if (n != VGEO_INVALID) n += cageBase << 2;
    dst.patches.push_back(p);
  }
  dst.patchPoints.insert(dst.patchPoints.end(), src.patchPoints.begin(), src.patchPoints.end());
  return geometryBase;
}

namespace {

glm::mat4 instanceMatrix(const shaderio::Instance& inst) {
  glm::mat4 m(1.0f);
  for (int c = 0; c < 4; c++) {
    m[c][0] = inst.row0[c];
    m[c][1] = inst.row1[c];
    m[c][2] = inst.row2[c];
  }
  return m;
}

glm::mat4 parseTransform(const nlohmann::json& j, const std::string& path, size_t index) {
  auto numbers = [&](const char* key, size_t count) {
    const auto& a = j.at(key);
    if (!a.is_array() || a.size() != count) throw InputError(path, "instance " + std::to_string(index) + ": '" + key + "' needs " + std::to_string(count) + " numbers");
    std::vector<float> v;
    for (const auto& x : a) v.push_back(x.get<float>());
    return v;
  };
  if (j.contains("matrix")) return glm::make_mat4(numbers("matrix", 16).data());
  glm::mat4 t(1.0f), r(1.0f), s(1.0f);
  if (j.contains("translation")) {
    auto v = numbers("translation", 3);
    t = glm::translate(glm::mat4(1.0f), {v[0], v[1], v[2]});
  }
  if (j.contains("rotation")) {
    auto v = numbers("rotation", 4);
    r = glm::mat4_cast(glm::normalize(glm::quat(v[3], v[0], v[1], v[2])));
  }
  if (j.contains("scale")) {
    if (j.at("scale").is_number()) s = glm::scale(glm::mat4(1.0f), glm::vec3(j.at("scale").get<float>()));
    else {
      auto v = numbers("scale", 3);
      s = glm::scale(glm::mat4(1.0f), {v[0], v[1], v[2]});
    }
  }
  return t * r * s;
}

RenderScene loadSceneFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open");
  RenderScene scene;
  try {
    nlohmann::json j = nlohmann::json::parse(in);
    std::filesystem::path dir = std::filesystem::path(path).parent_path();
    std::vector<VgeoData> files;
    for (const auto& g : j.at("geometries")) {
      std::string file = g.is_string() ? g.get<std::string>() : g.at("path").get<std::string>();
      std::filesystem::path p(file);
      if (p.is_relative()) p = dir / p;
      files.push_back(readVgeo(p.string()));
    }
    if (files.empty()) throw InputError(path, "no geometries");
    std::vector<nlohmann::json> placements;
    if (j.contains("instances")) placements.assign(j.at("instances").begin(), j.at("instances").end());
    else
      for (size_t i = 0; i < files.size(); i++) placements.push_back({{"geometry", i}});
    std::vector<uint32_t> base(files.size());
    VgeoData merged;
    for (size_t i = 0; i < files.size(); i++) {
      VgeoData copy = files[i];
      copy.instances.clear();
      base[i] = appendVgeo(merged, copy);
    }
    for (size_t k = 0; k < placements.size(); k++) {
      size_t file = placements[k].at("geometry").get<size_t>();
      if (file >= files.size()) throw InputError(path, "instance " + std::to_string(k) + " uses geometry " + std::to_string(file) + ", which is not listed");
      glm::mat4 m = parseTransform(placements[k], path, k);
      for (const auto& inst : files[file].instances) {
        uint32_t geometry = base[file] + inst.geometry;
        shaderio::Instance placed = makeInstance(m * instanceMatrix(inst), geometry, merged.geometries[geometry].flags & VGEO_GEOMETRY_CLOSED);
        if (!(placed.maxScale > 0.0f) || !std::isfinite(placed.maxScale)) throw InputError(path, "instance " + std::to_string(k) + " has a degenerate transform");
        merged.instances.push_back(placed);
      }
    }
    scene.data = std::move(merged);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("bad scene file: ") + e.what());
  }
  return scene;
}

}  // namespace

void finishScene(RenderScene& scene) {
  const VgeoData& d = scene.data;
  scene.bvhDepth.assign(d.geometries.size(), 0);
  scene.maxBvhDepth = 0;
  scene.maxClusters = 0;
  for (size_t g = 0; g < d.geometries.size(); g++) {
    std::function<uint32_t(uint32_t)> depth = [&](uint32_t n) -> uint32_t {
      const auto& node = d.nodes[n];
      if (node.childCountAndFlags & VGEO_NODE_LEAF_BIT) return 1;
      uint32_t best = 0, count = node.childCountAndFlags & ~VGEO_NODE_LEAF_BIT;
      for (uint32_t i = 0; i < count; i++) best = std::max(best, depth(node.childOffset + i));
      return best + 1;
    };
    scene.bvhDepth[g] = depth(d.geometries[g].nodeOffset);
    scene.maxBvhDepth = std::max(scene.maxBvhDepth, scene.bvhDepth[g]);
    scene.maxClusters = std::max(scene.maxClusters, d.geometries[g].clusterCount);
  }
  // Each instance carries its geometry's BVH root (shaderio.h, Instance).
  for (auto& inst : scene.data.instances) {
    const auto& root = d.nodes[d.geometries[inst.geometry].nodeOffset];
    inst.flags = (inst.flags & VGEO_INSTANCE_CONE_CULL) | ((root.childCountAndFlags & ~VGEO_NODE_LEAF_BIT) << VGEO_INSTANCE_ROOT_COUNT_SHIFT) |
                 (root.childCountAndFlags & VGEO_NODE_LEAF_BIT ? VGEO_INSTANCE_ROOT_LEAF : 0u);
    inst.rootChildOffset = root.childOffset;
  }
  // Level subtrees' cluster runs (the layout stores groups in BVH leaf order and clusters in group order,
  // so each is one run; checked here, not assumed).
  scene.levelClusterRuns.assign(d.nodes.size(), glm::uvec2(0));
  for (const auto& geometry : d.geometries) {
    const auto& root = d.nodes[geometry.nodeOffset];
    if (root.childCountAndFlags & VGEO_NODE_LEAF_BIT) continue;
    for (uint32_t i = 0; i < (root.childCountAndFlags & ~VGEO_NODE_LEAF_BIT); i++) {
      uint32_t first = UINT32_MAX, end = 0;
      uint64_t count = 0;
      std::function<void(uint32_t)> visit = [&](uint32_t n) {
        const auto& node = d.nodes[n];
        const uint32_t children = node.childCountAndFlags & ~VGEO_NODE_LEAF_BIT;
        for (uint32_t c = 0; c < children; c++) {
          if (!(node.childCountAndFlags & VGEO_NODE_LEAF_BIT)) {
            visit(node.childOffset + c);
          } else {
            const auto& group = d.groups[node.childOffset + c];
            first = std::min(first, group.clusterOffset);
            end = std::max(end, group.clusterOffset + group.clusterCount);
            count += group.clusterCount;
          }
        }
      };
      visit(root.childOffset + i);
      if (count != 0 && end - first == count) scene.levelClusterRuns[root.childOffset + i] = glm::uvec2(first, uint32_t(count));
    }
  }
  // Bounds: centred on the AABB of the instances' spheres, with the radius that encloses them all.
  std::vector<uint64_t> leafTriangles(d.geometries.size(), 0);
  for (size_t g = 0; g < d.geometries.size(); g++)
    for (uint32_t i = d.geometries[g].clusterOffset; i < d.geometries[g].clusterOffset + d.geometries[g].clusterCount; i++)
      if (d.clusters[i].producer == VGEO_NO_GROUP) leafTriangles[g] += shaderio::clusterTriangleCount(d.clusters[i].counts);
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  scene.virtualTriangles = 0;
  for (const auto& inst : d.instances) {
    const auto& g = d.geometries[inst.geometry];
    glm::vec4 s = g.boundsSphere;
    glm::vec3 c(glm::dot(inst.row0, glm::vec4(glm::vec3(s), 1.0f)), glm::dot(inst.row1, glm::vec4(glm::vec3(s), 1.0f)),
                glm::dot(inst.row2, glm::vec4(glm::vec3(s), 1.0f)));
    float r = s.w * inst.maxScale;
    lo = glm::min(lo, c - r);
    hi = glm::max(hi, c + r);
    scene.virtualTriangles += leafTriangles[inst.geometry];
  }
  glm::vec3 centre = (lo + hi) * 0.5f;
  float radius = 1e-6f;
  for (const auto& inst : d.instances) {
    glm::vec4 s = d.geometries[inst.geometry].boundsSphere;
    glm::vec3 c(glm::dot(inst.row0, glm::vec4(glm::vec3(s), 1.0f)), glm::dot(inst.row1, glm::vec4(glm::vec3(s), 1.0f)),
                glm::dot(inst.row2, glm::vec4(glm::vec3(s), 1.0f)));
    radius = std::max(radius, glm::distance(centre, c) + s.w * inst.maxScale);
  }
  scene.bounds = d.instances.empty() ? glm::vec4(0, 0, 0, 1) : glm::vec4(centre, radius);
  scene.boxMin = lo;
  scene.boxMax = hi;
}

RenderScene makeBenchScene(const RenderScene& base, uint32_t count, bool scatter, uint64_t seed) {
  RenderScene scene;
  scene.data = base.data;
  scene.data.instances.clear();
  const auto& g = base.data.geometries[0];
  const bool closed = g.flags & VGEO_GEOMETRY_CLOSED;
  const float spacing = 2.5f * g.boundsSphere.w;
  const uint32_t side = uint32_t(std::ceil(std::sqrt(double(std::max(count, 1u)))));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (uint32_t i = 0; i < count; i++) {
    glm::vec3 at((float(i % side) - 0.5f * float(side - 1)) * spacing, 0.0f, (float(i / side) - 0.5f * float(side - 1)) * spacing);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), at - glm::vec3(g.boundsSphere));
    if (scatter) {
      at = glm::vec3((unit(rng) - 0.5f) * float(side) * spacing, 0.0f, (unit(rng) - 0.5f) * float(side) * spacing);
      float scale = 0.7f + 0.6f * unit(rng);
      m = glm::translate(glm::mat4(1.0f), at) * glm::rotate(glm::mat4(1.0f), 6.2831853f * unit(rng), glm::vec3(0, 1, 0)) *
          glm::scale(glm::mat4(1.0f), glm::vec3(scale)) * glm::translate(glm::mat4(1.0f), -glm::vec3(g.boundsSphere));
    }
    scene.data.instances.push_back(makeInstance(m, 0, closed));
  }
  finishScene(scene);
  return scene;
}

RenderScene loadRenderScene(const std::string& path, uint32_t grid) {
  RenderScene scene;
  std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".json") scene = loadSceneFile(path);
  else scene.data = readVgeo(path);
  if (scene.data.instances.empty()) throw InputError(path, "the scene has no instances");
  finishScene(scene);
  if (grid > 1) {
    // N x N copies of the whole scene on the x-z plane, with a quarter of its diameter between copies.
    float spacing = 2.5f * scene.bounds.w;
    std::vector<shaderio::Instance> original = scene.data.instances;
    scene.data.instances.clear();
    for (uint32_t z = 0; z < grid; z++)
      for (uint32_t x = 0; x < grid; x++) {
        glm::mat4 t = glm::translate(glm::mat4(1.0f), glm::vec3((float(x) - 0.5f * float(grid - 1)) * spacing, 0.0f,
                                                                (float(z) - 0.5f * float(grid - 1)) * spacing));
        for (const auto& inst : original)
          scene.data.instances.push_back(makeInstance(t * instanceMatrix(inst), inst.geometry,
                                                      scene.data.geometries[inst.geometry].flags & VGEO_GEOMETRY_CLOSED));
      }
    finishScene(scene);
  }
  return scene;
}

}  // namespace vgeo
