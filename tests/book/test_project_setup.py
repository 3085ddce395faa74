"""The README's two set-up commands are what users and CI run; keep them and .ci/run in step."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _readme_commands():
    return re.findall(r"```bash\n(.+?)\n```", (ROOT / "README.md").read_text(encoding="utf-8"))


def test_readme_has_exactly_two_setup_commands():
    commands = _readme_commands()
    assert len(commands) == 2, commands
    main_job, tests = commands
    assert "photolib verify" in main_job and "jupyter-book build ." in main_job
    assert tests.rstrip().endswith("pytest")


def test_ci_runs_the_readme_test_command():
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert _readme_commands()[1] in ci


def test_toc_lists_every_notebook():
    toc = (ROOT / "_toc.yml").read_text(encoding="utf-8")
    for nb in (ROOT / "chapters").glob("*.ipynb"):
        assert f"chapters/{nb.stem}" in toc, f"{nb.name} is not in _toc.yml"


def test_verify_needs_no_test_only_package():
    """`pip install .` installs only the runtime dependencies: `photolib verify` must not import
    OpenCV, pytest or hypothesis (the `test` extra) nor matplotlib (the `book` extra)."""
    import subprocess
    import sys
    code = ("import sys\n"
            "for name in ('cv2', 'pytest', 'hypothesis', 'nbval', 'matplotlib', 'mpl_toolkits'):\n"
            "    sys.modules[name] = None\n"
            "from photolib.book.cli import main\n"
            "sys.exit(main(['verify', '--json']))\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]


def test_pyproject_lists_every_subpackage():
    """Packages are listed by hand in pyproject.toml (textbook/ is mapped in as data): none may be
    forgotten, or `pip install .` would ship a package without its subpackage."""
    import tomllib
    listed = set(tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]["packages"])
    found = {".".join(p.parent.relative_to(ROOT).parts) for p in (ROOT / "photolib").rglob("__init__.py")}
    assert found <= listed, f"not listed in pyproject.toml: {sorted(found - listed)}"
    assert "photolib.book.published" in listed
