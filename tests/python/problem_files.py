"""Writing throwaway problem folders for the harness tests."""
from pathlib import Path


def write_problem(root, text, folder="X-1"):
    """root/folder/problem.toml holding `text`, beside a placeholder scene.toml; its path."""
    path = Path(root) / folder
    path.mkdir(parents=True, exist_ok=True)
    (path / "scene.toml").write_text('title = "fake"\n')
    (path / "problem.toml").write_text(text)
    return path / "problem.toml"
