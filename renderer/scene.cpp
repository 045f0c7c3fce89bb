// scene.cpp: loading .vgeo files and scene files into one RenderScene.
//
// Scene file (JSON):
//   { "geometries": ["a.vgeo", {"path": "b.vgeo"}],
//     "instances": [ {"geometry": 0, "translation": [x, y, z], "rotation": [x, y, z, w], "scale": s | [sx, sy, sz]},
//                    {"geometry": 1, "matrix": [16 numbers, column-major]} ] }
// Paths are relative to the scene file and stay in its folder. An instance places all of its file's
// instances (a glTF scene built into one .vgeo keeps its own layout); without "instances", each file
// is placed once as it is. Unknown keys, values of the wrong kind, 'matrix' beside the other transform
// keys and a zero quaternion are errors.
#include "scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "../common/input_error.h"
#include "../common/json_depth.h"

namespace vgeo {

uint32_t appendVgeo(VgeoData& dst, const VgeoData& src) {
  const uint32_t geometryBase = uint32_t(dst.geometries.size()), vertexBase = uint32_t(dst.vertexCount()),
                 clusterBase = uint32_t(dst.clusters.size()), groupBase = uint32_t(dst.groups.size()),
                 nodeBase = uint32_t(dst.nodes.size()), clusterVertexBase = uint32_t(dst.clusterVertices.size()),
                 clusterTriangleBase = uint32_t(dst.clusterTriangles.size()), cageBase = uint32_t(dst.cageFaces.size()),
                 cageVertexBase = uint32_t(dst.cageFaceVertices.size()),
                 patchPointBase = uint32_t(dst.patchPoints.size()),
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

// Scene files are read strictly: a typo ("tranlsation") or a value of the wrong kind is an error that
// names the instance and the key, not a silently different scene.
[[noreturn]] void sceneError(const std::string& path, const std::string& where, const std::string& cause) {
  throw InputError(path, where + ": " + cause);
}

void onlyKeys(const nlohmann::json& j, std::initializer_list<const char*> allowed, const std::string& path,
              const std::string& where) {
  if (!j.is_object()) sceneError(path, where, "expected an object");
  for (const auto& [key, value] : j.items()) {
    bool known = false;
    for (const char* a : allowed) known |= key == a;
    if (!known) {
      std::string list;
      for (const char* a : allowed) {
        if (!list.empty()) list += ", ";
        list.append("'").append(a).append("'");
      }
      sceneError(path, where, "unknown key '" + key + "' (expected " + list + ")");
    }
  }
}

std::vector<float> numbers(const nlohmann::json& j, const char* key, size_t count, const std::string& path,
                           const std::string& where) {
  const auto& a = j.at(key);
  const std::string name = std::string("'").append(key).append("'");
  if (!a.is_array() || a.size() != count)
    sceneError(path, where, name + " needs " + std::to_string(count) + " numbers");
  std::vector<float> v;
  for (const auto& x : a) {
    if (!x.is_number() || !std::isfinite(x.get<double>()) || std::abs(x.get<double>()) > 1e30)
      sceneError(path, where, name + " needs finite numbers");
    v.push_back(x.get<float>());
  }
  return v;
}

glm::mat4 parseTransform(const nlohmann::json& j, const std::string& path, const std::string& where) {
  if (j.contains("matrix")) {
    if (j.contains("translation") || j.contains("rotation") || j.contains("scale"))
      sceneError(path, where, "'matrix' and 'translation', 'rotation' or 'scale' together: give one or the other");
    std::vector<float> m = numbers(j, "matrix", 16, path, where);
    if (m[3] != 0.0f || m[7] != 0.0f || m[11] != 0.0f || m[15] != 1.0f)
      sceneError(path, where,
                 "'matrix' (column-major) must end each column with 0, 0, 0 and the last with 1: no projection");
    return glm::make_mat4(m.data());
  }
  glm::mat4 t(1.0f), r(1.0f), s(1.0f);
  if (j.contains("translation")) {
    auto v = numbers(j, "translation", 3, path, where);
    t = glm::translate(glm::mat4(1.0f), {v[0], v[1], v[2]});
  }
  if (j.contains("rotation")) {
    auto v = numbers(j, "rotation", 4, path, where);
    glm::quat q(v[3], v[0], v[1], v[2]);
    if (!(glm::length(q) > 1e-6f)) sceneError(path, where, "'rotation' is a zero quaternion (x, y, z, w)");
    r = glm::mat4_cast(glm::normalize(q));
  }
  if (j.contains("scale")) {
    if (j.at("scale").is_number()) {
      auto v = numbers(nlohmann::json{{"scale", nlohmann::json::array({j.at("scale")})}}, "scale", 1, path, where);
      s = glm::scale(glm::mat4(1.0f), glm::vec3(v[0]));
    } else {
      auto v = numbers(j, "scale", 3, path, where);
      s = glm::scale(glm::mat4(1.0f), {v[0], v[1], v[2]});
    }
  }
  return t * r * s;
}

// A geometry's path: relative, inside the scene file's folder (no absolute path, no '..' out of it),
// naming a regular file. Nothing outside the scene's folder is read.
std::string geometryPath(const std::filesystem::path& folder, const std::string& name, const std::string& path,
                         const std::string& where) {
  namespace fs = std::filesystem;
  fs::path p(name);
  if (name.empty() || p.is_absolute() || p.has_root_name())
    sceneError(path, where, "'" + name + "' must be a path relative to the scene file");
  fs::path normal = p.lexically_normal();
  if (normal.empty() || *normal.begin() == "..")
    sceneError(path, where, "'" + name + "' leaves the scene file's folder");
  std::error_code ec;
  const fs::path root = folder.empty() ? fs::path(".") : folder, full = root / normal;
  const fs::path base = fs::weakly_canonical(root, ec), resolved = fs::weakly_canonical(full, ec);
  auto rel = resolved.lexically_relative(base);
  if (ec || rel.empty() || *rel.begin() == "..")
    sceneError(path, where, "'" + name + "' leaves the scene file's folder (through a link)");
  if (!fs::is_regular_file(resolved, ec)) sceneError(path, where, "'" + name + "' is not a file");
  return full.string();
}

RenderScene loadSceneFile(const std::string& path) {
  constexpr uintmax_t kMaxSceneFileBytes = 64u << 20;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "cannot open: not a file");
  if (std::filesystem::file_size(path, ec) > kMaxSceneFileBytes)
    throw InputError(path, "larger than the 64 MiB a scene file may be");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (jsonDepth(text.data(), text.size(), kMaxJsonDepth) > kMaxJsonDepth)
    throw InputError(path, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  RenderScene scene;
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    onlyKeys(j, {"geometries", "instances"}, path, "the scene");
    if (!j.contains("geometries") || !j.at("geometries").is_array() || j.at("geometries").empty())
      throw InputError(path, "'geometries' must be a non-empty array of paths");
    std::filesystem::path dir = std::filesystem::path(path).parent_path();
    // Each distinct file read and merged once, however many entries name it.
    std::vector<VgeoData> files;
    std::vector<size_t> fileOf;                    // geometries entry -> files
    std::map<std::string, size_t> byPath, byName;  // by canonical path, and by the text that names it
    for (size_t g = 0; g < j.at("geometries").size(); g++) {
      const auto& entry = j.at("geometries")[g];
      const std::string where = "geometry " + std::to_string(g);
      if (entry.is_object()) onlyKeys(entry, {"path"}, path, where);
      const nlohmann::json& name = entry.is_object() && entry.contains("path") ? entry.at("path") : entry;
      if (!name.is_string()) sceneError(path, where, "expected a path or {\"path\": ...}");
      if (auto seen = byName.find(name.get<std::string>()); seen != byName.end()) {  // named again, as written
        fileOf.push_back(seen->second);
        continue;
      }
      const std::string file = geometryPath(dir, name.get<std::string>(), path, where);
      const std::string key = std::filesystem::weakly_canonical(file, ec).string();
      auto [it, added] = byPath.emplace(key, files.size());
      if (added) files.push_back(readVgeo(file));
      byName.emplace(name.get<std::string>(), it->second);
      fileOf.push_back(it->second);
    }
    const nlohmann::json* placements = nullptr;
    if (j.contains("instances") && !j.at("instances").is_array())
      throw InputError(path, "'instances' must be an array");
    if (j.contains("instances")) placements = &j.at("instances");
    // Counted before any is made: a small file may name a file of many instances many times.
    uint64_t total = 0;
    for (size_t k = 0; k < (placements ? placements->size() : fileOf.size()); k++) {
      size_t entry = k;
      if (placements) {
        const nlohmann::json& p = (*placements)[k];
        if (!p.is_object() || !p.contains("geometry"))
          sceneError(path, "instance " + std::to_string(k), "no 'geometry'");
        const auto& g = p.at("geometry");
        if (!g.is_number_integer() || g.get<int64_t>() < 0 || uint64_t(g.get<int64_t>()) >= fileOf.size())
          sceneError(path, "instance " + std::to_string(k),
                     "'geometry' must be an index into 'geometries' (0.." + std::to_string(fileOf.size() - 1) +
                         "), got " + g.dump());
        entry = size_t(g.get<int64_t>());
      }
      total += files[fileOf[entry]].instances.size();
      if (total > kMaxSceneInstances)
        throw InputError(path, "more than " + std::to_string(kMaxSceneInstances) + " instances in all");
    }
    std::vector<uint32_t> base(files.size());
    VgeoData merged;
    for (size_t i = 0; i < files.size(); i++) {
      VgeoData copy = files[i];
      copy.instances.clear();
      base[i] = appendVgeo(merged, copy);
    }
    merged.instances.reserve(total);
    for (size_t k = 0; k < (placements ? placements->size() : fileOf.size()); k++) {
      const std::string where = "instance " + std::to_string(k);
      glm::mat4 m(1.0f);
      size_t file = fileOf[k < fileOf.size() ? k : 0];
      if (placements) {
        const nlohmann::json& p = (*placements)[k];
        onlyKeys(p, {"geometry", "translation", "rotation", "scale", "matrix"}, path, where);
        file = fileOf[size_t(p.at("geometry").get<int64_t>())];
        m = parseTransform(p, path, where);
      }
      for (const auto& inst : files[file].instances) {
        uint32_t geometry = base[file] + inst.geometry;
        shaderio::Instance placed =
            makeInstance(m * instanceMatrix(inst), geometry, merged.geometries[geometry].flags & VGEO_GEOMETRY_CLOSED);
        const glm::mat3 linear(m * instanceMatrix(inst));
        if (!(placed.maxScale > 0.0f) || !std::isfinite(placed.maxScale) ||
            !(std::abs(glm::determinant(linear)) > 1e-9f * placed.maxScale * placed.maxScale * placed.maxScale))
          sceneError(path, where, "has a degenerate transform (it flattens the geometry)");
        const std::string problem = instanceProblem(placed, merged.geometries[geometry]);
        if (!problem.empty()) sceneError(path, where, "places an instance that " + problem);
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
  scene.maxLevels = 0;
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
    scene.maxLevels = std::max(scene.maxLevels, d.geometries[g].levelCount);
  }
  scene.instanceRoots.clear();
  for (const auto& inst : d.instances) {
    const auto& root = d.nodes[d.geometries[inst.geometry].nodeOffset];
    scene.instanceRoots.push_back(glm::uvec2(root.childCountAndFlags, root.childOffset));
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
      if (count != 0 && end - first == count)
        scene.levelClusterRuns[root.childOffset + i] = glm::uvec2(first, uint32_t(count));
    }
  }
  // Bounds: centred on the AABB of the instances' spheres, with the radius that encloses them all.
  std::vector<uint64_t> leafTriangles(d.geometries.size(), 0);
  for (size_t g = 0; g < d.geometries.size(); g++)
    for (uint32_t i = d.geometries[g].clusterOffset; i < d.geometries[g].clusterOffset + d.geometries[g].clusterCount;
         i++)
      if (d.clusters[i].producer == VGEO_NO_GROUP)
        leafTriangles[g] += shaderio::clusterTriangleCount(d.clusters[i].counts);
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
  // The tight box: each geometry's vertices' box, its corners placed by each instance.
  std::vector<glm::vec3> geometryMin(d.geometries.size(), glm::vec3(INFINITY)),
      geometryMax(d.geometries.size(), glm::vec3(-INFINITY));
  for (size_t g = 0; g < d.geometries.size(); g++)
    for (uint32_t v = d.geometries[g].vertexOffset; v < d.geometries[g].vertexOffset + d.geometries[g].vertexCount;
         v++) {
      geometryMin[g] = glm::min(geometryMin[g], d.position(v));
      geometryMax[g] = glm::max(geometryMax[g], d.position(v));
    }
  scene.objectMin = glm::vec3(INFINITY);
  scene.objectMax = glm::vec3(-INFINITY);
  for (const auto& inst : d.instances) {
    const glm::vec3 a = geometryMin[inst.geometry], b = geometryMax[inst.geometry];
    if (a.x > b.x) continue;  // no vertices
    for (int corner = 0; corner < 8; corner++) {
      const glm::vec4 p(corner & 1 ? b.x : a.x, corner & 2 ? b.y : a.y, corner & 4 ? b.z : a.z, 1.0f);
      const glm::vec3 w(glm::dot(inst.row0, p), glm::dot(inst.row1, p), glm::dot(inst.row2, p));
      scene.objectMin = glm::min(scene.objectMin, w);
      scene.objectMax = glm::max(scene.objectMax, w);
    }
  }
  if (scene.objectMin.x > scene.objectMax.x) {
    scene.objectMin = scene.boxMin;
    scene.objectMax = scene.boxMax;
  }
}

Camera sceneCamera(const RenderScene& scene, float fovYDegrees, float aspect) {
  const glm::vec3 extent = scene.objectMax - scene.objectMin;
  constexpr size_t kFramedVertices = size_t(1) << 22;  // past this many, the instances' boxes frame them
  const auto& d = scene.data;
  size_t vertices = 0;
  for (const auto& inst : d.instances) vertices += d.geometries[inst.geometry].vertexCount;
  if (extent.y < 0.25f * std::max(extent.x, extent.z) || vertices > kFramedVertices)  // flat, or too many
    return defaultCamera(scene.bounds, scene.objectMin, scene.objectMax, fovYDegrees, aspect);
  std::vector<glm::vec3> points;
  points.reserve(vertices);
  for (const auto& inst : d.instances) {
    const shaderio::Geometry& g = d.geometries[inst.geometry];
    for (uint32_t v = g.vertexOffset; v < g.vertexOffset + g.vertexCount; v++) {
      const glm::vec4 p(d.position(v), 1.0f);
      points.push_back({glm::dot(inst.row0, p), glm::dot(inst.row1, p), glm::dot(inst.row2, p)});
    }
  }
  return framePoints(points, fovYDegrees, aspect);
}

BenchLayout benchLayoutNamed(const std::string& name) {
  if (name == "grid") return BenchLayout::Grid;
  if (name == "scatter") return BenchLayout::Scatter;
  if (name == "forest") return BenchLayout::Forest;
  throw std::runtime_error("unknown layout '" + name + "' (grid, scatter or forest)");
}

RenderScene makeBenchScene(const RenderScene& base, uint32_t count, BenchLayout layout, uint64_t seed) {
  if (count > kMaxSceneInstances)
    throw std::runtime_error(std::to_string(count) + " instances: more than a scene may hold (" +
                             std::to_string(kMaxSceneInstances) + ")");
  RenderScene scene;
  scene.data = base.data;
  scene.data.instances.clear();
  const auto& g = base.data.geometries[0];
  const bool closed = g.flags & VGEO_GEOMETRY_CLOSED;
  const bool scatter = layout == BenchLayout::Scatter, forest = layout == BenchLayout::Forest;
  const float spacing = (forest ? 1.0f : 2.5f) * g.boundsSphere.w;
  const uint32_t side = uint32_t(std::ceil(std::sqrt(double(std::max(count, 1u)))));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (uint32_t i = 0; i < count; i++) {
    glm::vec3 at((float(i % side) - 0.5f * float(side - 1)) * spacing, 0.0f,
                 (float(i / side) - 0.5f * float(side - 1)) * spacing);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), at - glm::vec3(g.boundsSphere));
    if (scatter) {
      at = glm::vec3((unit(rng) - 0.5f) * float(side) * spacing, 0.0f, (unit(rng) - 0.5f) * float(side) * spacing);
      float scale = 0.7f + 0.6f * unit(rng);
      m = glm::translate(glm::mat4(1.0f), at) *
          glm::rotate(glm::mat4(1.0f), 6.2831853f * unit(rng), glm::vec3(0, 1, 0)) *
          glm::scale(glm::mat4(1.0f), glm::vec3(scale)) * glm::translate(glm::mat4(1.0f), -glm::vec3(g.boundsSphere));
    } else if (forest) {
      at += glm::vec3(unit(rng) - 0.5f, 0.0f, unit(rng) - 0.5f) * (0.3f * spacing);
      float scale = 0.85f + 0.3f * unit(rng);
      m = glm::translate(glm::mat4(1.0f), at) *
          glm::rotate(glm::mat4(1.0f), 6.2831853f * unit(rng), glm::vec3(0, 1, 0)) *
          glm::scale(glm::mat4(1.0f), glm::vec3(scale)) * glm::translate(glm::mat4(1.0f), -glm::vec3(g.boundsSphere));
    }
    scene.data.instances.push_back(makeInstance(m, 0, closed));
  }
  for (size_t i : {size_t(0), scene.data.instances.size() - 1}) {  // the layout's corners
    if (i >= scene.data.instances.size()) continue;
    const auto& inst = scene.data.instances[i];
    const std::string problem = instanceProblem(inst, g);
    if (!problem.empty()) throw std::runtime_error(std::to_string(count) + " instances laid out: one " + problem);
  }
  finishScene(scene);
  return scene;
}

