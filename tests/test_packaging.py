"""Packaging: what the wheel and the sdist carry (pyproject.toml, MANIFEST.in), checked from the
source tree so a forgotten package or data folder fails here, not in a user's install.

The full proof -- build both, install each in a fresh virtual environment, run these tests
from the unpacked sdist -- is in CONTRIBUTING.md ("Packages") and is run by hand before a
release; it takes minutes.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import broadsword

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
SETUPTOOLS = PYPROJECT["tool"]["setuptools"]


def test_every_package_folder_is_listed():
    found = {".".join(p.parent.relative_to(ROOT).parts) for p in (ROOT / "broadsword").rglob("__init__.py")}
    missing = found - set(SETUPTOOLS["packages"])
    assert not missing, (
        f"add {sorted(missing)} to [tool.setuptools] packages in pyproject.toml, or the wheel lacks them"
    )


def test_shipped_data_folders_are_packages_of_the_wheel():
    for name, folder in SETUPTOOLS["package-dir"].items():
        assert name in SETUPTOOLS["packages"] and (ROOT / folder).is_dir()
    for name, patterns in SETUPTOOLS["package-data"].items():
        folder = ROOT / SETUPTOOLS["package-dir"].get(name, name.replace(".", "/"))
        for pattern in patterns:
            assert list(folder.glob(pattern)), f"{name}: {pattern} matches nothing in {folder}"


def test_license_is_mit_everywhere():
    assert PYPROJECT["project"]["license"] == "MIT"
    assert PYPROJECT["project"]["license-files"] == ["LICENSE"]
    assert (ROOT / "LICENSE").read_text(encoding="utf-8").startswith("MIT License")
    assert "Typing :: Typed" in PYPROJECT["project"]["classifiers"]
    assert (ROOT / "broadsword" / "py.typed").is_file()


def test_the_sdist_carries_tests_docs_and_data():
    manifest = (ROOT / "MANIFEST.in").read_text(encoding="utf-8").split("\n")
    for folder in ("tests", "docs", "levels", "assets"):
        assert f"graft {folder}" in manifest
    assert (ROOT / "tests" / "conftest.py").is_file()


def test_version_is_one_string_in_one_place():
    assert PYPROJECT["project"]["dynamic"] == ["version"]
    assert broadsword.__version__.count(".") == 2 and all(p.isdigit() for p in broadsword.__version__.split("."))


def test_shipped_data_found_from_the_package():
    from broadsword.data import data_dir, list_levels

    assert (data_dir("levels") / f"{list_levels()[0]}.toml").is_file()
    assert (data_dir("assets") / "sprites").is_dir()


def test_readme_reads_right_on_a_package_index():
    """No relative link (it would point nowhere on a package index page); every image it
    shows exists (and ships in the sdist, docs/ being grafted) and has a caption."""
    import re

    text = (ROOT / "README.md").read_text(encoding="utf-8")
    links = re.findall(r"(?<!!)\[[^\]]*\]\(([^)]+)\)", text)
    assert [link for link in links if not link.startswith(("https://", "http://", "#"))] == []
    images = re.findall(r"!\[([^\]]*)\]\(([^)]+)\)", text)
    assert images and all(caption.strip() for caption, _ in images)
    assert all((ROOT / path).is_file() for _, path in images if not path.startswith("https://"))


def _quick_start_commands() -> list[str]:
    """The README quick start's shell commands (the lines of its ``sh`` blocks)."""
    import re

    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text[text.index("## Quick start") : text.index("\n## ", text.index("## Quick start") + 1)]
    return [line for block in re.findall(r"```sh\n(.*?)```", section, re.S) for line in block.splitlines() if line]


def test_quick_start_installs_into_a_virtual_environment():
    """The README's two commands work where the system Python is externally managed (PEP 668:
    Debian 12, Ubuntu 24.04): each makes a virtual environment and installs into it, never
    with the system's pip; one plays, one runs the tests."""
    commands = _quick_start_commands()
    assert len(commands) == 2
    for command in commands:
        steps = command.split(" && ")
        assert steps[0] == "python3 -m venv .venv"
        assert all(not s.startswith(("python3 -m pip", "pip ")) for s in steps)
        assert steps[1].startswith(".venv/bin/python -m pip install ")
    assert commands[0].endswith("-m broadsword") and commands[1].endswith("-m pytest")


def test_ci_runs_the_readme_test_command_verbatim():
    """``.ci/run`` runs the quick start's test command as the README states it."""
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    test_command = _quick_start_commands()[1]
    assert any(line.startswith(test_command) for line in ci.splitlines())
