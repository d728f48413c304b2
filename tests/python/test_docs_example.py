"""Runs the example of docs/python.md (its first python block) as it is
written, from the repository's root, so the documented example keeps working.

    PYTHONPATH=<build>/python python3 -m pytest tests/python/test_docs_example.py
"""
import os
import re

from conftest import REPOSITORY


def test_docs_example(monkeypatch):
    with open(os.path.join(REPOSITORY, "docs", "python.md")) as f:
        blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
    assert blocks, "docs/python.md has no python example"
    monkeypatch.chdir(REPOSITORY)
    exec(compile(blocks[0], "docs/python.md example", "exec"), {"__name__": "__main__"})
