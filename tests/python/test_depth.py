"""rangefill's depth functions on numpy arrays: fill_depth, inpaint, backends, read/write_depth."""

import threading
import time

import numpy as np
import pytest

import rangefill
from conftest import plane_depth


def with_holes(depth):
    """`depth` with two discs and a band at the left border set to 0 (invalid)."""
    holed = depth.copy()
    y, x = np.mgrid[0:depth.shape[0], 0:depth.shape[1]]
    holed[(x - 50) ** 2 + (y - 40) ** 2 < 12 ** 2] = 0
    holed[(x - 110) ** 2 + (y - 80) ** 2 < 8 ** 2] = 0
    holed[60:70, 0:6] = 0
    return holed


def test_fill_depth_restores_a_plane_and_keeps_every_valid_pixel():
    truth = plane_depth()
    holed = with_holes(truth)
    filled, stats = rangefill.fill_depth(holed)
    assert filled.dtype == np.uint16 and filled.shape == holed.shape
    valid = holed > 0
    assert np.array_equal(filled[valid], holed[valid])
    assert np.abs(filled.astype(int) - truth.astype(int)).max() <= 2  # mm, on a plane at 1.5 m
    assert stats["holes"] == 3 and stats["filled"] == 3 and stats["left_holes"] == 0
    assert stats["filled_pixels"] == int((~valid).sum())
    assert np.array_equal(stats["filled_mask"] == 255, ~valid)


def test_fill_depth_in_metres_takes_nan_and_zero_as_invalid():
    truth = plane_depth().astype(np.float32) / 1000
    holed = with_holes(truth)
    holed[5:9, 100:104] = np.nan
    filled, stats = rangefill.fill_depth(holed)
    assert filled.dtype == np.float32 and np.isfinite(filled).all()
    assert np.abs(filled - truth).max() < 2e-3
    assert stats["filled"] == 4


def test_a_mask_chooses_the_pixels_to_fill():
    truth = plane_depth()
    mask = np.zeros(truth.shape, bool)
    mask[20:30, 20:30] = True  # valid pixels, filled because the mask says so
    filled, stats = rangefill.fill_depth(truth, mask)
    assert stats["filled_pixels"] == 100
    assert np.array_equal(filled[~mask], truth[~mask])
    assert np.abs(filled.astype(int) - truth.astype(int)).max() <= 2


def test_any_strides_give_the_same_fill_as_a_contiguous_array():
    holed = with_holes(plane_depth(120, 320))
    strided = holed[:, ::2]  # columns two elements apart: copied
    window = holed[10:110, 40:200]  # rows apart by the full width: no copy
    transposed = np.ascontiguousarray(holed.T).T
    for array in (strided, window, transposed):
        assert not array.flags.c_contiguous
        assert np.array_equal(rangefill.fill_depth(array)[0],
                              rangefill.fill_depth(np.ascontiguousarray(array))[0])


def test_fill_depth_is_bit_for_bit_the_command(cli, tmp_path):
    holed = with_holes(plane_depth())
    source, target = tmp_path / "holed.png", tmp_path / "filled.png"
    rangefill.write_depth(holed, source)
    for arguments, options in (([], {}), (["--fast"], {"fast": True}),
                               (["--inpainter", "telea", "--keep-border"],
                                {"inpainter": "telea", "keep_border": True})):
        cli("depth", source, "-o", target, *arguments)
        filled, _ = rangefill.fill_depth(rangefill.read_depth(source), **options)
        assert np.array_equal(filled, rangefill.read_depth(target)), arguments


def test_a_sensor_frame_is_filled_as_the_command_fills_it(cli, shared, tmp_path):
    frame = shared / "depth-real" / "livingroom-00000.png"
    cli("depth", frame, "-o", tmp_path / "filled.png")
    depth = rangefill.read_depth(frame)
    filled, stats = rangefill.fill_depth(depth)
    assert np.array_equal(filled, rangefill.read_depth(tmp_path / "filled.png"))
    assert stats["filled"] == stats["holes"] > 0
    assert (filled > 0).all()


def test_a_colour_guided_fill_is_the_commands_whatever_the_channel_order(cli, shared, tmp_path):
    frame = shared / "depth-real" / "livingroom-00000.png"
    colour_file = shared / "depth-real" / "color" / "livingroom-00000.jpg"
    cli("depth", frame, "--color", colour_file, "-o", tmp_path / "filled.png")
    depth, colour = rangefill.read_depth(frame), rangefill.read_color(colour_file)
    assert colour.shape == depth.shape + (3,) and colour.dtype == np.uint8
    filled, _ = rangefill.fill_depth(depth, color=colour)
    assert np.array_equal(filled, rangefill.read_depth(tmp_path / "filled.png"))
    assert np.array_equal(rangefill.fill_depth(depth, color=colour[:, :, ::-1])[0], filled)
    assert not np.array_equal(rangefill.fill_depth(depth)[0], filled)
    with pytest.raises(ValueError, match="colour image is 320x480"):
        rangefill.fill_depth(depth, color=colour[:, :320])


