#!/usr/bin/env python3
"""Writes docs/results.md from a work directory of scripts/results-page.sh (stdlib only).

usage: results-page.py WORK [-o docs/results.md]

WORK holds about.tsv (version, commit, machine, data paths), commands.tsv (KEY<TAB>command) and
each bench's output under the names results-page.sh gives them. Every table on the page is made
from those outputs and printed under the command that made it; a bench that was not run is said.
"""
import argparse
import csv
import json
import math
import pathlib
import statistics


def read_tsv(path):
    rows = {}
    if path.exists():
        for line in path.read_text().splitlines():
            key, _, value = line.partition("\t")
            rows[key] = value
    return rows


def fmt(value, digits=2):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "—"
    return f"{value:.{digits}f}"


def table(header, rows, align=None):
    align = align or ["---"] + ["---:"] * (len(header) - 1)
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join(align) + "|"]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines)


class Page:
    def __init__(self, work):
        self.work = work
        self.commands = read_tsv(work / "commands.tsv")
        self.about = read_tsv(work / "about.tsv")
        self.parts = []

    def add(self, text):
        self.parts.append(text.strip("\n"))

    def command(self, *keys):
        lines = [self.commands[key] for key in keys if key in self.commands]
        self.add("\n".join("    " + line for line in lines))

    def has(self, key):
        return key in self.commands

    def text(self):
        return "\n\n".join(self.parts) + "\n"


def tables_md_sections(path, prefixes):
    """The sections of a bench's tables.md whose '### ' heading starts with one of `prefixes`,
    each as (heading, body), in the order of `prefixes`."""
    sections, heading, body = {}, None, []
    for line in path.read_text().splitlines():
        if line.startswith("### "):
            if heading:
                sections[heading] = "\n".join(body).strip()
            heading, body = line[4:], []
        elif heading:
            body.append(line)
    if heading:
        sections[heading] = "\n".join(body).strip()
    found = []
    for prefix in prefixes:
        for name, text in sections.items():
            if name.startswith(prefix):
                found.append((name, text))
                break
    return found


def bench_section(page, key, title, intro, prefixes):
    page.add(f"## {title}")
    if not page.has(key):
        page.add("Not run: the closed meshes were not found.")
        return
    page.add(intro)
    page.command(key)
    directory = page.work / key
    for heading, body in tables_md_sections(directory / "tables.md", prefixes):
        page.add(f"**{heading}**")
        page.add(body)


def sample_section(page):
    page.add("## The bundled sample")
    page.add(
        "`data/bunny-bottom.ply` ([data/README.md](../data/README.md)): the lower part of the "
        "Stanford bunny scan, five genuine scan holes and the loop where it was cut. There is no "
        "ground truth for genuine holes; the table gives what the default repair did.")
    page.command("holes-sample", "repair-sample", "info-sample")
    loops = json.loads((page.work / "holes-sample.json").read_text())["loops"]
    report = json.loads((page.work / "repair-sample.json").read_text())
    info = json.loads((page.work / "info-sample.json").read_text())
    by_loop = {}
    for hole in report["holes"]:
        if hole["pass"] == 0:
            by_loop[hole["loop"]] = hole
    open_by_hole = {loop["hole"]: loop for loop in report["open_loops"]}
    rows = []
    for loop in loops:
        hole = by_loop.get(loop["id"])
        if hole is None:
            reason = open_by_hole.get(loop["id"], {}).get("reason", "left open")
            rows.append([loop["id"], loop["edges"], f"{100 * loop['area_share']:.1f} %",
                         f"left open ({reason})", "", "", ""])
            continue
        scores = ", ".join(
            f"{s['candidate']} {fmt(s['band_rms']) if s['band_rms'] is not None else 'refused'}"
            for s in hole["selection"]) or "no band test"
        filled = (hole["selected"] or hole["method"]) if hole["filled"] else hole["failure"]
        rows.append([loop["id"], loop["edges"], f"{100 * loop['area_share']:.1f} %", filled,
                     scores, hole["new_faces"], fmt(hole["seconds"], 3)])
    page.add(table(["loop", "edges", "area share", "filled by", "band test: RMS / d_m",
                    "new faces", "s"], rows, ["---:", "---:", "---:", "---", "---", "---:", "---:"]))
    page.add(
        f"Result: {info['faces']} faces, {len(info['boundary_loops'])} boundary loop(s) left "
        f"({', '.join(str(e) for e in info['boundary_loops'])} edges), "
        f"{info['nonmanifold_edges']} non-manifold edges, "
        f"{info['self_intersecting_face_pairs']} self-intersecting face pairs.")


