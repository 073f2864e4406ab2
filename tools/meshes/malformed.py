#!/usr/bin/env python3
"""Writes the small MSH 4.1 files of tests/data/msh/: one valid body (ok.msh, a 2 x 1
rectangle in four triangles) and one file per refusal of the mesh reader (src/msh.rs)
or of the mesh scene (src/body.rs). Plain text, written by hand so that each file
holds exactly the fault it tests (Gmsh would not write most of them). Every file of
tests/data/msh seeds the fuzz corpus (fuzz/corpus/msh/).

Usage: python3 tools/meshes/malformed.py
"""
import os
import shutil

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "..", "tests", "data", "msh")
CORPUS = os.path.join(HERE, "..", "..", "fuzz", "corpus", "msh")

# The rectangle (0,2) x (0,1): nodes 1..6, triangles counter-clockwise.
NODES = [(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (2, 1)]
TRIS = [(1, 2, 5), (1, 5, 4), (2, 3, 6), (2, 6, 5)]
GROUPS = {
    "bottom": [(1, 2), (2, 3)],
    "top": [(4, 5), (5, 6)],
    "left": [(1, 4)],
    "right": [(3, 6)],
}


def msh(nodes=NODES, blocks=None, groups=GROUPS, version="4.1"):
    """blocks: [(dim, entity, type, [node tuples])]; the surface's triangles by default."""
    if blocks is None:
        blocks = [(2, 1, 2, TRIS)]
    lines = ["$MeshFormat", f"{version} 0 8", "$EndMeshFormat"]
    names = list(groups)
    lines += ["$PhysicalNames", str(len(names) + 1)]
    lines += [f'1 {i + 1} "{n}"' for i, n in enumerate(names)]
    lines += [f'2 {len(names) + 1} "body"', "$EndPhysicalNames"]
    xs = [p[0] for p in nodes]
    ys = [p[1] for p in nodes]
    box = f"{min(xs)} {min(ys)} 0 {max(xs)} {max(ys)} 0"
    lines += ["$Entities", f"0 {len(names)} 1 0"]
    lines += [f"{i + 1} {box} 1 {i + 1} 0" for i in range(len(names))]
    lines += [f"1 {box} 1 {len(names) + 1} 0", "$EndEntities"]
    n = len(nodes)
    lines += ["$Nodes", f"1 {n} 1 {n}", f"2 1 0 {n}"]
    lines += [str(i + 1) for i in range(n)]
    lines += [f"{x} {y} 0" for x, y in nodes]
    lines += ["$EndNodes"]
    all_blocks = list(blocks) + [(1, i + 1, 1, groups[g]) for i, g in enumerate(names)]
    count = sum(len(b[3]) for b in all_blocks)
    lines += ["$Elements", f"{len(all_blocks)} {count} 1 {count}"]
    tag = 1
    for dim, ent, ty, elems in all_blocks:
        lines.append(f"{dim} {ent} {ty} {len(elems)}")
        for e in elems:
            lines.append(" ".join(str(v) for v in (tag,) + tuple(e)))
            tag += 1
    lines += ["$EndElements", ""]
    return "\n".join(lines)


FILES = {
    "ok.msh": msh(),
    # A quadrangle (type 3) beside the triangles.
    "quadrangle.msh": msh(blocks=[(2, 1, 2, TRIS), (2, 1, 3, [(1, 2, 5, 4)])]),
    # Second-order triangles (type 9, six nodes).
    "second_order.msh": msh(blocks=[(2, 1, 9, [(1, 2, 5, 2, 5, 1)])]),
    # A tetrahedron (type 4) on a volume.
    "tetrahedron.msh": msh(blocks=[(2, 1, 2, TRIS), (3, 1, 4, [(1, 2, 4, 5)])]),
    # A triangle whose three nodes lie on the bottom.
    "zero_area.msh": msh(blocks=[(2, 1, 2, TRIS + [(1, 2, 3)])]),
    # A fifth triangle over the first: two triangles on the same side of edge 1-2.
    "tangled.msh": msh(blocks=[(2, 1, 2, TRIS + [(1, 2, 4)])]),
    # A second piece, away from the rectangle.
    "two_pieces.msh": msh(
        nodes=NODES + [(5, 0), (6, 0), (5, 1)],
        blocks=[(2, 1, 2, TRIS + [(7, 8, 9)])],
    ),
    # A group edge across the body (the diagonal 1-5).
    "inner_group.msh": msh(groups=dict(GROUPS, inner=[(1, 5)])),
    # The contact part "bottom" and the part "clamped" share the edge 1-2.
    "contact_clamp_overlap.msh": msh(groups=dict(GROUPS, clamped=[(1, 2), (1, 4)])),
    # A slanted part: rollers there are refused.
    "slanted.msh": msh(
        nodes=[(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (3, 1)],
        groups=dict(GROUPS, right=[(3, 6)]),
    ),
    # MSH 2.2 (the old format).
    "version_2.msh": msh(version="2.2"),
    # Not an MSH file at all.
    "not_msh.msh": "solid body\nfacet normal 0 0 1\nendsolid\n",
    # Cut short inside the nodes.
    "truncated.msh": msh()[:400],
    # No elements section: never meshed.
    "no_elements.msh": msh().split("$Elements")[0],
}


def main():
    os.makedirs(OUT, exist_ok=True)
    os.makedirs(CORPUS, exist_ok=True)
    for name, text in FILES.items():
        with open(os.path.join(OUT, name), "w") as f:
            f.write(text)
    # Every test file seeds the corpus, the binary paper mesh too
    # (tools/meshes/paper_mesh.py --binary --out tests/data/msh/paper_n16_binary.msh).
    for name in sorted(os.listdir(OUT)):
        shutil.copy(os.path.join(OUT, name), os.path.join(CORPUS, name))
    print(f"wrote {len(FILES)} files to {OUT}; copied its files to {CORPUS}")


if __name__ == "__main__":
    main()
