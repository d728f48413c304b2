"""The Python module `bounce` from the outside: load a scene, bake it (a bad
setting, a cancelled bake), open the bake and relight it, and check the
relit patch light against the bake folder's own arrays read with numpy.

    PYTHONPATH=<build>/python python3 -m pytest tests/python/test_bounce_module.py
"""
import json
import os

import numpy as np
import pytest

import bounce
from conftest import SMALL_DENSE_BAKE


def test_load_scene(scene, resources):
    assert scene.triangle_count > 0, "the Cornell box has triangles"
    assert [l["name"] for l in scene.lights] == ["ceiling-point"]
    missing = os.path.join(resources, "scenes", "no-such-scene")
    with pytest.raises(bounce.Error, match="no-such-scene"):
        bounce.load_scene(missing)


def test_bad_settings(scene, tmp_path):
    out = str(tmp_path / "bad")
    with pytest.raises(ValueError, match="voxel_resolution"):
        bounce.bake(scene, out, voxel_resolution=-3)
    with pytest.raises(ValueError, match="codec"):
        bounce.bake(scene, out, codec="jpeg")
    with pytest.raises(ValueError, match="voxel_resolutoin"):
        bounce.bake(scene, out, voxel_resolutoin=8)
    assert not os.path.exists(out), "a refused bake writes nothing"


def test_cancel(scene, cornell, tmp_path):
    out = str(tmp_path / "cancelled")
    calls = []

    def stop_at_third_call(stage, fraction):
        calls.append((stage, fraction))
        return len(calls) < 3

    with pytest.raises(bounce.Cancelled, match="cancelled"):
        bounce.bake(scene, out, progress=stop_at_third_call, **SMALL_DENSE_BAKE)
    assert len(calls) >= 3, "the callable was called until it said stop"
    assert os.listdir(tmp_path) == [], "a cancelled bake leaves nothing"

    # An exception in the callable stops the bake and comes out as itself
    # (the scene given by its path this time).
    def broken(stage, fraction):
        raise KeyError("from the callable")

    with pytest.raises(KeyError, match="from the callable"):
        bounce.bake(cornell, out, progress=broken, **SMALL_DENSE_BAKE)
    assert os.listdir(tmp_path) == [], "a failed bake leaves nothing"


def test_bake(baked):
    folder, manifest, stages = baked
    assert bounce.is_bake_folder(folder), "the bake wrote a bake folder"
    assert len(stages) >= 3, f"progress heard the stages: {stages}"
    with open(os.path.join(folder, "manifest.json")) as f:
        assert json.load(f)["counts"] == manifest["counts"], "the returned manifest is the written one"


def expected_patch_light(folder, lights):
    """b + T b from the folder's arrays: the stored first-hit light of the
    scene's lights (its point lights, then the emissive triangles as one area
    light, the last evaluation light) and the exact matrix T.npy."""
    with open(os.path.join(folder, "manifest.json")) as f:
        manifest = json.load(f)
    first_hit = np.load(os.path.join(folder, "lights_first_hit.npy")).astype(np.float64)
    T = np.load(os.path.join(folder, "T.npy")).astype(np.float64)
    channel_of_rgb = manifest["transport"]["channel_of_rgb"]
    patches = np.load(os.path.join(folder, "patches.npy"))
    n = patches.shape[0]
    assert first_hit.shape[1:] == (n, 3), f"lights_first_hit shape {first_hit.shape}"
    assert T.shape[1:] == (n, n), f"T shape {T.shape}"
    b = first_hit[: len(lights)].sum(axis=0)
    if np.any(patches[:, 12:15] > 0):
        b += first_hit[-1]
    tb = np.stack([T[channel_of_rgb[k]] @ b[:, k] for k in range(3)], axis=1)
    return b, b + tb


