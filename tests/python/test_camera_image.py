"""Bake.camera_image() gives the scene camera's pictures as numpy arrays, the
same pictures `bounce solve` writes (camera_*.exr, linear float32), read
back here through oiiotool: the two must agree to float precision.

ctest passes the bounce program (BOUNCE_CLI); oiiotool comes with
openimageio-tools.
"""
import os
import re
import shutil
import subprocess

import numpy as np
import pytest

import bounce

WIDTH, HEIGHT, GATHER_RAYS = 40, 30, 32


def read_exr(path):
    """The pixels of a float EXR as oiiotool --dumpdata prints them
    ("Pixel (x, y): r g b", nine decimals), height x width x 3."""
    text = subprocess.run(["oiiotool", "--dumpdata", path], check=True, capture_output=True,
                          text=True).stdout
    pixels = {}
    for line in text.splitlines():
        m = re.match(r"\s*Pixel \((\d+), (\d+)\):\s+(\S+) (\S+) (\S+)", line)
        if m:
            pixels[int(m[2]), int(m[1])] = [float(v) for v in m.groups()[2:]]
    height, width = max(pixels)[0] + 1, max(k[1] for k in pixels) + 1
    out = np.zeros((height, width, 3))
    for (y, x), rgb in pixels.items():
        out[y, x] = rgb
    return out


def solve_pictures(folder, out):
    cli = os.environ.get("BOUNCE_CLI")
    if not cli or not shutil.which("oiiotool"):
        pytest.skip("needs BOUNCE_CLI (ctest sets it) and oiiotool")
    subprocess.run([cli, "solve", folder, "--out", out, "--no-mesh", "--width", str(WIDTH),
                    "--height", str(HEIGHT), "--samples", "1", "--camera-gather-rays",
                    str(GATHER_RAYS)], check=True, capture_output=True)
    return {part: read_exr(os.path.join(out, f"camera_{part}.exr"))
            for part in ("direct", "indirect", "full")}


def test_camera_image_is_what_solve_renders(baked, tmp_path):
    folder = baked[0]
    images = bounce.open_bake(folder).camera_image(WIDTH, HEIGHT, samples=1,
                                                   gather_rays=GATHER_RAYS)
    for part in ("direct", "indirect", "full"):
        assert images[part].shape == (HEIGHT, WIDTH, 3) and images[part].dtype == np.float32
    assert images["coverage"].shape == (HEIGHT, WIDTH)
    assert images["indirect"].max() > 0, "the camera sees indirect light"
    assert np.allclose(images["full"], images["direct"] + images["indirect"], rtol=1e-5,
                       atol=1e-6 * images["full"].max())

    expected = solve_pictures(folder, str(tmp_path / "solve"))
    for part in ("direct", "indirect", "full"):
        scale = np.abs(expected[part]).max()
        error = np.abs(images[part] - expected[part]).max() / scale
        assert expected[part].shape == images[part].shape and error < 1e-5, f"camera {part}: differs from bounce solve's by {error:.2e}"


def test_camera_image_refuses_bad_sizes(baked):
    bake = bounce.open_bake(baked[0])
    with pytest.raises(bounce.Error):
        bake.camera_image(0, 10)
    with pytest.raises(bounce.Error, match="gather_rays"):
        bake.camera_image(8, 6, gather_rays=-1)
