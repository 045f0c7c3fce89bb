// bounds.cpp: smallest enclosing spheres (CGAL's Min_sphere_of_spheres_d: Fischer & Gaertner's
// algorithm, exact up to floating point) of points and of spheres, and a cluster's bounds for the file.
// The float sphere is made to enclose every input for certain: the radius is recomputed in double around
// the float centre and rounded up, so the containment invariants hold when checked in float or double,
// not merely approximately.
#include <CGAL/Min_sphere_of_spheres_d.h>
#include <CGAL/Min_sphere_of_spheres_d_traits_3.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>

#include "builder.h"

namespace vgeo {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Traits = CGAL::Min_sphere_of_spheres_d_traits_3<Kernel, double, CGAL::Tag_true>;
using MinSphere = CGAL::Min_sphere_of_spheres_d<Traits>;

glm::vec4 roundOutward(MinSphere& ms, const glm::dvec4* spheres, size_t count) {
  auto it = ms.center_cartesian_begin();
  double c[3];
  for (int i = 0; i < 3; i++, ++it) c[i] = *it;
  const glm::vec3 center{float(c[0]), float(c[1]), float(c[2])};
  double radius = 0.0;
  for (size_t i = 0; i < count; i++)
    radius = std::max(radius, glm::distance(glm::dvec3(center), glm::dvec3(spheres[i])) + spheres[i].w);
  float r = float(radius);
  while (double(r) < radius) r = std::nextafter(r, INFINITY);
  return glm::vec4(center, r);
}

glm::vec4 enclose(const std::vector<glm::dvec4>& spheres) {
  if (spheres.empty()) return glm::vec4(0.0f);
  std::vector<Traits::Sphere> input;
  input.reserve(spheres.size());
  for (const auto& s : spheres) input.emplace_back(Kernel::Point_3(s.x, s.y, s.z), s.w);
  MinSphere ms(input.begin(), input.end());
  return roundOutward(ms, spheres.data(), spheres.size());
}

// The cone of the triangles' unit normals (ClusterBounds::cone).
glm::vec4 normalCone(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions) {
  std::vector<glm::dvec3> normals;
  glm::dvec3 sum(0.0);
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    glm::dvec3 a(positions[indices[t]]), b(positions[indices[t + 1]]), c(positions[indices[t + 2]]);
    glm::dvec3 n = glm::cross(b - a, c - a);
    double len = glm::length(n);
    if (len == 0.0) continue;  // degenerate: faces nowhere, culling it is harmless
    normals.push_back(n / len);
    sum += n / len;
  }
  double len = glm::length(sum);
  if (normals.empty() || len < 1e-9) return glm::vec4(0.0f, 0.0f, 1.0f, -1.0f);
  glm::dvec3 axis = sum / len;
  double minCos = 1.0;
  for (const auto& n : normals) minCos = std::min(minCos, glm::dot(axis, n));
  if (minCos <= 0.02) return glm::vec4(glm::vec3(axis), -1.0f);
  double sine = std::sqrt(std::max(0.0, 1.0 - minCos * minCos));
  // Rounded up a little so that float tests never cull a cluster that has a triangle facing the eye.
  return glm::vec4(glm::vec3(axis), float(std::min(1.0, sine * 1.0001 + 1e-6)));
}

}  // namespace

glm::vec4 sphereOfPoints(const std::vector<glm::vec3>& positions, const uint32_t* vertices, size_t count) {
  std::vector<glm::dvec4> spheres(count);
  for (size_t i = 0; i < count; i++) spheres[i] = glm::dvec4(glm::dvec3(positions[vertices[i]]), 0.0);
  return enclose(spheres);
}

glm::vec4 sphereOfSpheres(const glm::vec4* spheres, size_t count) {
  std::vector<glm::dvec4> input(spheres, spheres + count);
  return enclose(input);
}

ClusterBounds clusterBounds(const BuildCluster& c, const std::vector<glm::vec3>& positions,
                            const ShadingNormals* shading) {
  ClusterBounds b;
  b.cone = normalCone(c.indices, positions);
  const std::vector<uint32_t>& ids = c.wedges.empty() ? c.indices : c.wedges;
  if (c.level == 0) {
    b.sphere = c.selfSphere;
    b.vertexCount = uint32_t(distinctCount(ids));
    return b;
  }
  std::vector<uint32_t> own, local;
  localIds(ids, own, local);
  b.vertexCount = uint32_t(own.size());
  if (shading)
    for (uint32_t& v : own) v = shading->wedgeVertex[v];  // the wedges' positions
  b.sphere = sphereOfPoints(positions, own.data(), own.size());
  return b;
}

}  // namespace vgeo
