"""``wrinkle sweep --scheduler ADDRESS`` hands its sweep here (``python -m
wrinkle.cli_sweep``): the sweep as JSON on standard input (``recipe``, ``grid`` as ``[[key,
[value texts]], ...]``, ``command``, ``out``, ``scheduler``); runs it on the Dask scheduler at
``scheduler`` and prints the table. Exit 0 once every point has a row."""

from __future__ import annotations

import json
import sys
import time

from .sweep import crossed_points, run_points


def main() -> int:
    """Runs the sweep read from standard input; returns the exit code."""
    start = time.perf_counter()
    request = json.load(sys.stdin)
    from distributed import Client

    with Client(request["scheduler"]) as client:
        table = run_points(
            crossed_points(request["recipe"], request["grid"]),
            command=request["command"],
            out=request["out"],
            client=client,
            workers=None,
            threads_per_point=None,
            progress=True,
            start=start,
        )
    for record in table.records():
        inputs = " ".join(f"{c}={record[c]}" for c in table.columns[1 : table.columns.index("outcome")])
        print(f"{record['index']:>4}  {inputs}  {record['outcome']:<11} λ_c {record['critical_load']}")
    print(f"sweep table in {table.csv} ({table.ran} points run, {table.seconds:.1f} s)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
