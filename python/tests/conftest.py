"""Shared fixtures: paths into the repository's fixtures and a seeded generator;
the runner of a page's Python example."""

import os
import pathlib
import re

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "fixtures"


@pytest.fixture
def fixtures() -> pathlib.Path:
    return FIXTURES


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(20261125)


def run_python_block(page: str) -> dict:
    """Runs the one ```python block of `page` (a path from the repository's
    root) from the root, as a reader would, and returns its variables."""
    text = (ROOT / page).read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) == 1, f"{page}: {len(blocks)} python blocks"
    here = os.getcwd()
    os.chdir(ROOT)
    try:
        scope: dict = {}
        exec(compile(blocks[0], page, "exec"), scope)
    finally:
        os.chdir(here)
    return scope
