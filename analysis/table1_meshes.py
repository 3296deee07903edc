#!/usr/bin/env python3
"""The objects of 000's Table 1 (per-object PAN of [CZJ12]'s plate, mug, dice and coin) as closed
triangle meshes for `clatter-bank pan-object` (docs/pan.md "Table 1"). Sizes are those of the
everyday objects; pan-object scales each to a bounding radius of 0.5 m, so only the shape counts:

  die          a 16 mm cube (mirror-symmetric: one octant)
  rounded-die  the same cube with its edges and corners rounded to 2 mm (one octant)
  coin         a disc 24.26 mm across, 1.75 mm thick (a US quarter; one octant)
  plate        a dinner plate 27 cm across: a shallow dish 4 mm thick (no mirror plane z = 0: eight)
  mug          a cup 8 cm across and 9.5 cm tall, 4 mm walls, with a torus handle overlapping its
               wall (two closed components; pan-object takes the union by winding number: eight)

  analysis/table1_meshes.py OUT_DIR

Every mesh is closed and oriented outward (its signed volume is checked positive).
"""
import math
import os
import sys

import numpy as np


def write_obj(path, verts, faces):
    with open(path, "w") as f:
        for p in verts:
            f.write("v %.17g %.17g %.17g\n" % tuple(p))
        for t in faces:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))


def signed_volume(verts, faces):
    v = np.asarray(verts)
    t = np.asarray(faces)
    return float(np.einsum("ij,ij->i", v[t[:, 0]], np.cross(v[t[:, 1]], v[t[:, 2]])).sum() / 6)


def oriented(verts, faces):
    """The faces turned outward (positive signed volume) if they were not."""
    if signed_volume(verts, faces) < 0:
        faces = [(a, c, b) for a, b, c in faces]
    return verts, faces


def revolve(profile, segments):
    """The solid of revolution about z of a closed profile [(r, z), ...] that starts and ends on the
    axis (r = 0): those two points become poles."""
    assert profile[0][0] == 0 and profile[-1][0] == 0
    verts, faces, ring = [], [], []
    for r, z in profile:
        if r == 0:
            ring.append([len(verts)] * segments)
            verts.append((0.0, 0.0, z))
        else:
            ring.append([len(verts) + j for j in range(segments)])
            verts += [(r * math.cos(2 * math.pi * j / segments), r * math.sin(2 * math.pi * j / segments), z)
                      for j in range(segments)]
    for i in range(len(profile) - 1):
        a, b = ring[i], ring[i + 1]
        for j in range(segments):
            k = (j + 1) % segments
            if a[j] == a[k]:  # from a pole
                faces.append((a[j], b[k], b[j]))
            elif b[j] == b[k]:  # to a pole
                faces.append((a[j], a[k], b[j]))
            else:
                faces += [(a[j], a[k], b[k]), (a[j], b[k], b[j])]
    return oriented(verts, faces)


def cube(half_m, round_m, n):
    """A cube of half-side half_m, its faces n x n quads; round_m > 0 rounds its edges and corners
    to about that radius: the surface |x|^p + |y|^p + |z|^p = half_m^p, p = 2 half_m / round_m, its
    points found along the centre's rays. Each quad is four triangles about its centre, so the
    triangulation is mirror-symmetric like the solid (pan-object then solves one octant)."""
    p = 2.0 * half_m / round_m if round_m > 0 else None
    verts, faces, index = [], [], {}

    def vertex(q):
        key = tuple(round(c, 12) for c in q)
        if key not in index:
            x = np.array(q, dtype=float)
            s = (np.abs(x) ** p).sum() ** (1 / p) if p else 1.0
            index[key] = len(verts)
            verts.append(tuple(half_m * x / s))
        return index[key]

    for axis in range(3):
        for sign in (-1, 1):
            u, w = [a for a in range(3) if a != axis]

            def at(a, b):
                q = [0.0, 0.0, 0.0]
                q[axis] = sign
                q[u] = -1 + 2 * a / n
                q[w] = -1 + 2 * b / n
                return vertex(q)
            for i in range(n):
                for j in range(n):
                    c = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]
                    m = at(i + 0.5, j + 0.5)
                    faces += [(c[k], c[(k + 1) % 4], m) for k in range(4)]
    # Each triangle turned outward on its own (the solid is convex).
    v = np.asarray(verts)
    out = []
    for a, b, c in faces:
        normal = np.cross(v[b] - v[a], v[c] - v[a])
        out.append((a, b, c) if normal @ (v[a] + v[b] + v[c]) > 0 else (a, c, b))
    return verts, out


def torus(centre, major_m, minor_m, n_major, n_minor):
    """A torus in the x-z plane (its axis along y) around `centre`."""
    verts, faces = [], []
    for i in range(n_major):
        a = 2 * math.pi * i / n_major
        for j in range(n_minor):
            b = 2 * math.pi * j / n_minor
            r = major_m + minor_m * math.cos(b)
            verts.append((centre[0] + r * math.cos(a), centre[1] + minor_m * math.sin(b), centre[2] + r * math.sin(a)))
    for i in range(n_major):
        for j in range(n_minor):
            p, q = i * n_minor + j, ((i + 1) % n_major) * n_minor + j
            p1, q1 = i * n_minor + (j + 1) % n_minor, ((i + 1) % n_major) * n_minor + (j + 1) % n_minor
            faces += [(p, q, q1), (p, q1, p1)]
    return oriented(verts, faces)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    meshes = {}
    meshes["die"] = cube(0.008, 0.0, 8)
    meshes["rounded-die"] = cube(0.008, 0.002, 16)
    meshes["coin"] = revolve([(0, -0.000875), (0.01213, -0.000875), (0.01213, 0.000875), (0, 0.000875)], 96)
    meshes["plate"] = revolve([(0, 0.0), (0.08, 0.0), (0.12, 0.015), (0.135, 0.022), (0.135, 0.026), (0.118, 0.019),
                               (0.078, 0.004), (0, 0.004)], 128)
    cup = revolve([(0, 0.0), (0.04, 0.0), (0.04, 0.095), (0.036, 0.095), (0.036, 0.006), (0, 0.006)], 96)
    handle = torus((0.065, 0.0, 0.05), 0.022, 0.005, 48, 16)  # its inner edge at x = 0.038, in the wall
    n = len(cup[0])
    meshes["mug"] = (cup[0] + handle[0], cup[1] + [(a + n, b + n, c + n) for a, b, c in handle[1]])
    for name, (v, f) in meshes.items():
        path = os.path.join(out, name + ".obj")
        write_obj(path, v, f)
        print(f"{path}: {len(v)} vertices, {len(f)} triangles, volume {signed_volume(v, f) * 1e6:.3f} cm^3")


if __name__ == "__main__":
    main()
