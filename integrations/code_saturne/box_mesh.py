#!/usr/bin/env python3
"""Writes a box of hexahedra as a Gmsh 2.2 ASCII mesh, which Code_Saturne's preprocessor reads.

    box_mesh.py OUT.msh LX LY LZ NX NY NZ

The box spans [0, LX] x [0, LY] x [0, LZ] m in NX x NY x NZ cells. Boundary faces carry
physical groups, named for Gmsh and numbered for Code_Saturne 6.0 (whose preprocessor names a
Gmsh mesh's groups by their numbers):

    1 floor (z = 0)   2 ceiling (z = LZ)   3 sides (y = 0 and y = LY)
    4 start (x = 0)   5 end (x = LX)       6 the cells
"""
import sys


def main(out, lx, ly, lz, nx, ny, nz):
    def node(i, j, k):
        return 1 + i + (nx + 1) * (j + (ny + 1) * k)

    nodes = [
        (node(i, j, k), lx * i / nx, ly * j / ny, lz * k / nz)
        for k in range(nz + 1)
        for j in range(ny + 1)
        for i in range(nx + 1)
    ]
    groups = {"floor": 1, "ceiling": 2, "sides": 3, "start": 4, "end": 5, "air": 6}
    elements = []  # (gmsh type, physical group, node ids)
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                bottom = [node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k)]
                top = [node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)]
                elements.append((5, groups["air"], bottom + top))
    # Boundary quadrangles, each ordered with its normal pointing out of the box.
    for j in range(ny):
        for i in range(nx):
            elements.append((3, groups["floor"], [node(i, j, 0), node(i, j + 1, 0), node(i + 1, j + 1, 0), node(i + 1, j, 0)]))
            elements.append((3, groups["ceiling"], [node(i, j, nz), node(i + 1, j, nz), node(i + 1, j + 1, nz), node(i, j + 1, nz)]))
    for k in range(nz):
        for j in range(ny):
            elements.append((3, groups["start"], [node(0, j, k), node(0, j, k + 1), node(0, j + 1, k + 1), node(0, j + 1, k)]))
            elements.append((3, groups["end"], [node(nx, j, k), node(nx, j + 1, k), node(nx, j + 1, k + 1), node(nx, j, k + 1)]))
        for i in range(nx):
            elements.append((3, groups["sides"], [node(i, 0, k), node(i + 1, 0, k), node(i + 1, 0, k + 1), node(i, 0, k + 1)]))
            elements.append((3, groups["sides"], [node(i, ny, k), node(i, ny, k + 1), node(i + 1, ny, k + 1), node(i + 1, ny, k)]))

    with open(out, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write(f"$PhysicalNames\n{len(groups)}\n")
        for name, tag in groups.items():
            f.write(f'{3 if name == "air" else 2} {tag} "{name}"\n')
        f.write("$EndPhysicalNames\n")
        f.write(f"$Nodes\n{len(nodes)}\n")
        for n, x, y, z in nodes:
            f.write(f"{n} {x:.17g} {y:.17g} {z:.17g}\n")
        f.write("$EndNodes\n")
        f.write(f"$Elements\n{len(elements)}\n")
        for e, (kind, group, ids) in enumerate(elements, start=1):
            f.write(f"{e} {kind} 2 {group} {group} {' '.join(map(str, ids))}\n")
        f.write("$EndElements\n")


if __name__ == "__main__":
    if len(sys.argv) != 8:
        sys.exit(__doc__)
    out = sys.argv[1]
    lx, ly, lz = map(float, sys.argv[2:5])
    nx, ny, nz = map(int, sys.argv[5:8])
    main(out, lx, ly, lz, nx, ny, nz)