def test_relight(baked):
    folder = baked[0]
    bake = bounce.open_bake(folder)
    assert bake.patch_count > 0, "patches"
    assert [l["name"] for l in bake.lights] == ["ceiling-point"]
    light = bake.relight()
    n = bake.patch_count
    for name in ("first_hit", "indirect", "patch_light", "exitance"):
        assert light[name].shape == (n, 3), name
        assert np.all(np.isfinite(light[name])), f"{name} is finite"
    v = bake.vertex_positions.shape[0]
    assert v > 0 and light["vertex_light"].shape == (v, 3)
    assert light["vertex_light"].max() > 0, "the lit mesh is lit"

    b, expected = expected_patch_light(folder, bake.lights)
    scale = np.abs(expected).max()
    assert scale > 0, "the stored light is not all dark"
    b_error = np.abs(light["first_hit"] - b).max() / scale
    error = np.abs(light["patch_light"] - expected).max() / scale
    assert b_error < 1e-5, f"first-hit light differs from lights_first_hit.npy by {b_error:.2e}"
    assert error < 1e-5, f"b + T b differs from numpy's by {error:.2e}"
    assert np.allclose(light["patch_light"], light["first_hit"] + light["indirect"], rtol=1e-5,
                       atol=1e-6 * scale), "patch_light is first_hit + indirect"

    # Moving the light changes the light; an unknown light is an error naming it.
    moved = bake.relight({"ceiling-point": (0.5, 1.0, 0.0)})
    assert not np.allclose(moved["patch_light"], light["patch_light"]), "moving the light changes it"
    with pytest.raises(bounce.Error, match="no-such-light"):
        bake.relight({"no-such-light": (0, 0, 0)})


def test_light_probes(scene, baked, tmp_path):
    """A bake with light_probes="on": each probe stands at the centre of an
    empty cell that shares a face with an occupied one (voxels.npy and the
    manifest's grid, read with numpy); relight() gives 9 RGB SH coefficients
    per probe; a bake without probes gives none."""
    out = str(tmp_path / "probes")
    manifest = bounce.bake(scene, out, light_probes="on", **SMALL_DENSE_BAKE)
    bake = bounce.open_bake(out)
    positions = bake.probe_positions
    assert positions.shape == (manifest["light_probes"]["probes"], 3)
    assert positions.shape[0] > 0, "the Cornell box has room for probes"
    grid = manifest["grid"]
    cell = (positions - np.array(grid["origin"])) / grid["cell_size"] - 0.5
    ijk = np.rint(cell).astype(int)
    assert np.abs(cell - ijk).max() < 1e-3, "probes stand at cell centres"
    occupied = {tuple(int(c) for c in v[0:3]) for v in np.load(os.path.join(out, "voxels.npy"))}
    for c in map(tuple, ijk):
        assert c not in occupied, f"probe in occupied cell {c}"
        neighbours = [tuple(np.add(c, d)) for d in np.vstack([np.eye(3, dtype=int), -np.eye(3, dtype=int)])]
        assert any(n in occupied for n in neighbours), f"probe cell {c} is next to no surface"

    sh = bake.relight()["probe_sh"]
    assert sh.shape == (positions.shape[0], 9, 3)
    assert np.all(np.isfinite(sh))
    assert sh[:, 0, :].min() > 0, "every probe receives some bounced light"
    without = str(tmp_path / "no-probes")
    bounce.bake(scene, without, light_probes="off", **SMALL_DENSE_BAKE)
    assert bounce.open_bake(without).relight()["probe_sh"].shape == (0, 9, 3)

    # Between the probes: at a probe, that probe's SH exactly; halfway
    # between two neighbours, a blend of probes, so within their range.
    for i in range(0, positions.shape[0], max(1, positions.shape[0] // 8)):
        at = bake.probe_sh_at(positions[i])
        assert at.shape == (9, 3) and at.dtype == np.float32
        assert np.array_equal(at, sh[i]), f"probe {i}'s own SH"
    step = grid["cell_size"] * np.array([1.0, 0.0, 0.0])
    pair = next(i for i in range(positions.shape[0])
                if np.abs(positions - (positions[i] + step)).max(axis=1).min() < 1e-4)
    between = bake.probe_sh_at(positions[pair] + 0.5 * step)
    assert np.all(between >= sh.min(axis=0) - 1e-6) and np.all(between <= sh.max(axis=0) + 1e-6)
    assert between[0, 0] > 0, "the blend is lit"
    with pytest.raises(bounce.Error):
        bounce.open_bake(without).probe_sh_at((0.0, 1.0, 0.0))
