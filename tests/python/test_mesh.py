"""rangefill's meshes as numpy arrays: Mesh, read_mesh, write_mesh, repair, filler_names and holes."""

import json

import numpy as np
import pytest

import rangefill
from conftest import icosphere


def test_a_mesh_shows_its_elements_as_numpy_views():
    vertices, faces = icosphere(1)
    mesh = rangefill.Mesh(vertices, faces)
    assert mesh.vertices.dtype == np.float64 and mesh.vertices.shape == (42, 3)
    assert mesh.faces.dtype == np.int32 and mesh.faces.shape == (80, 3)
    assert np.array_equal(mesh.vertices, vertices) and np.array_equal(mesh.faces, faces)
    assert np.shares_memory(mesh.vertices, mesh.vertices)  # both views of the mesh's memory
    mesh.vertices[0] = (0, 0, 2)
    assert tuple(mesh.vertices[0]) == (0, 0, 2)
    assert mesh.colors.shape == (0, 3) and mesh.normals.shape == (0, 3)
    assert (mesh.vertex_hole == -1).all() and (mesh.face_hole == -1).all()
    view = mesh.faces
    del mesh  # the view keeps the mesh alive
    assert np.array_equal(view, faces)


def test_mesh_files_round_trip_with_colours_and_normals(tmp_path):
    vertices, faces = icosphere(2)
    colours = np.round(np.abs(vertices) * 255) / 255  # 8-bit colours come back exactly
    mesh = rangefill.Mesh(vertices, faces, colors=colours, normals=vertices)
    for name, options in (("m.ply", {}), ("a.ply", {"ascii": True}), ("m.obj", {})):
        rangefill.write_mesh(mesh, tmp_path / name, **options)
        back = rangefill.read_mesh(tmp_path / name)
        assert np.array_equal(back.vertices, mesh.vertices), name
        assert np.array_equal(back.faces, mesh.faces), name
        if name.endswith(".ply"):
            assert np.array_equal(back.colors, mesh.colors.astype(np.float32)), name
            assert np.allclose(back.normals, vertices, atol=1e-6), name


def test_holes_lists_the_loops(punched_sphere):
    report = rangefill.holes(rangefill.Mesh(*punched_sphere), vertices=True)
    assert len(report["loops"]) == 1
    loop = report["loops"][0]
    assert not loop["border"] and loop["edges"] == len(loop["vertices"]) > 10
    assert report["nonmanifold_edges"] == 0


def test_repair_closes_a_punched_sphere_and_keeps_the_input(punched_sphere):
    vertices, faces = punched_sphere
    mesh = rangefill.Mesh(vertices, faces)
    repaired, report = rangefill.repair(mesh)
    n, m = len(vertices), len(faces)
    assert np.array_equal(repaired.vertices[:n], vertices)  # bit for bit
    assert np.array_equal(repaired.faces[:m], faces)
    assert (repaired.vertex_hole[:n] == -1).all() and (repaired.vertex_hole[n:] == 0).all()
    assert (repaired.face_hole[m:] == 0).all() and len(repaired.faces) > m
    assert rangefill.holes(repaired)["loops"] == []  # closed
    radius = np.linalg.norm(repaired.vertices[n:], axis=1)
    assert np.abs(radius - 1).max() < 0.03  # the cap comes back on the sphere
    assert [hole["filled"] for hole in report["holes"]] == [True]
    assert report["loops_left_open"] == 0 and report["restoration_matrix"][0][0] == n


def test_repair_gives_the_command_s_mesh_and_report(cli, punched_sphere, tmp_path):
    source, target = tmp_path / "punched.ply", tmp_path / "repaired.ply"
    rangefill.write_mesh(rangefill.Mesh(*punched_sphere), source)
    command = json.loads(cli("repair", source, "-o", target, "--json"))
    repaired, report = rangefill.repair(rangefill.read_mesh(source))
    written = rangefill.read_mesh(target)
    assert np.array_equal(repaired.vertices, written.vertices)
    assert np.array_equal(repaired.faces, written.faces)
    assert np.array_equal(repaired.face_hole, written.face_hole)

    def without_times(value):
        if isinstance(value, dict):
            return {k: without_times(v) for k, v in value.items() if "seconds" not in k}
        return [without_times(v) for v in value] if isinstance(value, list) else value

    assert without_times(report) == without_times(
        {k: v for k, v in command.items() if k in report})


