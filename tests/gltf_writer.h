// gltf_writer.h: glTF files the tests make from meshes, for the loader's paths that no public sample
// takes (mirrored nodes, normals or none).
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "test_util.h"

namespace vgeo::test {

// Base64 of bytes, for a glTF buffer given as a data URI.
inline std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t v =
        uint32_t(bytes[i]) << 16 | (n > 1 ? uint32_t(bytes[i + 1]) << 8 : 0u) | (n > 2 ? uint32_t(bytes[i + 2]) : 0u);
    out += table[v >> 18 & 63];
    out += table[v >> 12 & 63];
    out += n > 1 ? table[v >> 6 & 63] : '=';
    out += n > 2 ? table[v & 63] : '=';
  }
  return out;
}

// A glTF of `mesh` (each face a fan) under one node with the JSON properties `node` (e.g.
// R"(, "scale": [-1, 1, 1])"). With corner normals, each corner becomes a vertex of its own with its
// normal as NORMAL (as exporters write hard edges); without, vertices are shared and there is no NORMAL.
// The buffer is a data URI: one file, nothing beside it.
inline std::string gltfOf(const std::string& dir, const std::string& name, const PolygonMesh& mesh,
                          const std::string& node) {
  const bool withNormals = !mesh.cornerNormals.empty();
  std::vector<float> positions, normals;
  std::vector<uint32_t> indices;
  glm::vec3 lo(1e30f), hi(-1e30f);
  auto addPosition = [&](glm::vec3 p) {
    positions.insert(positions.end(), {p.x, p.y, p.z});
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  if (!withNormals) {
    for (const glm::vec3& p : mesh.positions) addPosition(p);
    for (size_t f = 0; f < mesh.faceCount(); f++)
      for (uint32_t k = 2; k < mesh.faceSize(f); k++)
        indices.insert(indices.end(), {mesh.face(f)[0], mesh.face(f)[k - 1], mesh.face(f)[k]});
  } else {
    for (size_t f = 0; f < mesh.faceCount(); f++) {
      const uint32_t first = uint32_t(positions.size() / 3);
      for (uint32_t k = 0; k < mesh.faceSize(f); k++) {
        addPosition(mesh.positions[mesh.face(f)[k]]);
        const glm::vec3 n = mesh.faceNormals(f)[k];
        normals.insert(normals.end(), {n.x, n.y, n.z});
      }
      for (uint32_t k = 2; k < mesh.faceSize(f); k++) indices.insert(indices.end(), {first, first + k - 1, first + k});
    }
  }
  const size_t p = positions.size() * 4, n = normals.size() * 4, i = indices.size() * 4;
  std::vector<uint8_t> bytes(p + n + i);
  std::memcpy(bytes.data(), positions.data(), p);
  if (n) std::memcpy(bytes.data() + p, normals.data(), n);
  std::memcpy(bytes.data() + p + n, indices.data(), i);
  auto vec = [](glm::vec3 v) {
    char text[96];
    std::snprintf(text, sizeof text, "[%.9g, %.9g, %.9g]", v.x, v.y, v.z);
    return std::string(text);
  };
  const std::string vertices = std::to_string(positions.size() / 3);
  std::string json =
      R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0)" + node + R"(}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0)" +
      std::string(n ? R"(, "NORMAL": 2)" : "") + R"(}, "indices": 1}]}],
    "buffers": [{"byteLength": )" +
      std::to_string(bytes.size()) + R"(, "uri": "data:application/octet-stream;base64,)" + base64(bytes) + R"("}],
    "bufferViews": [{"buffer": 0, "byteLength": )" +
      std::to_string(p) + R"(},
                    {"buffer": 0, "byteOffset": )" +
      std::to_string(p + n) + R"(, "byteLength": )" + std::to_string(i) + "}" +
      (n ? R"(, {"buffer": 0, "byteOffset": )" + std::to_string(p) + R"(, "byteLength": )" + std::to_string(n) + "}"
         : std::string()) +
      R"(],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" +
      vertices + R"(, "type": "VEC3", "min": )" + vec(lo) + R"(, "max": )" + vec(hi) + R"(},
                  {"bufferView": 1, "componentType": 5125, "count": )" +
      std::to_string(indices.size()) + R"(, "type": "SCALAR"})" +
      (n ? R"(, {"bufferView": 2, "componentType": 5126, "count": )" + vertices + R"(, "type": "VEC3"})"
         : std::string()) +
      "]}";
  return writeFile(dir, name, json);
}

}  // namespace vgeo::test
