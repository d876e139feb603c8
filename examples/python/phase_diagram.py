"""A small wrinkling phase diagram with the `wrinkle` Python package (docs/python.md).

1. The threshold of the reference envelope (the paper's example 1, clamped rectangle under
   biaxial load) over a grid N_Y × L_X — critical load λ_c = −N_X and wavelength — computed on
   the mesh (a `buckle` sweep) with the closed form of eq. (42) minimised beside it.
2. The envelope-against-plate error over three scenes: the reference envelope on its coarse
   mesh against the full Föppl–von Kármán plate on a mesh that resolves its waves.

    pip install "./python[pandas]" matplotlib
    python examples/python/phase_diagram.py --out out/phase [--client tcp://host:8786]

Writes `OUT/phase_diagram.png` and the sweeps' tables (`OUT/grid/sweep.csv`,
`OUT/plate/sweep.csv`); a second call reuses every point.
"""

from __future__ import annotations

import argparse
import math
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import wrinkle  # noqa: E402

#: The grid: tension N_Y (N/mm) and length L_X (mm) of example 1 (L_Y = 200 mm).
TENSIONS = [2.5, 5.0, 10.0, 20.0, 40.0]
LENGTHS = [250.0, 300.0, 400.0, 500.0, 600.0]
#: The three scenes of the envelope-against-plate comparison (N_Y in N/mm).
PLATE_TENSIONS = [2.5, 5.0, 10.0]
#: The plate's mesh: 128 × 32 resolves the waves of example 1 (docs/comparison.md) with at
#: least 8 elements per wavelength up to N_Y = 10 (at N_Y = 20 it has 7.2: exit 4).
PLATE_MESH = {"mesh.nx": 128, "mesh.ny": 32}


def main() -> None:
    arguments = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    arguments.add_argument("--out", default="out/phase", type=pathlib.Path)
    arguments.add_argument("--client", default=None, help="a Dask scheduler address")
    options = arguments.parse_args()
    client = None
    if options.client:
        from dask.distributed import Client

        client = Client(options.client)
    grid = wrinkle.sweep(
        wrinkle.Scene(),
        {"load.tension_y": TENSIONS, "geometry.lx": LENGTHS},
        command="buckle",
        client=client,
        out=options.out / "grid",
    ).to_pandas()
    scenes = []
    for tension in PLATE_TENSIONS:
        scenes.append({"load.tension_y": tension})
        scenes.append({"load.tension_y": tension, "model.name": "fvk-plate", **PLATE_MESH})
    plate = wrinkle.sweep(None, scenes, command="buckle", client=client, out=options.out / "plate")
    figure = draw(grid, plate.to_pandas())
    path = options.out / "phase_diagram.png"
    figure.savefig(path, dpi=130)
    print(grid[["load.tension_y", "geometry.lx", "critical_load", "closed_form_critical_load",
                "wavelength", "outcome"]].to_string(index=False))
    print(f"figure: {path}")


def draw(grid, plate) -> plt.Figure:
    """Four panels: λ_c and the wavelength against N_Y (computed: markers; eq. (42): lines),
    the relative difference of the computed λ_c to eq. (42) over the whole N_Y × L_X grid, and
    the envelope-against-plate differences."""
    figure, ((loads, waves), (accuracy, errors)) = plt.subplots(2, 2, figsize=(12, 9))
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(LENGTHS)))
    for length, colour in zip(LENGTHS, colours):
        rows = grid[grid["geometry.lx"] == length].sort_values("load.tension_y")
        label = f"$L_X$ = {length:g} mm"
        loads.loglog(rows["load.tension_y"], rows["critical_load"], "o", color=colour, label=label)
        loads.loglog(rows["load.tension_y"], rows["closed_form_critical_load"], "-", color=colour)
        waves.semilogx(rows["load.tension_y"], rows["wavelength"], "o", color=colour, label=label)
        closed = 2 * math.pi / rows["closed_form_wavenumber"]
        waves.semilogx(rows["load.tension_y"], closed, "-", color=colour)
    for axes in (loads, waves):
        axes.set_xticks(TENSIONS, [f"{t:g}" for t in TENSIONS])
        axes.minorticks_off()
        axes.set_xlabel("tension $N_Y$ (N/mm)")
        axes.grid(alpha=0.3)
    loads.set_yticks([0.05, 0.07, 0.1, 0.14, 0.2], ["0.05", "0.07", "0.1", "0.14", "0.2"])
    loads.set(ylabel=r"critical load $\lambda_c = -N_X$ (N/mm)",
              title="threshold: mesh (markers), eq. (42) (lines); $L_X$ moves it < 1 %")
    waves.set(ylabel="wavelength (mm)", title="wavelength: mesh (markers), eq. (42) (lines)")
    loads.legend(fontsize=8)
    draw_accuracy(accuracy, grid)
    draw_errors(errors, plate)
    figure.suptitle("reference envelope, clamped 200 mm wide rectangle under biaxial load (example 1)")
    figure.tight_layout()
    return figure


def draw_accuracy(axes, grid) -> None:
    """The mesh's λ_c relative to eq. (42) over N_Y × L_X, as a table of coloured cells."""
    table = grid.pivot(index="geometry.lx", columns="load.tension_y",
                       values="closed_form_relative_difference") * 1e6
    image = axes.imshow(table.values, origin="lower", cmap="viridis")
    middle = 0.5 * (table.values.min() + table.values.max())
    for (i, j), value in np.ndenumerate(table.values):
        colour = "black" if value > middle else "white"
        axes.text(j, i, f"{value:+.2f}", ha="center", va="center", fontsize=9, color=colour)
    axes.set_xticks(range(len(table.columns)), [f"{t:g}" for t in table.columns])
    axes.set_yticks(range(len(table.index)), [f"{x:g}" for x in table.index])
    axes.set(xlabel="tension $N_Y$ (N/mm)", ylabel="length $L_X$ (mm)",
             title=r"mesh (32×16) against eq. (42): $\lambda_c/\lambda_c^{(42)} - 1$ (ppm)")
    plt.colorbar(image, ax=axes, label="ppm")


def draw_errors(axes, plate) -> None:
    """The envelope's threshold and wavelength relative to the plate's, per scene."""
    envelope = plate[plate["model"] == "reference-envelope"].reset_index(drop=True)
    plates = plate[plate["model"] == "fvk-plate"].reset_index(drop=True)
    load_error = envelope["critical_load"] / plates["critical_load"] - 1
    wave_error = envelope["wavelength"] / plates["wavelength"] - 1
    positions = np.arange(len(PLATE_TENSIONS))
    axes.bar(positions - 0.18, 100 * load_error, 0.36, label=r"$\lambda_c$")
    axes.bar(positions + 0.18, 100 * wave_error, 0.36, label="wavelength")
    axes.axhline(0, color="black", linewidth=0.8)
    axes.set_xticks(positions, [f"$N_Y$ = {t:g}" for t in PLATE_TENSIONS])
    axes.set(ylabel="envelope / plate − 1 (%)",
             title="envelope against FvK plate (128×32), $L_X$ = 400 mm")
    axes.legend(fontsize=8)


if __name__ == "__main__":
    main()