def test_depth_files_round_trip(tmp_path):
    millimetres = plane_depth()
    metres = millimetres.astype(np.float32) / 1000
    for array, name in ((millimetres, "d.png"), (millimetres, "d.tif"), (metres, "d.tiff"),
                        (metres, "d.exr")):
        rangefill.write_depth(array, tmp_path / name)
        back = rangefill.read_depth(tmp_path / name)
        assert back.dtype == array.dtype and np.array_equal(back, array), name


@pytest.mark.parametrize("backend", rangefill.backends())
def test_every_backend_restores_a_ramp_and_keeps_the_rest(backend):
    y, x = np.mgrid[0:48, 0:48].astype(np.float32)
    image = 0.2 + 0.01 * x + 0.005 * y
    mask = np.zeros(image.shape, np.uint8)
    mask[18:28, 20:30] = 255
    out = rangefill.inpaint(image, mask, backend)
    assert out.dtype == np.float32
    assert np.array_equal(out[mask == 0], image[mask == 0])
    assert np.abs(out - image)[mask > 0].max() < 0.03  # the ramp spans 0.2 to 0.9


def test_backends_lists_the_inpainters():
    assert {"harmonic", "telea", "ns", "mls", "foe"} <= set(rangefill.backends())


def test_invalid_input_raises_value_error_naming_what_is_wrong():
    depth = plane_depth()
    with pytest.raises(ValueError, match="depth: uint16 .* or float32 .* expected, got float64"):
        rangefill.fill_depth(depth.astype(np.float64))
    with pytest.raises(ValueError, match="depth: a 2-D array expected, got shape \\(120, 160, 1\\)"):
        rangefill.fill_depth(depth[..., None])
    with pytest.raises(ValueError, match="unknown"):
        rangefill.fill_depth(depth, inpainter="nope")
    with pytest.raises(ValueError, match="threads"):
        rangefill.fill_depth(depth, threads=0)
    with pytest.raises(ValueError):
        rangefill.fill_depth(depth, np.zeros((3, 3), bool))  # the mask's size
    with pytest.raises(ValueError, match="mask"):
        rangefill.inpaint(depth.astype(np.float32), np.zeros(depth.shape, np.float32), "ns")
    with pytest.raises(ValueError, match="got >u2"):
        rangefill.fill_depth(depth.astype(">u2"))
    with pytest.raises(ValueError, match="empty"):
        rangefill.fill_depth(np.zeros((0, 0), np.uint16))


def test_file_errors_raise_os_error_or_value_error_naming_the_file(tmp_path):
    with pytest.raises(OSError, match="missing.png"):
        rangefill.read_depth(tmp_path / "missing.png")
    text = tmp_path / "text.png"
    text.write_text("not a PNG")
    with pytest.raises(ValueError, match="text.png"):
        rangefill.read_depth(text)
    with pytest.raises(ValueError, match="d.exr"):
        rangefill.write_depth(plane_depth(), tmp_path / "d.exr")  # EXR holds metres
    with pytest.raises(OSError):
        rangefill.write_depth(plane_depth(), tmp_path / "no-such-dir" / "d.png")


def test_two_threads_fill_at_once_and_get_the_single_thread_result():
    frames = [with_holes(plane_depth(480, 640)), with_holes(plane_depth(480, 640))[::-1].copy()]
    alone = [rangefill.fill_depth(frame, inpainter="ns")[0] for frame in frames]
    results = [None, None]

    def fill(i):
        results[i] = rangefill.fill_depth(frames[i], inpainter="ns")[0]

    threads = [threading.Thread(target=fill, args=(i,)) for i in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert all(np.array_equal(a, b) for a, b in zip(alone, results))


def test_the_gil_is_released_while_a_frame_is_filled():
    # While another thread is inside fill_depth this one keeps running Python: were the GIL held,
    # it would wait for the whole fill and count only the turns before and after it.
    y, x = np.mgrid[0:960, 0:1280]
    frame = plane_depth(960, 1280)
    frame[(x - 640) ** 2 + (y - 480) ** 2 < 300 ** 2] = 0
    worker = threading.Thread(target=rangefill.fill_depth, args=(frame,))
    turns = 0
    worker.start()
    while worker.is_alive():
        turns += 1
        time.sleep(0.001)
    assert turns >= 20


def test_the_example_fills_a_folder(tmp_path):
    import pathlib
    import subprocess
    import sys

    folder = tmp_path / "frames"
    folder.mkdir()
    for i in range(3):
        rangefill.write_depth(with_holes(plane_depth())[:, i:], folder / f"frame-{i}.png")
    example = (pathlib.Path(__file__).parents[2] / "python" / "examples" / "fill_depth_folder.py")
    output = subprocess.run([sys.executable, example, folder, "--out", tmp_path / "out",
                             "--no-plot"], check=True, capture_output=True, text=True).stdout
    assert output.count("3 of 3 holes") == 3
    for i in range(3):
        assert (rangefill.read_depth(tmp_path / "out" / f"frame-{i}.png") > 0).all()