def border_section(page):
    page.add("## Border or hole")
    page.add(
        "`repair` leaves a loop open when its area share (the loop's vector area over its "
        "component's area) is at least 0.2 ([repair.md](repair.md#which-loops-are-filled)). The "
        "area shares of the bundled sample's loops and of the shared open scans "
        "(`real-holes`: a scan with genuine holes, and three models cut off at the neck):")
    keys = ["holes-sample"] + sorted(k for k in page.commands if k.startswith("holes-real:"))
    page.command(*keys)
    rows = []
    for key in keys:
        name = "bunny-bottom (bundled)" if key == "holes-sample" else key.split(":", 1)[1]
        file = page.work / ("holes-sample.json" if key == "holes-sample"
                            else f"holes-real-{key.split(':', 1)[1]}.json")
        loops = json.loads(file.read_text())["loops"]
        shares = ", ".join(f"{100 * loop['area_share']:.1f}" for loop in
                           sorted(loops, key=lambda loop: -loop["area_share"]))
        borders = sum(loop["border"] for loop in loops)
        rows.append([name, len(loops), shares, borders])
    page.add(table(["mesh", "loops", "area shares, %", "borders"], rows,
                   ["---", "---:", "---", "---:"]))
    if not any(k.startswith("holes-real:") for k in page.commands):
        page.add("The shared open scans were not found; only the bundled sample is listed.")


def depth_rows(rows):
    """Per method, in order of appearance: frames, punched pixels, pooled RMSE and MAE (mm),
    median ms per frame, pixels left at 0."""
    methods = list(dict.fromkeys(r["method"] for r in rows))
    out = []
    for method in methods:
        mine = [r for r in rows if r["method"] == method]
        pixels = sum(float(r["punched"]) for r in mine)
        rmse = math.sqrt(sum(float(r["punched"]) * float(r["rmse_mm"]) ** 2 for r in mine) / pixels)
        mae = sum(float(r["punched"]) * float(r["mae_mm"]) for r in mine) / pixels
        frames = len({r["frame"] for r in mine})
        ms = statistics.median(float(r["ms"]) for r in mine)
        left = sum(int(r["unfilled"]) for r in mine)
        out.append([method, frames, len(mine), int(pixels), fmt(rmse, 1), fmt(mae, 1),
                    fmt(ms, 1), left])
    return out


DEPTH_HEADER = ["method", "frames", "frame × pattern", "punched pixels", "RMSE mm (pooled)",
                "MAE mm (pooled)", "ms / frame (median)", "left at 0"]


def depth_section(page):
    page.add("## Depth bench")
    page.add(
        "`rangefill depth-bench` ([bench.md](bench.md#rangefill-depth-bench)) punches sensor-like "
        "holes (5 % of the valid pixels, 3 patterns per frame) and fills only the punched pixels. "
        "`fill_depth harmonic` is `rangefill depth`'s default (holes of up to 2000 pixels by the "
        "harmonic back-end, larger ones along lines); `fill_depth lines` is `--inpainter lines`; "
        "`fill_depth, colour-guided` is the default with the frame's colour image. Errors are "
        "pooled over every punched pixel; times are the fill alone, in one process.")
    if page.has("depth-bench-frames"):
        page.add("**Sensor frames** (`depth-real`: one 640×480 frame each from TUM RGB-D, SUN3D "
                 "and Open3D's test data, and a rendered ICL-NUIM living-room frame with simulated "
                 "sensor noise; colour images for tum, sun3d and livingroom)")
        page.command("depth-bench-frames")
        rows = list(csv.DictReader(open(page.work / "depth-bench-frames.csv")))
        page.add(table(DEPTH_HEADER, depth_rows(rows)))
        coloured = {r["frame"] for r in rows if r["method"] == "fill_depth, colour-guided"}
        if coloured:
            page.add(f"The same, on the {len(coloured)} frames with a colour image only:")
            page.add(table(DEPTH_HEADER, depth_rows([r for r in rows if r["frame"] in coloured])))
    else:
        page.add("Recorded frames: not run, the frames were not found.")
    page.add("**Frames rendered from the bundled sample** (640×480, 4 views, no sensor noise, no "
             "colour)")
    page.command("depth-bench-sample")
    rows = list(csv.DictReader(open(page.work / "depth-bench-sample.csv")))
    page.add(table(DEPTH_HEADER, depth_rows(rows)))