def test_repair_of_a_shared_mesh_closes_every_punched_hole(shared):
    mesh = rangefill.read_mesh(shared / "meshes" / "bunny.ply")
    centres = mesh.vertices[mesh.faces].mean(axis=1)
    rng = np.random.default_rng(1)
    kept = np.ones(len(mesh.faces), bool)
    for centre in centres[rng.choice(len(centres), 3, replace=False)]:
        kept &= np.linalg.norm(centres - centre, axis=1) > 0.01
    punched = rangefill.Mesh(mesh.vertices, mesh.faces[kept])  # unused vertices are allowed
    repaired, report = rangefill.repair(punched, threads=2)
    assert all(hole["filled"] for hole in report["holes"]) and len(report["holes"]) >= 3
    assert rangefill.holes(repaired)["loops"] == []
    assert np.array_equal(repaired.faces[: kept.sum()], punched.faces)


def test_invalid_meshes_and_options_raise_value_error():
    vertices, faces = icosphere(1)
    with pytest.raises(ValueError, match="mesh: face 80 refers to vertex 42, out of range"):
        rangefill.Mesh(vertices, np.vstack([faces, [[0, 1, 42]]]))
    nan = vertices.copy()
    nan[3, 1] = np.nan
    with pytest.raises(ValueError, match="mesh: .*(NaN|finite)"):
        rangefill.Mesh(nan, faces)
    with pytest.raises(ValueError, match="vertices: an N×3 array expected"):
        rangefill.Mesh(vertices[:, :2], faces)
    with pytest.raises(ValueError, match="faces: integer"):
        rangefill.Mesh(vertices, faces.astype(float))
    mesh = rangefill.Mesh(vertices, faces)
    mesh.vertices[5, 0] = np.inf  # a view written in place is checked before use
    with pytest.raises(ValueError, match="mesh: "):
        rangefill.repair(mesh)
    with pytest.raises(ValueError, match="unknown"):
        rangefill.repair(rangefill.Mesh(vertices, faces), inpainter="nope")
    with pytest.raises(ValueError, match="unknown filler 'nope'"):
        rangefill.repair(rangefill.Mesh(vertices, faces), filler="nope")
    with pytest.raises(ValueError, match="unknown filler 'plane:'"):
        rangefill.repair(rangefill.Mesh(vertices, faces), select="fairing,plane:")


def test_each_filler_named_closes_the_punched_sphere(punched_sphere):
    mesh = rangefill.Mesh(*punched_sphere)
    names = rangefill.filler_names()
    assert names[0] == "fairing" and "plane" in names and "least-area" in names
    for name in names:
        repaired, report = rangefill.repair(mesh, filler=name, fallback="none", select="none")
        assert report["holes"][0]["filled"] and report["holes"][0]["filler"] == name, name
        if name != "plane-in-part":  # a part of the loop per pass, Section VI-C
            assert len(report["holes"]) == 1 and rangefill.holes(repaired)["loops"] == [], name


def test_file_errors_name_the_file(tmp_path):
    with pytest.raises(OSError, match="missing.ply"):
        rangefill.read_mesh(tmp_path / "missing.ply")
    truncated = tmp_path / "truncated.ply"
    truncated.write_bytes(b"ply\nformat binary_little_endian 1.0\nelement vertex 10\n"
                          b"property float x\nproperty float y\nproperty float z\nend_header\n\0\0")
    with pytest.raises(ValueError, match="truncated.ply"):
        rangefill.read_mesh(truncated)
    with pytest.raises(OSError):
        rangefill.write_mesh(rangefill.Mesh(*icosphere(0)), tmp_path / "no-dir" / "m.ply")


def test_a_point_cloud_that_cannot_be_meshed_raises_processing_error():
    cloud = rangefill.Mesh(np.zeros((20, 3)), np.zeros((0, 3), np.int32))
    with pytest.raises(rangefill.ProcessingError, match="same place"):
        rangefill.repair(cloud)
    assert issubclass(rangefill.ProcessingError, RuntimeError)


def test_face_indices_beyond_int32_are_refused_not_wrapped():
    vertices, faces = icosphere(0)
    wide = faces.astype(np.int64)
    wide[0, 0] += 2 ** 32  # would wrap round to a valid index
    with pytest.raises(ValueError, match="faces: vertex indices must lie in"):
        rangefill.Mesh(vertices, wide)
    with pytest.raises(ValueError, match="faces: vertex indices must lie in"):
        rangefill.Mesh(vertices, -faces)
