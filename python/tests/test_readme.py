"""The README's Python example runs as printed (from the repository root)."""

from conftest import run_python_block


def test_the_readme_python_example_runs(capsys):
    scope = run_python_block("README.md")
    assert scope["image"].shape == (240, 320, 3)
    assert scope["t"].tolist() == [1.0] and scope["transition"].tolist() == [1]
    assert capsys.readouterr().out.startswith("valid")
    # A slot through the prism: a tunnel, so genus 1.
    assert abs(scope["cut"].volume - 2.7) < 1e-12 and scope["cut"].genus == 1
