"""The Python module `bounce` from the outside: load a scene, bake it (a bad
setting, a cancelled bake), open the bake and relight it, and check the
relit patch light against the bake folder's own arrays read with numpy.

    PYTHONPATH=<build>/python python3 tests/python/test_bounce_module.py <resources>
"""
import json
import os
import sys
import tempfile

import numpy as np

import bounce

RESOURCES = sys.argv[1]
CORNELL = os.path.join(RESOURCES, "scenes", "cornell-box")
# Small enough to bake in a few seconds; dense, so the folder holds T.npy.
SETTINGS = dict(voxel_resolution=8, codec="dense")


def check(condition, what):
    if not condition:
        raise AssertionError(what)


def expect_raises(kind, words, call):
    try:
        call()
    except kind as e:
        for w in words:
            check(w in str(e), f"{kind.__name__} '{e}' does not name '{w}'")
        return e
    raise AssertionError(f"expected {kind.__name__} naming {words}")


def test_load_scene():
    scene = bounce.load_scene(CORNELL)
    check(scene.triangle_count > 0, "the Cornell box has triangles")
    check([l["name"] for l in scene.lights] == ["ceiling-point"], f"lights: {scene.lights}")
    missing = os.path.join(RESOURCES, "scenes", "no-such-scene")
    expect_raises(bounce.Error, ["no-such-scene"], lambda: bounce.load_scene(missing))
    return scene


def test_bad_settings(scene, tmp):
    out = os.path.join(tmp, "bad")
    expect_raises(ValueError, ["voxel_resolution"],
                  lambda: bounce.bake(scene, out, voxel_resolution=-3))
    expect_raises(ValueError, ["codec"], lambda: bounce.bake(scene, out, codec="jpeg"))
    expect_raises(ValueError, ["voxel_resolutoin"],
                  lambda: bounce.bake(scene, out, voxel_resolutoin=8))
    check(not os.path.exists(out), "a refused bake writes nothing")


def test_cancel(scene, tmp):
    out = os.path.join(tmp, "cancelled")
    calls = []

    def stop_at_form_factors(stage, fraction):
        calls.append((stage, fraction))
        return len(calls) < 3

    expect_raises(bounce.Cancelled, ["cancelled"],
                  lambda: bounce.bake(scene, out, progress=stop_at_form_factors, **SETTINGS))
    check(len(calls) >= 3, "the callable was called until it said stop")
    check(sorted(os.listdir(tmp)) == [], f"a cancelled bake leaves nothing: {os.listdir(tmp)}")

    # An exception in the callable stops the bake and comes out as itself
    # (the scene given by its path this time).
    def broken(stage, fraction):
        raise KeyError("from the callable")

    expect_raises(KeyError, ["from the callable"],
                  lambda: bounce.bake(CORNELL, out, progress=broken, **SETTINGS))
    check(sorted(os.listdir(tmp)) == [], f"a failed bake leaves nothing: {os.listdir(tmp)}")


def test_bake(scene, tmp):
    out = os.path.join(tmp, "cornell")
    stages = set()

    def note(stage, fraction):
        check(0.0 <= fraction <= 1.0, f"fraction {fraction}")
        stages.add(stage)

    manifest = bounce.bake(scene, out, progress=note, **SETTINGS)
    check(bounce.is_bake_folder(out), "the bake wrote a bake folder")
    check(len(stages) >= 3, f"progress heard the stages: {stages}")
    with open(os.path.join(out, "manifest.json")) as f:
        check(json.load(f)["counts"] == manifest["counts"], "the returned manifest is the written one")
    return out


def expected_patch_light(folder, lights):
    """b + T b from the folder's arrays: the stored first-hit light of the
    scene's lights (its point lights, then the emissive triangles as one area
    light, the last evaluation light) and the exact matrix T.npy."""
    manifest = json.load(open(os.path.join(folder, "manifest.json")))
    first_hit = np.load(os.path.join(folder, "lights_first_hit.npy")).astype(np.float64)
    T = np.load(os.path.join(folder, "T.npy")).astype(np.float64)
    channel_of_rgb = manifest["transport"]["channel_of_rgb"]
    patches = np.load(os.path.join(folder, "patches.npy"))
    n = patches.shape[0]
    check(first_hit.shape[1:] == (n, 3), f"lights_first_hit shape {first_hit.shape}")
    check(T.shape[1:] == (n, n), f"T shape {T.shape}")
    b = first_hit[: len(lights)].sum(axis=0)
    if np.any(patches[:, 12:15] > 0):
        b += first_hit[-1]
    tb = np.stack([T[channel_of_rgb[k]] @ b[:, k] for k in range(3)], axis=1)
    return b, b + tb


def test_relight(folder, tmp):
    bake = bounce.open_bake(folder)
    check(bake.patch_count > 0, "patches")
    check([l["name"] for l in bake.lights] == ["ceiling-point"], f"lights: {bake.lights}")
    light = bake.relight()
    n = bake.patch_count
    for name in ("first_hit", "indirect", "patch_light", "exitance"):
        check(light[name].shape == (n, 3), f"{name}: {light[name].shape}")
        check(np.all(np.isfinite(light[name])), f"{name} is finite")
    v = bake.vertex_positions.shape[0]
    check(v > 0 and light["vertex_light"].shape == (v, 3), f"vertex light {light['vertex_light'].shape}")
    check(light["vertex_light"].max() > 0, "the lit mesh is lit")

    b, expected = expected_patch_light(folder, bake.lights)
    scale = np.abs(expected).max()
    check(scale > 0, "the stored light is not all dark")
    b_error = np.abs(light["first_hit"] - b).max() / scale
    error = np.abs(light["patch_light"] - expected).max() / scale
    print(f"relit b + T b against numpy: max error {error:.2e} of the largest value (b: {b_error:.2e})")
    check(b_error < 1e-5, f"first-hit light differs from lights_first_hit.npy by {b_error:.2e}")
    check(error < 1e-5, f"b + T b differs from numpy's by {error:.2e}")
    check(np.allclose(light["patch_light"], light["first_hit"] + light["indirect"], rtol=1e-5, atol=1e-6 * scale),
          "patch_light is first_hit + indirect")

    # Moving the light changes the light; an unknown light is an error naming it.
    moved = bake.relight({"ceiling-point": (0.5, 1.0, 0.0)})
    check(not np.allclose(moved["patch_light"], light["patch_light"]), "moving the light changes the light")
    expect_raises(bounce.Error, ["no-such-light"], lambda: bake.relight({"no-such-light": (0, 0, 0)}))


def main():
    scene = test_load_scene()
    with tempfile.TemporaryDirectory() as root:
        tmp = os.path.join(root, "failed")
        os.mkdir(tmp)
        test_bad_settings(scene, tmp)
        test_cancel(scene, tmp)
        folder = test_bake(scene, root)
        test_relight(folder, root)
    print("ok")


if __name__ == "__main__":
    main()
