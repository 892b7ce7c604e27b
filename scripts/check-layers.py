#!/usr/bin/env python3
"""Fails when a folder of the library includes a folder above it (DEVELOPERS.md, Layout).

Reads every #include "rangefill/<folder>/..." and "<folder>/..." (a private header of src/) in
include/rangefill/, src/, tools/ and python/, and checks it against LAYERS: a folder may include
itself and the folders it lists, nothing else. Prints one line per violation, exits 1 if any.
"""

import pathlib
import re
import sys

# Each folder and the folders it may include, lowest first.
LAYERS = {
    "core": set(),
    "io": {"core"},
    "inpaint": {"core"},
    "depth": {"core", "inpaint"},
    "hole": {"core"},
    "image": {"core", "hole", "inpaint"},
    "fillers": {"core", "hole"},
    "repair": {"core", "hole", "image", "fillers", "inpaint"},
    "point_cloud": {"core"},
    "reports": {"core", "inpaint", "depth", "hole", "image", "fillers", "repair"},
    "eval": {"core", "io", "inpaint", "depth", "hole", "image", "fillers", "repair"},
    # The programs: everything but each other.
    "tools": set(),
    "python": set(),
}
LIBRARY = set(LAYERS) - {"tools", "python"}
LAYERS["tools"] = LIBRARY
LAYERS["python"] = LIBRARY - {"eval"}

INCLUDE = re.compile(r'^\s*#\s*include\s+"(?:rangefill/)?([a-z_]+)/[^"]+"', re.M)


def folder_of(root, path):
    parts = path.relative_to(root).parts
    if parts[0] == "include":
        return parts[2] if len(parts) > 3 else None
    if parts[0] == "src":
        return parts[1] if len(parts) > 2 else None
    return parts[0]  # tools, python


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parents[1])
    sources = [p for top in ("include/rangefill", "src", "tools", "python")
               for p in sorted((root / top).rglob("*")) if p.suffix in (".h", ".cpp")]
    violations = 0
    for path in sources:
        folder = folder_of(root, path)
        if folder not in LAYERS:
            print(f"{path.relative_to(root)}: folder '{folder}' is not in scripts/check-layers.py")
            violations += 1
            continue
        for included in INCLUDE.findall(path.read_text()):
            if included != folder and included in LAYERS and included not in LAYERS[folder]:
                print(f"{path.relative_to(root)}: {folder}/ includes {included}/, "
                      f"which is not below it")
                violations += 1
    if violations:
        print(f"{violations} include(s) against the layering of DEVELOPERS.md")
        return 1
    print(f"{len(sources)} files keep the layering")
    return 0


if __name__ == "__main__":
    sys.exit(main())
