// cages.h: small control cages the tests generate, each showing one kind of Catmull-Clark patch.
#pragma once

#include <cmath>
#include <string>

#include "test_util.h"

namespace vgeo::test {

inline std::string vertexLine(double x, double y, double z) {
  return "v " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
}

// A cube of six quads: after one round every face is a ring around a valence-3 corner.
inline std::string cubeCage(const std::string& dir) {
  return writeFile(dir, "cube.obj",
                   "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                   "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
}

// A hexagonal prism of two hexagons and six quads: after one round its hexagons' face points have
// valence 6 and its corners valence 3.
inline std::string hexagonalPrism(const std::string& dir) {
  std::string obj;
  for (int z = 0; z < 2; z++)
    for (int i = 0; i < 6; i++)
      obj += "v " + std::to_string(std::cos(i * 1.0471976)) + " " + std::to_string(std::sin(i * 1.0471976)) + " " +
             std::to_string(z * 1.3) + "\n";
  obj += "f 6 5 4 3 2 1\nf 7 8 9 10 11 12\n";
  for (int i = 0; i < 6; i++) {
    int a = i + 1, b = (i + 1) % 6 + 1;
    obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(b + 6) + " " +
           std::to_string(a + 6) + "\n";
  }
  return writeFile(dir, "hexagonal_prism.obj", obj);
}

// A box without its top: its rim is a boundary whose cube corners have two faces (regular there), its
// bottom corners are interior of valence 3.
inline std::string openBox(const std::string& dir) {
  std::string obj;
  for (int i = 0; i < 8; i++) obj += vertexLine(i & 1 ? 1.0 : -1.0, i & 2 ? 1.2 : -1.2, i & 4 ? 0.9 : -0.9);
  obj += "f 1 3 4 2\nf 1 2 6 5\nf 2 4 8 6\nf 4 3 7 8\nf 3 1 5 7\n";
  return writeFile(dir, "open_box.obj", obj);
}

// Three quads of a curved 2 x 2 sheet, an L: its inner corner is a boundary vertex of three faces
// (extraordinary), its outer corners have one face (corners, which stay put).
inline std::string lSheet(const std::string& dir) {
  std::string obj;
  for (int y = 0; y < 3; y++)
    for (int x = 0; x < 3; x++)
      obj += vertexLine(x, y, 0.4 * std::sin(1.3 * x) * std::cos(0.9 * y) + 0.2 * (x == 1 && y == 1));
  obj += "f 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\n";
  return writeFile(dir, "l_sheet.obj", obj);
}

// A fan of five triangles around a raised centre (open, rim of boundary vertices with two faces), and
// a tetrahedron (closed): after one round every face has two extraordinary corners or one and a
// boundary (face points of valence 3, the fan's centre of valence 5, the tetrahedron's corners of 3).
inline std::string triangleFan(const std::string& dir) {
  std::string obj = vertexLine(0.0, 0.0, 0.7);
  for (int i = 0; i < 5; i++) obj += vertexLine(std::cos(i * 1.2566371), std::sin(i * 1.2566371), 0.15 * (i % 2));
  for (int i = 0; i < 5; i++) obj += "f 1 " + std::to_string(i + 2) + " " + std::to_string((i + 1) % 5 + 2) + "\n";
  return writeFile(dir, "triangle_fan.obj", obj);
}

inline std::string tetrahedron(const std::string& dir) {
  std::string obj = vertexLine(1, 1, 1) + vertexLine(1, -1, -1) + vertexLine(-1, 1, -1) + vertexLine(-1, -1, 1.4);
  obj += "f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";
  return writeFile(dir, "tetrahedron.obj", obj);
}

}  // namespace vgeo::test
