#!/usr/bin/env python3
"""Writes data/meshes/hertz_<N>.msh: the right half of a half-cylinder of radius R = 1
(plane strain), the quarter disc x >= 0 of the disc centred at (0, R) below its flat
face y = R. It touches the foundation y = 0 at the origin. Graded towards the contact
zone: triangles of size h = 0.1 R / N (N elements across 0.1 R) within 1.2 A of the
origin, growing to R / 8 beyond 0.6 R. A is the largest contact half-width the mesh is
for: 0.1 R, or 0.2 R with --wide, which writes hertz_wide_<N>.msh (the Hertz
experiment's a/R = 0.2, where the finite body's offset is measured).

Groups (curves): "axis" (x = 0, the symmetry line: rollers), "flat" (y = R, the face
that is pressed), "contact" (the arc from the origin to the angle 0.5 rad, Gamma_3),
"arc" (the rest of the arc, traction free); the surface is the group "body".

Usage: python3 -m venv /tmp/gmsh-venv && /tmp/gmsh-venv/bin/pip install gmsh
       /tmp/gmsh-venv/bin/python tools/meshes/hertz.py [--n 12 25 50 100 200] [--ascii]
       /tmp/gmsh-venv/bin/python tools/meshes/hertz.py --wide --n 12 25 50
The tests and the experiment read the committed .msh files and need no Gmsh.
"""
import argparse
import math
import os

import gmsh

R = 1.0
H = 0.1 * R
THETA_CONTACT = 0.5


def mesh(n, reach, binary, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add(f"hertz_{n}")
    geo = gmsh.model.geo
    h = H / n
    origin = geo.addPoint(0.0, 0.0, 0.0)
    centre = geo.addPoint(0.0, R, 0.0)
    end_contact = geo.addPoint(
        R * math.sin(THETA_CONTACT), R - R * math.cos(THETA_CONTACT), 0.0
    )
    rim = geo.addPoint(R, R, 0.0)
    contact = geo.addCircleArc(origin, centre, end_contact)
    arc = geo.addCircleArc(end_contact, centre, rim)
    flat = geo.addLine(rim, centre)
    axis = geo.addLine(centre, origin)
    loop = geo.addCurveLoop([contact, arc, flat, axis])
    surf = geo.addPlaneSurface([loop])
    geo.synchronize()
    for dim, tags, name in [
        (1, [axis], "axis"),
        (1, [flat], "flat"),
        (1, [contact], "contact"),
        (1, [arc], "arc"),
        (2, [surf], "body"),
    ]:
        gmsh.model.addPhysicalGroup(dim, tags, name=name)

    dist = gmsh.model.mesh.field.add("Distance")
    gmsh.model.mesh.field.setNumbers(dist, "PointsList", [origin])
    thr = gmsh.model.mesh.field.add("Threshold")
    gmsh.model.mesh.field.setNumber(thr, "InField", dist)
    gmsh.model.mesh.field.setNumber(thr, "SizeMin", h)
    gmsh.model.mesh.field.setNumber(thr, "SizeMax", R / 8)
    gmsh.model.mesh.field.setNumber(thr, "DistMin", 1.2 * reach)
    gmsh.model.mesh.field.setNumber(thr, "DistMax", 0.6 * R)
    gmsh.model.mesh.field.setAsBackgroundMesh(thr)
    for opt in [
        "Mesh.MeshSizeExtendFromBoundary",
        "Mesh.MeshSizeFromPoints",
        "Mesh.MeshSizeFromCurvature",
    ]:
        gmsh.option.setNumber(opt, 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.ElementOrder", 1)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1 if binary else 0)
    gmsh.option.setNumber("Mesh.SaveAll", 0)
    gmsh.write(out)
    ntri = sum(len(t) for t in gmsh.model.mesh.getElementsByType(2)[0:1])
    gmsh.finalize()
    return ntri


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, nargs="+", default=[12, 25, 50, 100, 200])
    ap.add_argument("--wide", action="store_true", help="fine up to 1.2 * 0.2 R")
    ap.add_argument("--ascii", action="store_true")
    a = ap.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    reach, stem = (0.2 * R, "hertz_wide") if a.wide else (0.1 * R, "hertz")
    for n in a.n:
        out = os.path.join(here, "..", "..", "data", "meshes", f"{stem}_{n}.msh")
        ntri = mesh(n, reach, not a.ascii, out)
        print(f"{os.path.normpath(out)}: {ntri} triangles, h = {H / n:g} at the contact")


if __name__ == "__main__":
    main()
