#!/usr/bin/env python3
"""Writes data/meshes/paper_n16.msh: the paper's rectangle (0,2) x (0,1) triangulated
exactly as evhi's built-in structured mesh of level n = 16 (src/mesh.rs, Mesh::build
with the paper's diagonal pattern): the same nodes in the same order, the same
triangles, with the boundary groups a mesh scene names.

Nodes: node j*(n+1)+i (0-based) at (i*2/n, j*2/n), i = 0..n, j = 0..n/2.
Triangles: each cell [ll, lr, ur] then [ll, ur, ul], cells row by row.
Groups (curves): "bottom" (y = 0, the contact boundary), "top" (y = 1), "clamped"
(x = 0 and x = 2 with y >= 1/2, the paper's Gamma_1), "free" (x = 0 and x = 2 with
y <= 1/2); the surface is the group "body".

Usage: python3 -m venv /tmp/gmsh-venv && /tmp/gmsh-venv/bin/pip install gmsh
       /tmp/gmsh-venv/bin/python tools/meshes/paper_mesh.py [--n 16] [--binary] [--out FILE]
The tests read the committed .msh and need no Gmsh.
"""
import argparse
import os

import gmsh


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=16)
    ap.add_argument("--binary", action="store_true")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    n = a.n
    assert n > 0 and n % 4 == 0, "n must be a positive multiple of 4"
    nx, ny = n, n // 2
    side = 2.0 / n
    out = a.out or os.path.join(
        os.path.dirname(__file__), "..", "..", "data", "meshes", f"paper_n{n}.msh"
    )

    def node(i, j):  # 1-based Gmsh tag of evhi's node j*(nx+1)+i
        return j * (nx + 1) + i + 1

    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add(f"paper_n{n}")
    surf = gmsh.model.addDiscreteEntity(2)
    coords, tags = [], []
    for j in range(ny + 1):
        for i in range(nx + 1):
            tags.append(node(i, j))
            coords += [i * side, j * side, 0.0]
    gmsh.model.mesh.addNodes(2, surf, tags, coords)
    tris = []
    for j in range(ny):
        for i in range(nx):
            ll, lr, ur, ul = node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)
            tris += [ll, lr, ur, ll, ur, ul]
    gmsh.model.mesh.addElementsByType(surf, 2, [], tris)

    half = ny // 2
    parts = {
        "bottom": [(node(i, 0), node(i + 1, 0)) for i in range(nx)],
        "top": [(node(i, ny), node(i + 1, ny)) for i in range(nx)],
        "clamped": [(node(0, j), node(0, j + 1)) for j in range(half, ny)]
        + [(node(nx, j), node(nx, j + 1)) for j in range(half, ny)],
        "free": [(node(0, j), node(0, j + 1)) for j in range(half)]
        + [(node(nx, j), node(nx, j + 1)) for j in range(half)],
    }
    for name, edges in parts.items():
        curve = gmsh.model.addDiscreteEntity(1)
        gmsh.model.mesh.addElementsByType(curve, 1, [], [v for e in edges for v in e])
        gmsh.model.addPhysicalGroup(1, [curve], name=name)
    gmsh.model.addPhysicalGroup(2, [surf], name="body")

    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1 if a.binary else 0)
    gmsh.write(out)
    gmsh.finalize()
    print(f"wrote {out}: {len(tags)} nodes, {len(tris) // 3} triangles")


if __name__ == "__main__":
    main()
