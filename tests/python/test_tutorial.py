"""docs/guide/python.md runs: every ```python block, in order, in one namespace, from a scratch
folder that sees the repository's data/ (so a user's copy of the tour works as printed)."""
import os
import pathlib
import re

SOURCE = pathlib.Path(os.environ.get("LIMSURF_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def test_the_python_guide_runs(tmp_path, monkeypatch):
    text = (SOURCE / "docs" / "guide" / "python.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) >= 5
    (tmp_path / "data").symlink_to(SOURCE / "data")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    for number, block in enumerate(blocks, start=1):
        exec(compile(block, f"python.md block {number}", "exec"), namespace)
