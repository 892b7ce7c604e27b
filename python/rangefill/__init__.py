"""rangefill: the holes of 3D scans and depth maps filled by inpainting (the C++ library).

Depth maps: fill_depth, inpaint, backends, read_depth, read_color, write_depth.
Meshes: Mesh, read_mesh, write_mesh, repair, filler_names, holes.
Errors: ValueError (invalid input), OSError (files), ProcessingError (a well-formed input that
could not be processed), each with the one-line message of the command-line tool.
Every long call releases the GIL: threads filling frames at once run in parallel.
"""

from ._rangefill import (
    Mesh,
    ProcessingError,
    __version__,
    backends,
    fill_depth,
    filler_names,
    holes,
    inpaint,
    read_color,
    read_depth,
    read_mesh,
    repair,
    write_depth,
    write_mesh,
)

__all__ = [
    "Mesh",
    "ProcessingError",
    "backends",
    "fill_depth",
    "filler_names",
    "holes",
    "inpaint",
    "read_color",
    "read_depth",
    "read_mesh",
    "repair",
    "write_depth",
    "write_mesh",
]
