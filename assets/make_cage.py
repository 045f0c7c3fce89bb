#!/usr/bin/env python3
"""Writes vgeo's default control cage, assets/horned_cube.obj: a cube of 3x3 quads a side whose nine
faces each grow a twisted, tapering horn. All faces are quads; the cube corners are extraordinary
(valence 3) and the horn bases add valence-5 vertices, so Catmull-Clark shows both regular and
extraordinary patches. Generated here, so it carries no third-party licence.

Usage: python3 assets/make_cage.py [OUT.obj]
"""
import math
import sys


def cube(n):
    """Quads of a cube [-1,1]^3 with n x n quads a side, outward-facing, shared vertices."""
    verts, index = [], {}

    def vid(p):
        key = tuple(round(c * n) for c in p)
        if key not in index:
            index[key] = len(verts)
            verts.append(list(p))
        return index[key]

    faces = []
    for axis in range(3):
        for sign in (-1, 1):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            for i in range(n):
                for j in range(n):
                    corners = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = [0.0, 0.0, 0.0]
                        p[axis] = sign
                        p[u] = -1 + 2 * (i + di) / n
                        p[v] = -1 + 2 * (j + dj) / n
                        corners.append(vid(p))
                    if sign < 0:
                        corners.reverse()
                    faces.append(corners)
    return verts, faces


def extrude(verts, faces, f, height, scale, twist):
    """Replaces face f by a ring of 4 side quads and a smaller, twisted top: one horn segment."""
    quad = faces[f]
    pts = [verts[i] for i in quad]
    centre = [sum(p[k] for p in pts) / 4 for k in range(3)]
    a = [pts[1][k] - pts[0][k] for k in range(3)]
    b = [pts[2][k] - pts[0][k] for k in range(3)]
    normal = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    length = math.sqrt(sum(c * c for c in normal))
    normal = [c / length for c in normal]
    top = []
    c, s = math.cos(twist), math.sin(twist)
    for p in pts:
        d = [p[k] - centre[k] for k in range(3)]
        # Rodrigues rotation of d about the normal by `twist`.
        cross = [normal[1] * d[2] - normal[2] * d[1], normal[2] * d[0] - normal[0] * d[2], normal[0] * d[1] - normal[1] * d[0]]
        dot = sum(normal[k] * d[k] for k in range(3))
        r = [d[k] * c + cross[k] * s + normal[k] * dot * (1 - c) for k in range(3)]
        top.append(len(verts))
        verts.append([centre[k] + normal[k] * height + r[k] * scale for k in range(3)])
    for i in range(4):
        j = (i + 1) % 4
        faces.append([quad[i], quad[j], top[j], top[i]])
    faces[f] = top
    return f


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "assets/horned_cube.obj"
    verts, faces = cube(3)
    # The centre quad of each side and the four quads at its corners grow horns; centres grow longest.
    for f in range(len(faces)):
        i, j = (f % 9) // 3, f % 3
        if (i, j) == (1, 1):
            segments, height = 4, 0.45
        elif i != 1 and j != 1:
            segments, height = 2, 0.25
        else:
            continue
        face = f
        for k in range(segments):
            face = extrude(verts, faces, face, height * (0.85 ** k), 0.72, 0.35)
    with open(out, "w") as obj:
        obj.write("# vgeo default cage: horned cube, %d vertices, %d quads (assets/make_cage.py)\n" % (len(verts), len(faces)))
        for v in verts:
            obj.write("v %.6f %.6f %.6f\n" % tuple(v))
        for f in faces:
            obj.write("f %s\n" % " ".join(str(i + 1) for i in f))


if __name__ == "__main__":
    main()
