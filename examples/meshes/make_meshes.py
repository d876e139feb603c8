"""Remakes the .msh files of this folder from their .geo sources (needs the `gmsh` Python
package: `pip install gmsh`). Running wrinkle needs no Gmsh.

    python3 examples/meshes/make_meshes.py
"""
import os
import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))

# (source, output, mesh size factor (Mesh.MeshSizeFactor), binary, grid to snap to (mm) or 0,
#  numbers the .geo reads if set: {name: value})
MESHES = [
    ("example1_rectangle.geo", "example1_rectangle.msh", 1.0, False, 6.25, {}),
    ("example1_rectangle.geo", "example1_rectangle_binary.msh", 1.0, True, 6.25, {}),
    ("example1_unstructured.geo", "example1_unstructured_25.msh", 1.0, False, 0, {}),
    ("example1_unstructured.geo", "example1_unstructured_12.msh", 0.5, False, 0, {}),
    ("example1_unstructured.geo", "example1_unstructured_6.msh", 0.25, True, 0, {}),
    # The annulus: nc elements per quarter turn, nr across, radial growth ratio grow.
    ("annulus.geo", "annulus.msh", 1.0, False, 0, {"nc": 24, "nr": 12, "grow": 1.08}),
    ("annulus.geo", "annulus_coarse.msh", 1.0, False, 0, {"nc": 12, "nr": 4, "grow": 1.2}),
]


def snap(grid):
    """Moves every node within 1e-6 mm of the `grid` (mm) onto it: Gmsh's transfinite
    interpolation places the nodes of a uniform grid up to 1.3e-9 mm off (measured), and the
    example 1 mesh is meant to have exactly the built-in mesh's nodes."""
    tags, coordinates, _ = gmsh.model.mesh.getNodes()
    for k, tag in enumerate(tags):
        xyz = list(coordinates[3 * k : 3 * k + 3])
        snapped = [round(c / grid) * grid for c in xyz]
        if all(abs(a - b) < 1e-6 for a, b in zip(xyz, snapped)):
            gmsh.model.mesh.setNode(tag, snapped, [])


def make(source, output, size_factor, binary, grid, numbers):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    for name, value in numbers.items():
        gmsh.parser.setNumber(name, [value])
    gmsh.merge(os.path.join(HERE, source))
    gmsh.option.setNumber("Mesh.MeshSizeFactor", size_factor)
    gmsh.model.mesh.generate(2)
    if grid:
        snap(grid)
    gmsh.option.setNumber("Mesh.Binary", 1 if binary else 0)
    gmsh.write(os.path.join(HERE, output))
    gmsh.finalize()


if __name__ == "__main__":
    for mesh in MESHES:
        if os.path.exists(os.path.join(HERE, mesh[0])):
            make(*mesh)
            print("wrote", mesh[1])
