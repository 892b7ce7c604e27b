#!/usr/bin/env python3
"""Fills every depth image of a folder with rangefill and plots each next to its fill.

    PYTHONPATH=build/python python3 python/examples/fill_depth_folder.py \\
        ../shared/data/depth-real --out filled [--fast] [--threads 2]

Writes OUT/NAME (the filled depth, same format) and, when matplotlib is installed,
OUT/NAME.plot.png (depth, fill and filled pixels side by side); prints one line per frame.
Frames are filled two at a time: rangefill releases the GIL while it works.
"""

import argparse
import pathlib
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import rangefill


def plot(depth, filled, filled_mask, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    valid = filled[filled > 0]
    low, high = (np.percentile(valid, [1, 99]) if valid.size else (0, 1))
    figure, axes = plt.subplots(1, 3, figsize=(15, 4))
    for axis, image, title in ((axes[0], np.where(depth > 0, depth, np.nan), "depth (white: invalid)"),
                               (axes[1], filled, "filled"),
                               (axes[2], filled_mask, "filled pixels")):
        shown = axis.imshow(image, cmap="gray" if image is filled_mask else "viridis",
                            vmin=None if image is filled_mask else low,
                            vmax=None if image is filled_mask else high)
        axis.set_title(title)
        axis.axis("off")
        if image is not filled_mask:
            figure.colorbar(shown, ax=axis, shrink=0.8)
    figure.tight_layout()
    figure.savefig(path, dpi=80)
    plt.close(figure)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", type=pathlib.Path)
    parser.add_argument("--out", type=pathlib.Path, required=True)
    parser.add_argument("--fast", action="store_true", help="fill along lines (a few ms a frame)")
    parser.add_argument("--threads", type=int, default=2, help="frames filled at once")
    parser.add_argument("--no-plot", action="store_true")
    arguments = parser.parse_args()
    arguments.out.mkdir(parents=True, exist_ok=True)
    frames = sorted(p for p in arguments.folder.iterdir()
                    if p.suffix.lower() in (".png", ".tif", ".tiff", ".exr"))
    try:
        import matplotlib  # noqa: F401
        plotting = not arguments.no_plot
    except ImportError:
        plotting = False
        print("matplotlib is not installed (python3-matplotlib): no plots")

    def fill(path):
        depth = rangefill.read_depth(path)
        start = time.perf_counter()
        filled, stats = rangefill.fill_depth(depth, fast=arguments.fast)
        seconds = time.perf_counter() - start
        rangefill.write_depth(filled, arguments.out / path.name)
        if plotting:
            plot(depth, filled, stats["filled_mask"], arguments.out / (path.name + ".plot.png"))
        return path, stats, seconds

    with ThreadPoolExecutor(arguments.threads) as pool:
        for path, stats, seconds in pool.map(fill, frames):
            print(f"{path.name}: {stats['filled']} of {stats['holes']} holes, "
                  f"{stats['filled_pixels']} pixels filled in {1000 * seconds:.1f} ms")


if __name__ == "__main__":
    main()
