"""`cmake --install` puts the module where the README says, and a Python
started afresh imports it from there (not from the build folder).

ctest passes the build folder, the cmake program and the install folder the
build computed (BOUNCE_BUILD_DIR, BOUNCE_CMAKE, BOUNCE_PYTHON_INSTALL_DIR).
"""
import os
import subprocess
import sys

import pytest


def environment(name):
    value = os.environ.get(name)
    if not value:
        pytest.skip(f"{name} is not set (ctest sets it)")
    return value


def test_installed_module_imports(tmp_path, cornell):
    build = environment("BOUNCE_BUILD_DIR")
    cmake = environment("BOUNCE_CMAKE")
    site = environment("BOUNCE_PYTHON_INSTALL_DIR")
    prefix = tmp_path / "prefix"
    subprocess.run([cmake, "--install", build, "--component", "python", "--prefix", str(prefix)],
                   check=True, capture_output=True)
    installed = prefix / site
    assert any(f.startswith("bounce.") and f.endswith(".so") for f in os.listdir(installed)), \
        f"no module in {installed}: {os.listdir(installed)}"

    script = ("import bounce; print(bounce.__file__); "
              f"print(bounce.load_scene({cornell!r}).triangle_count)")
    env = dict(os.environ, PYTHONPATH=str(installed))
    run = subprocess.run([sys.executable, "-c", script], env=env, check=True, capture_output=True,
                         text=True)
    module_file, triangles = run.stdout.split()
    assert os.path.dirname(module_file) == str(installed), module_file
    assert int(triangles) > 0
