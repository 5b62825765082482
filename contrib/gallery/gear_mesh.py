#!/usr/bin/python3
"""Write the 2D gear of prm/gallery_gear.prm as a Gmsh 4.1 ASCII mesh (an
example of a body from a mesh file, Shape = mesh): a fan of triangles
around the centre, rings of quadrilaterals out to the root circle, and an
outer ring of quadrilaterals whose outer nodes follow the teeth.

Usage: contrib/gallery/gear_mesh.py [FILE] [--teeth 12] [--root 0.8]
FILE defaults to gear.msh in the current directory. The gear's tip radius
is 1 (the scene scales it with 'Mesh scale'); --root is the root radius."""
import argparse
import math

SEGMENTS_PER_TOOTH = 8  # four on the tip, four in the gap; the flanks join them


def gear(teeth, root, rings=3):
    """Nodes (x, y) and cells (Gmsh type, 0-based node indices)."""
    n = teeth * SEGMENTS_PER_TOOTH
    angle = [2 * math.pi * (i + 0.5) / n for i in range(n)]
    nodes = [(0.0, 0.0)]
    # rings of radius root * (k + 1) / (rings + 1), the last one inside the
    # root circle so that the outer ring has no flat cells in the gaps
    radii = [root * (k + 1) / (rings + 1) for k in range(rings + 1)]
    for r in radii:
        nodes += [(r * math.cos(a), r * math.sin(a)) for a in angle]
    tip = [1.0 if (i % SEGMENTS_PER_TOOTH) >= SEGMENTS_PER_TOOTH // 2 else root + 0.25 * (1 - root)
           for i in range(n)]
    nodes += [(t * math.cos(a), t * math.sin(a)) for t, a in zip(tip, angle)]

    def ring(k, i):
        return 1 + k * n + i % n

    cells = [(2, (0, ring(0, i), ring(0, i + 1))) for i in range(n)]
    for k in range(len(radii)):
        cells += [(3, (ring(k, i), ring(k + 1, i), ring(k + 1, i + 1), ring(k, i + 1))) for i in range(n)]
    return nodes, cells


def write_msh(path, nodes, cells):
    with open(path, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        xs, ys = [x for x, _ in nodes], [y for _, y in nodes]
        f.write(f"$Entities\n0 0 1 0\n1 {min(xs)!r} {min(ys)!r} 0 {max(xs)!r} {max(ys)!r} 0 1 1 0\n$EndEntities\n")
        f.write(f"$Nodes\n1 {len(nodes)} 1 {len(nodes)}\n2 1 0 {len(nodes)}\n")
        f.write("".join(f"{i + 1}\n" for i in range(len(nodes))))
        f.write("".join(f"{x:.12g} {y:.12g} 0\n" for x, y in nodes))
        f.write("$EndNodes\n")
        blocks = [(t, [c for c in cells if c[0] == t]) for t in (2, 3)]
        f.write(f"$Elements\n{len(blocks)} {len(cells)} 1 {len(cells)}\n")
        tag = 1
        for t, block in blocks:
            f.write(f"2 1 {t} {len(block)}\n")
            for _, vertices in block:
                f.write(f"{tag} " + " ".join(str(v + 1) for v in vertices) + "\n")
                tag += 1
        f.write("$EndElements\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", nargs="?", default="gear.msh")
    parser.add_argument("--teeth", type=int, default=12)
    parser.add_argument("--root", type=float, default=0.8)
    args = parser.parse_args()
    if args.teeth < 3 or not 0 < args.root < 1:
        raise SystemExit("gear_mesh.py: --teeth must be >= 3 and --root in (0, 1)")
    write_msh(args.file, *gear(args.teeth, args.root))
    print(f"wrote {args.file}")


if __name__ == "__main__":
    main()