def patch_section(page):
    page.add("## Fields of Experts on depth patches")
    if not page.has("patch-bench"):
        page.add("Not run: the closed meshes were not found.")
        return
    page.add(
        "`rangefill patch-bench` ([backends.md](backends.md#rangefill-patch-bench)) on 32×32-pixel "
        "range-image patches of bunny, fandisk and homer, the meshes held out of the `depth` "
        "model's training, with blob holes of 5–30 %; seed 2 draws patches training never saw. "
        "RMSE in d_m over the masked pixels; \"foe better on\": the share of patches on which "
        "`foe` (the `depth` model) has the lower RMSE.")
    page.command("patch-bench")
    report = json.loads((page.work / "patch-bench.json").read_text())
    rows = []
    for name, entry in report.items():
        rows.append([f"`{name}`", entry["patches"], fmt(entry["rmse_median"], 3),
                     fmt(entry["rmse_mean"], 3), f"{100 * entry['best_share']:.0f} %",
                     "—" if name == "foe" else f"{100 * entry['beaten_by_first']:.0f} %",
                     fmt(entry["ms_median"], 2)])
    page.add(table(["back-end", "patches", "RMSE median", "RMSE mean", "best on",
                    "foe better on", "ms / patch"], rows))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("work", type=pathlib.Path)
    parser.add_argument("-o", "--output", type=pathlib.Path, default=pathlib.Path("docs/results.md"))
    args = parser.parse_args()
    page = Page(args.work)
    about = page.about
    page.add("# Results")
    page.add(
        "<!-- Generated by scripts/results-page.sh from its bench outputs; do not edit by hand. -->")
    page.add(
        f"Made by `scripts/results-page.sh` on {about.get('date', '?')} at commit "
        f"{about.get('commit', '?')}, with {about.get('version', 'rangefill')} (`build/bin/rangefill` "
        f"built {about.get('built', '?')}), on a machine with "
        f"{about.get('cores', '?')} cores ({about.get('cpu', '?')}). Regenerate with "
        "`scripts/results-page.sh` after building; `scripts/results-page.sh --help` lists the "
        "data paths it takes. Every table below is printed under the command that made it, run "
        "from the repository root. Times depend on the machine; the other figures do not.")
    page.add(
        "Data: the bundled sample `data/bunny-bottom.ply`, and the shared test data, which is not "
        f"part of the repository: closed meshes `{about.get('data_meshes')}` (12 public research "
        f"meshes), depth frames `{about.get('data_frames')}`, open scans "
        f"`{about.get('data_real_holes')}`. Without them, only the bundled sample's sections are "
        "made. Distances are in d_m, the mesh's mean edge length. The benches on the shared "
        "meshes use every mesh, so they mix the tuning and validation halves "
        "([DEVELOPERS.md](../DEVELOPERS.md#tuning-and-validation)). The independent evaluation "
        "kits' figures, held-out data apart, are in [mesh-repair.md](mesh-repair.md) and "
        "[depth-maps.md](depth-maps.md).")
    sample_section(page)
    border_section(page)
    bench_section(
        page, "bench-default", "Mesh bench: the default repair against CGAL",
        "`rangefill bench` ([bench.md](bench.md#rangefill-bench)) punches disks and capsules of "
        "3–20 d_m into the closed meshes, spread over low, medium and high curvature and sharp "
        "features. The `telea` method is `rangefill repair`'s default: the band test over "
        "`fairing,fairing:c1,plane:telea`, then the default chain. `cgal-fair` is CGAL's "
        "triangulate, refine and fair (Liepa), `cgal-triangulate` its triangulation alone.",
        ["Per method", "Effectiveness ranking by H"])
    bench_section(
        page, "bench-plane", "Mesh bench: the back-ends on the paper's pipeline",
        "`--filler plane` turns the band test off and sends every hole a plane sees through the "
        "image pipeline, so that the back-ends differ; the front and the loop triangulations take "
        "the rest (the per-hole table in `tables.md` names the strategy).",
        ["Per method", "The back-ends ranked among themselves"])
    bench_section(
        page, "bench-trends", "Mesh bench: the trend",
        "The same pipeline with Telea's back-end and each trend: `none` is the paper's pipeline, "
        "`auto` the default.",
        ["Per method"])
    patch_section(page)
    depth_section(page)
    page.add("## Depth evaluation kit")
    page.add(
        "The depth kit's tables in [depth-maps.md](depth-maps.md) are regenerated from a kit run's "
        "`results.csv` by `scripts/depth-kit-tables.py runs/depth/results.csv --held-out sun3d`; "
        "the kit run's command is on that page.")
    args.output.write_text(page.text())


if __name__ == "__main__":
    main()
