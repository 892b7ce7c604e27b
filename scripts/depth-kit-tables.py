#!/usr/bin/env python3
"""Markdown tables of a depth-kit run (its results.csv), the tuning and held-out frames apart.

usage: depth-kit-tables.py RESULTS.csv [--held-out STEM,...]

Per method: RMSE median over frames, then pooled RMSE (all filled punched pixels together) over
all, edge, non-edge pixels and per hole kind, and the median ms per frame, as the kit's summary.md
gives them for the whole run. Frames whose name starts with a held-out stem (DEVELOPERS.md,
Tuning and validation) are tabled apart, then every frame together.
"""
import argparse
import csv
import math
import statistics

REGIONS = [("all", "filled", "rmse_mm"), ("edge", "edge_filled", "edge_rmse_mm"),
           ("non-edge", "nonedge_filled", "nonedge_rmse_mm"), ("blobs", "blob_filled", "blob_rmse_mm"),
           ("bands", "band_filled", "band_rmse_mm"), ("dropouts", "dropout_filled", "dropout_rmse_mm")]


def pooled(rows, count, rmse):
    pixels = sum(float(r[count] or 0) for r in rows)
    squares = sum(float(r[count] or 0) * float(r[rmse] or 0) ** 2 for r in rows)
    return math.sqrt(squares / pixels) if pixels else float("nan")


def table(title, rows):
    methods = list(dict.fromkeys(r["method"] for r in rows))
    print(f"\n{title} ({len({r['frame'] for r in rows})} frames)\n")
    print("| method | RMSE median | " + " | ".join(f"{name} pooled" for name, _, _ in REGIONS) +
          " | ms/frame |")
    print("|---" * (len(REGIONS) + 3) + "|")
    for method in methods:
        mine = [r for r in rows if r["method"] == method]
        median = statistics.median(float(r["rmse_mm"]) for r in mine)
        ms = statistics.median(float(r["ms"]) for r in mine)
        cells = " | ".join(f"{pooled(mine, c, e):.1f}" for _, c, e in REGIONS)
        print(f"| {method} | {median:.1f} | {cells} | {ms:.0f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results")
    parser.add_argument("--held-out", default="sun3d")
    args = parser.parse_args()
    rows = [r for r in csv.DictReader(open(args.results)) if r["status"] == "ok"]
    held = tuple(args.held_out.split(","))
    table("Tuning frames", [r for r in rows if not r["frame"].startswith(held)])
    table("Held-out frames: " + ", ".join(held), [r for r in rows if r["frame"].startswith(held)])
    table("All frames", rows)


if __name__ == "__main__":
    main()
