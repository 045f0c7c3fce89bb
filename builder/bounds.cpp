// bounds.cpp: smallest enclosing spheres (CGAL's Min_sphere_of_spheres_d: Fischer & Gaertner's
// algorithm, exact up to floating point) of points and of spheres. The float result is made to enclose
// every input for certain: the radius is recomputed in double around the float centre and rounded up,
// so the containment invariants hold when checked in float or double, not merely approximately.
#include <CGAL/Min_sphere_of_spheres_d.h>
#include <CGAL/Min_sphere_of_spheres_d_traits_3.h>
#include <CGAL/Simple_cartesian.h>

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

}  // namespace vgeo
