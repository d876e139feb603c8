"""Reads every VTU and PVD file below a run directory the way a researcher's script would.

Usage: python read_with_meshio.py DIR [DIR ...]

Every `.vtu` is read with `meshio.read` (points, cells, point/cell/field data); every `.pvd`
is parsed with `xml.etree` (meshio has no reader for ParaView collections) and each dataset it
lists is read with `meshio.read`, its `timestep` checked to increase. Text field data (a `UInt8`
array of UTF-8 bytes) is decoded. Prints one line per file; exits 1 on the first failure.
"""

import pathlib
import sys
import xml.etree.ElementTree as ET

import meshio


def read_vtu(path):
    mesh = meshio.read(path)
    assert len(mesh.points) > 0, f"{path}: no points"
    assert sum(len(block.data) for block in mesh.cells) > 0, f"{path}: no cells"
    load = float(mesh.field_data["load"][0])
    unit = bytes(mesh.field_data["load_unit"]).decode()
    kinds = ",".join(sorted({block.type for block in mesh.cells}))
    arrays = sorted(mesh.point_data) + sorted(mesh.cell_data)
    return f"{kinds}, load {load:.6g} {unit}, arrays {' '.join(arrays)}"


def read_pvd(path):
    root = ET.parse(path).getroot()
    assert root.get("type") == "Collection", f"{path}: not a collection"
    times = []
    for dataset in root.iter("DataSet"):
        times.append(float(dataset.get("timestep")))
        read_vtu(path.parent / dataset.get("file"))
    assert times, f"{path}: empty collection"
    assert all(a < b for a, b in zip(times, times[1:])), f"{path}: times not increasing"
    return f"{len(times)} datasets, loads {times[0]:.6g} … {times[-1]:.6g}"


def main(directories):
    count = 0
    for directory in directories:
        for path in sorted(pathlib.Path(directory).rglob("*")):
            if path.suffix == ".vtu":
                print(f"{path}: {read_vtu(path)}")
            elif path.suffix == ".pvd":
                print(f"{path}: {read_pvd(path)}")
            else:
                continue
            count += 1
    if count == 0:
        sys.exit(f"no VTU or PVD file below {directories}")
    print(f"read {count} files")


if __name__ == "__main__":
    main(sys.argv[1:])
