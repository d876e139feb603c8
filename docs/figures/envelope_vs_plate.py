"""The envelope-vs-plate figure of docs/benchmarks.md (issue 30).

Relative error against the fvk-plate bench reference (128 x 32, ANM + Pade, N = 30,
eps = 1e-9) as a function of the whole run's time, log-log, one panel per compared quantity:
the plate's own points (its mesh sweep, every method) and the reference envelope's mesh sweep,
whose error is taken against the *plate's* reference -- what the multi-scale model buys.

usage: python3 envelope_vs_plate.py PLATE_RUNS_DIR ENVELOPE_BENCH_CSV OUT_STEM
  PLATE_RUNS_DIR      the runs/fvk-plate directory of `wrinkle bench --models fvk-plate`
                      (each point's summary.json; read directly, so a sweep that did not
                      finish can be plotted)
  ENVELOPE_BENCH_CSV  bench.csv of `wrinkle bench` (reference envelope), e.g. bench_example1.csv
Needs matplotlib. The load at a/h = 1 and a/h at 1.1 lambda_c are read from each plate run's
path with the bench's rule: a cubic through the two points on either side of the crossing,
kept only when it lies between them (linear otherwise).
"""

import csv
import json
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def crossing(xs, ys, level):
    """x where y first reaches level (the bench's cubic-or-linear rule), None if never."""
    for i in range(len(ys) - 1):
        if ys[i] < level <= ys[i + 1]:
            linear = xs[i] + (level - ys[i]) / (ys[i + 1] - ys[i]) * (xs[i + 1] - xs[i])
            j = max(0, min(i - 1, len(ys) - 4))
            px, py = ys[j:j + 4], xs[j:j + 4]
            if len(px) < 4 or len(set(px)) < 4:
                return linear
            value = sum(
                py[k] * math.prod((level - px[m]) / (px[k] - px[m]) for m in range(4) if m != k)
                for k in range(4)
            )
            low, high = sorted((xs[i], xs[i + 1]))
            return value if low <= value <= high else linear
    return None


def plate_point(summary):
    path = [p for p in summary["path"]]
    loads = [p["lambda"] for p in path]
    amplitudes = [p["max_amplitude_over_h"] for p in path]
    critical = summary["linear_buckling_load"]
    return {
        "time": summary["timings"]["total"],
        "critical_load": critical,
        "load_at_amplitude_1": crossing(loads, amplitudes, 1.0),
        "amplitude_at_1_1": crossing(amplitudes, loads, 1.1 * critical)
        if loads == sorted(loads) else None,
    }


def main(runs, envelope_csv, stem):
    runs = pathlib.Path(runs)
    points = {}
    for summary_file in sorted(runs.glob("*/summary.json")):
        points[summary_file.parent.name] = plate_point(json.loads(summary_file.read_text()))
    reference = next(v for k, v in points.items() if k.startswith("reference-"))
    quantities = [
        ("critical_load", "λ_c"),
        ("load_at_amplitude_1", "λ(a/h = 1)"),
        ("amplitude_at_1_1", "a/h at 1.1 λ_c"),
    ]
    with open(envelope_csv) as f:
        envelope = [r for r in csv.DictReader(f) if r["sweep"] in ("reference", "mesh")]
    figure, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    for axis, (key, label) in zip(axes, quantities):
        def error(value):
            if value is None or reference[key] is None:
                return None
            e = abs(value - reference[key]) / abs(reference[key])
            return e if e > 0 else None

        styles = (("anm-pade", "o", "-"), ("anm", "s", "--"), ("riks", "^", ":"))
        for method, marker, line in styles:
            rows = sorted(
                ((k, v) for k, v in points.items() if k.startswith(f"mesh-{method}-")),
                key=lambda kv: kv[1]["time"],
            )
            xy = [(v["time"], error(v[key]), k.split("-")[-4]) for k, v in rows if error(v[key])]
            if xy:
                axis.plot([t for t, _, _ in xy], [e for _, e, _ in xy], marker=marker,
                          linestyle=line, color="tab:red", markerfacecolor="none",
                          label=f"plate, mesh sweep, {method}")
                for t, e, mesh in xy:
                    axis.annotate(mesh, (t, e), fontsize=7, color="tab:red",
                                  textcoords="offset points", xytext=(4, -9))
        rows = sorted((r for r in envelope if r["method"] == "anm-pade"),
                      key=lambda r: float(r["time_total"]))
        xy = [(float(r["time_total"]), error(float(r[key])), f"{r['nx']}×{r['ny']}")
              for r in rows if r[key] and error(float(r[key]))]
        if xy:
            axis.plot([t for t, _, _ in xy], [e for _, e, _ in xy], marker="o",
                      color="tab:blue", label="reference envelope against the plate, anm-pade")
            for t, e, mesh in xy:
                axis.annotate(mesh, (t, e), fontsize=7, color="tab:blue",
                              textcoords="offset points", xytext=(3, 4))
        axis.axvline(reference["time"], color="tab:red", linestyle=":", linewidth=1)
        axis.annotate("plate reference 128×32", (reference["time"], 0.02), fontsize=7,
                      color="tab:red", xycoords=("data", "axes fraction"),
                      textcoords="offset points", xytext=(-4, 0), ha="right")
        axis.set_xscale("log")
        axis.set_yscale("log")
        axis.set_xlabel("time of the whole run (s)")
        axis.set_ylabel(f"relative error of {label} against the plate 128×32")
        axis.set_title(label)
        axis.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7, loc="best")
    figure.suptitle("Example 1: the plate's own error and the reference envelope's error "
                    "against the plate, against run time\n(plate points: `wrinkle bench --models "
                    "fvk-plate`, bench_plate_example1.csv; envelope points: bench_example1.csv; "
                    "both on a quiet host)", fontsize=10)
    figure.tight_layout()
    figure.savefig(f"{stem}.png", dpi=110)
    figure.savefig(f"{stem}.svg")


if __name__ == "__main__":
    main(*sys.argv[1:4])
