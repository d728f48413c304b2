"""What the Python tests share: the repository's resources (ctest passes
BOUNCE_RESOURCES; run by hand, the folder next to tests/) and one small bake
of the Cornell box, made once per session.

    PYTHONPATH=<build>/python python3 -m pytest tests/python
"""
import os

import pytest

import bounce

REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# Small enough to bake in a few seconds; dense, so the folder holds T.npy.
SMALL_DENSE_BAKE = dict(voxel_resolution=8, codec="dense")


@pytest.fixture(scope="session")
def resources():
    return os.environ.get("BOUNCE_RESOURCES", os.path.join(REPOSITORY, "resources"))


@pytest.fixture(scope="session")
def cornell(resources):
    return os.path.join(resources, "scenes", "cornell-box")


@pytest.fixture(scope="session")
def scene(cornell):
    return bounce.load_scene(cornell)


@pytest.fixture(scope="session")
def baked(scene, tmp_path_factory):
    """(bake folder, the manifest bounce.bake returned, the stages progress heard)."""
    out = str(tmp_path_factory.mktemp("bake") / "cornell")
    stages = []

    def note(stage, fraction):
        assert 0.0 <= fraction <= 1.0, f"fraction {fraction}"
        stages.append(stage)

    manifest = bounce.bake(scene, out, progress=note, **SMALL_DENSE_BAKE)
    return out, manifest, set(stages)
