"""The command line as a user meets it: version, usage errors, a changed status, an installed wheel."""

import json
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import photolib
from photolib.book.cli import main

ROOT = Path(__file__).resolve().parents[2]


def test_version(capsys):
    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0
    assert capsys.readouterr().out.strip() == f"photolib {photolib.__version__}"


@pytest.mark.parametrize("argv", [["verify", "--chapter", "99"], ["verify", "--chapter", "x"],
                                  ["verify", "--no-such-flag"], ["no-such-command"], [],
                                  ["verify", "--jobs", "0"], ["verify", "--jobs", "two"]])
def test_usage_errors_are_one_line_and_exit_2(argv, capsys):
    try:
        code = main(argv)
    except SystemExit as done:
        code = done.code
    assert code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("photolib") and "error" in err and "\n" not in err, err
    assert "Traceback" not in err


def test_unknown_chapter_names_the_available_ones(capsys):
    assert main(["verify", "--chapter", "99"]) == 2
    err = capsys.readouterr().err
    assert "chapter 99" in err and "1, 2, 3, 4" in err and "11" in err


def test_parallel_verify_gives_the_same_rows_in_the_same_order():
    """Worker processes (forked) check the entries of chapter 4; the rows equal the serial run's."""
    from photolib.book.verify import verify
    serial = [r.as_dict() for r in verify([4], jobs=1)]
    parallel = [r.as_dict() for r in verify([4], jobs=2)]
    assert parallel == serial and len(serial) > 100


def test_a_changed_status_exits_1(tmp_path, monkeypatch, capsys):
    """Record a wrong status for one published number: verify must flag it and exit 1."""
    for toml in (ROOT / "textbook").glob("*.toml"):
        shutil.copy(toml, tmp_path / toml.name)
    text = (tmp_path / "ch01.toml").read_text(encoding="utf-8")
    first = text.index('status = "reproduced"')
    (tmp_path / "ch01.toml").write_text(text[:first] + 'status = "not-reproducible"\nreason = "a test"'
                                        + text[first + len('status = "reproduced"'):], encoding="utf-8")
    monkeypatch.setenv("PHOTOLIB_TEXTBOOK", str(tmp_path))
    from photolib.book import textbook
    textbook.load_chapter.cache_clear() if hasattr(textbook.load_chapter, "cache_clear") else None
    try:
        assert main(["verify", "--chapter", "1", "--json"]) == 1
        rows = json.loads(capsys.readouterr().out)["rows"]
        assert sum(not r["ok"] for r in rows) == 1
    finally:
        monkeypatch.delenv("PHOTOLIB_TEXTBOOK")
        textbook.load_chapter.cache_clear() if hasattr(textbook.load_chapter, "cache_clear") else None


def test_the_wheel_carries_the_published_numbers_and_verifies_outside_the_checkout(tmp_path):
    """`pip install .` (not editable): the wheel ships textbook/ as photolib.book.published, and
    `photolib verify` run from another directory finds it (no checkout beside the package)."""
    built = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation",
                            "-q", "-w", str(tmp_path / "dist"), str(ROOT)],
                           capture_output=True, text=True, timeout=600)
    if built.returncode != 0 and "No module named" in built.stderr:
        pytest.skip(f"cannot build a wheel here: {built.stderr.strip().splitlines()[-1]}")
    assert built.returncode == 0, built.stderr[-2000:]
    wheel = next((tmp_path / "dist").glob("photolib-*.whl"))
    names = zipfile.ZipFile(wheel).namelist()
    shipped = {Path(n).name for n in names if n.startswith("photolib/book/published/")}
    assert {p.name for p in (ROOT / "textbook").glob("ch*.toml")} <= shipped
    site = tmp_path / "site"
    zipfile.ZipFile(wheel).extractall(site)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    env = {"PYTHONPATH": str(site), "PATH": "/usr/bin:/bin"}
    done = subprocess.run([sys.executable, "-c",
                           "import sys, photolib; print(photolib.__file__); "
                           "from photolib.book.cli import main; sys.exit(main(['verify', '--chapter', '1']))"],
                          capture_output=True, text=True, cwd=elsewhere, env=env, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.splitlines()[0].startswith(str(site)), "the checkout was imported, not the wheel"
    assert "status no longer holds: 0" in done.stdout
