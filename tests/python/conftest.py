"""Fixtures of the Python module's tests: the rangefill command, ../shared and built data."""

import os
import pathlib
import subprocess

import numpy as np
import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs the rangefill command (RANGEFILL_CLI) with the given arguments; returns its output."""
    path = os.environ.get("RANGEFILL_CLI")
    if not path:
        pytest.skip("RANGEFILL_CLI is not set (ctest sets it)")

    def run(*arguments):
        return subprocess.run([path, *map(str, arguments)], check=True, capture_output=True,
                              text=True).stdout

    return run


@pytest.fixture(scope="session")
def shared():
    """../shared/data, or a skip with a message when it is absent."""
    data = pathlib.Path(os.environ.get("RANGEFILL_SHARED_DIR", "../shared")) / "data"
    if not data.is_dir():
        pytest.skip(f"{data} is absent: the test needs the shared data")
    return data


def icosphere(subdivisions):
    """A unit sphere: an icosahedron whose faces are split in four `subdivisions` times, its
    vertices pushed onto the sphere. Returns (vertices N×3 float64, faces M×3 int32)."""
    t = (1 + 5 ** 0.5) / 2
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    vertices = [np.array(v, float) / np.linalg.norm(v) for v in vertices]
    for _ in range(subdivisions):
        middle = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                m = vertices[a] + vertices[b]
                vertices.append(m / np.linalg.norm(m))
                middle[key] = len(vertices) - 1
            return middle[key]

        split = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = split
    return np.array(vertices), np.array(faces, dtype=np.int32)


@pytest.fixture
def punched_sphere():
    """A unit sphere (1280 faces) without the faces whose centre lies within 0.35 of (0, 0, 1):
    (vertices, faces) with one hole, every vertex still used."""
    vertices, faces = icosphere(3)
    centres = vertices[faces].mean(axis=1)
    kept = faces[np.linalg.norm(centres - [0, 0, 1], axis=1) > 0.35]
    used = np.unique(kept)
    index = np.full(len(vertices), -1, dtype=np.int32)
    index[used] = np.arange(len(used), dtype=np.int32)
    return vertices[used], index[kept]


def plane_depth(height=120, width=160):
    """A tilted plane seen by a camera, in millimetres (uint16): planes are linear in inverse
    depth, which fill_depth restores exactly up to rounding."""
    y, x = np.mgrid[0:height, 0:width]
    inverse = 1 / 1500 + (x - width / 2) * 2e-7 + (y - height / 2) * 1e-7
    return np.round(1 / inverse).astype(np.uint16)
