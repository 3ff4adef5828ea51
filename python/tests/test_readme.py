"""The README's Python example runs as printed (from the repository root)."""

import os
import re

from conftest import ROOT


def test_the_readme_python_example_runs(capsys):
    text = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) == 1
    here = os.getcwd()
    os.chdir(ROOT)
    try:
        scope = {}
        exec(compile(blocks[0], "README.md", "exec"), scope)
    finally:
        os.chdir(here)
    assert scope["image"].shape == (240, 320, 3)
    assert scope["t"].tolist() == [1.0] and scope["transition"].tolist() == [1]
    assert capsys.readouterr().out.startswith("valid")
    # A slot through the prism: a tunnel, so genus 1.
    assert abs(scope["cut"].volume - 2.7) < 1e-12 and scope["cut"].genus == 1