RenderScene loadRenderScene(const std::string& path, uint32_t grid) {
  RenderScene scene;
  std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".json")
    scene = loadSceneFile(path);
  else
    scene.data = readVgeo(path);
  if (scene.data.instances.empty()) throw InputError(path, "the scene has no instances");
  finishScene(scene);
  if (grid > 1) {
    if (uint64_t(grid) * grid * scene.data.instances.size() > kMaxSceneInstances)
      throw InputError(path, "a grid of " + std::to_string(grid) + " x " + std::to_string(grid) + " copies of " +
                                 std::to_string(scene.data.instances.size()) + " instances is more than " +
                                 std::to_string(kMaxSceneInstances) + " instances");
    // N x N copies of the whole scene on the x-z plane, with a quarter of its diameter between copies.
    float spacing = 2.5f * scene.bounds.w;
    std::vector<shaderio::Instance> original = scene.data.instances;
    auto offset = [&](uint32_t x, uint32_t z) {
      return glm::translate(glm::mat4(1.0f), glm::vec3((float(x) - 0.5f * float(grid - 1)) * spacing, 0.0f,
                                                       (float(z) - 0.5f * float(grid - 1)) * spacing));
    };
    for (uint32_t corner : {0u, grid - 1})  // the grid's corners, before any copy is made
      for (const auto& inst : original) {
        const std::string problem =
            instanceProblem(makeInstance(offset(corner, corner) * instanceMatrix(inst), inst.geometry, false),
                            scene.data.geometries[inst.geometry]);
        if (!problem.empty())
          throw InputError(path, "a grid of " + std::to_string(grid) + " puts an instance that " + problem);
      }
    scene.data.instances.clear();
    scene.data.instances.reserve(size_t(grid) * grid * original.size());
    for (uint32_t z = 0; z < grid; z++)
      for (uint32_t x = 0; x < grid; x++)
        for (const auto& inst : original)
          scene.data.instances.push_back(
              makeInstance(offset(x, z) * instanceMatrix(inst), inst.geometry,
                           scene.data.geometries[inst.geometry].flags & VGEO_GEOMETRY_CLOSED));
    finishScene(scene);
  }
  return scene;
}

}  // namespace vgeo
