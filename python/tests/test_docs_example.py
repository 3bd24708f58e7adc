"""docs/python.md's example runs as printed: its ```python blocks, in order, in one namespace,
from a scratch folder (what a user pastes into a fresh interpreter) that sees the repository's
data/ and tests/ as its root does (the page names scene files from the root, where a user
pastes it)."""
import os
import re

from conftest import SOURCE

BLOCK = re.compile(r"^```python\n(.*?)^```$", re.S | re.M)


def test_the_pages_python_blocks_run(tmp_path, monkeypatch, capsys):
    with open(os.path.join(SOURCE, "docs", "python.md"), encoding="utf-8") as page:
        blocks = BLOCK.findall(page.read())
    assert blocks, "docs/python.md shows no python block"
    for folder in ("data", "tests"):
        os.symlink(os.path.join(SOURCE, folder), tmp_path / folder)
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__main__"}
    for code in blocks:
        exec(compile(code, "docs/python.md", "exec"), namespace)
    printed = capsys.readouterr().out
    assert "layer density:" in printed and "peak temperature:" in printed
    assert "layer 2: density" in printed and namespace["report"]["layers_done"] == 2
    assert 0 < namespace["track"]["max_temperature"] and len(namespace["settled"]) == 48
