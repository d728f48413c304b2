"""Runs the example of docs/python.md (its first python block) as it is
written, from the repository's root, so the documented example keeps working.

    PYTHONPATH=<build>/python python3 tests/python/run_docs_example.py <repository>
"""
import os
import re
import sys

root = sys.argv[1]
with open(os.path.join(root, "docs", "python.md")) as f:
    blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
if not blocks:
    raise SystemExit("docs/python.md has no python example")
os.chdir(root)
exec(compile(blocks[0], "docs/python.md example", "exec"), {"__name__": "__main__"})
