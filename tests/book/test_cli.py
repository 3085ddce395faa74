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
                                  ["verify", "--jobs", "0"], ["verify", "--jobs", "two"],
                                  ["show"], ["show", "no-such-example"], ["show", "4.3-dlt", "--chapter", "99"],
                                  ["list", "--chapter", "99"], ["errata", "--chapter", "99"],
                                  ["verify", "--source", "no-such-text"], ["list", "--source", "x"],
                                  ["verify", "--source", "sementsov", "--chapter", "1"]])
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


@pytest.fixture
def one_wrong_status(tmp_path, monkeypatch):
    """A copy of textbook/ in which the first reproduced number of Chapter 1 is recorded as not reproducible."""
    for toml in (ROOT / "textbook").glob("*.toml"):
        shutil.copy(toml, tmp_path / toml.name)
    text = (tmp_path / "ch01.toml").read_text(encoding="utf-8")
    first = text.index('status = "reproduced"')
    (tmp_path / "ch01.toml").write_text(text[:first] + 'status = "not-reproducible"\nreason = "a test"'
                                        + text[first + len('status = "reproduced"'):], encoding="utf-8")
    monkeypatch.setenv("PHOTOLIB_TEXTBOOK", str(tmp_path))
    from photolib.book import textbook
    textbook.load_chapter.cache_clear()
    yield
    monkeypatch.delenv("PHOTOLIB_TEXTBOOK")
    textbook.load_chapter.cache_clear()


def test_a_changed_status_exits_1(one_wrong_status, capsys):
    """Record a wrong status for one published number: verify must flag it and exit 1."""
    assert main(["verify", "--chapter", "1", "--json", "--jobs", "1"]) == 1
    rows = json.loads(capsys.readouterr().out)["rows"]
    changed = [r for r in rows if not r["ok"]]
    assert len(changed) == 1
    assert (changed[0]["status"], changed[0]["observed_status"]) == ("not-reproducible", "reproduced")


def test_only_changed_says_what_changed(one_wrong_status, capsys):
    """--only-changed prints the summary and the one changed row, with the old status, both values,
    the tolerance and the recorded reason."""
    assert main(["verify", "--chapter", "1", "--only-changed", "--jobs", "1"]) == 1
    out = capsys.readouterr().out
    lines = out.splitlines()
    assert "published quantities" in lines[0] and "not-reproducible 1" in out
    assert any(line.startswith("status no longer holds: 1") for line in lines[:3])
    table = [line for line in lines if line.startswith("1   ")]
    assert len(table) == 1 and table[0].rstrip().endswith("CHANGED")
    explanation = " ".join(out[out.index("What changed:"):].split())       # unwrapped
    for fact in ("recorded not-reproducible, now reproduced", "book 0,98421", "computed 0.9842078", "tolerance 5e-06",
                 "now rounds to the printed one", "Recorded reason: a test"):
        assert fact in explanation, fact


def test_verify_json_rows_carry_numbers(capsys):
    assert main(["verify", "--chapter", "4", "--json", "--jobs", "1"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["summary"]["changed"] == 0 and data["chapters"][0]["chapter"] == 4
    dlt = next(r for r in data["rows"] if r["example"] == "4.3-dlt" and r["quantity"] == "L4_img1")
    assert dlt["book_value"] == -96.237 and isinstance(dlt["computed_value"], float)
    assert dlt["delta"] == pytest.approx(dlt["computed_value"] - dlt["book_value"])
    assert dlt["observed_status"] == dlt["status"] and dlt["version"] == photolib.__version__ == data["version"]
    assert dlt["status"] == "input-rounding" and dlt["tolerance"] > 0 and dlt["reason"]
    assert abs(dlt["computed_value"] - dlt["book_value"]) <= dlt["tolerance"]
    erratum = next(r for r in data["rows"] if r["status"] == "erratum" and r["expected"] is not None)
    assert erratum["reason"], "an erratum row carries its diagnosis"


def test_verify_fits_100_columns_with_the_summary_first(capsys):
    assert main(["verify", "--chapter", "1", "--chapter", "4", "--jobs", "1"]) == 0
    lines = capsys.readouterr().out.splitlines()
    from photolib.book.textbook import load_chapter
    total = sum(len(ex.quantities) for n in (1, 4) for ex in load_chapter(n).examples) + \
        sum(len(load_chapter(n).formulas) for n in (1, 4))
    assert lines[0].startswith(f"{total} published quantities and formulas in chapters 1, 4")
    assert max(map(len, lines)) <= 100
    assert main(["verify", "--chapter", "1", "--wide", "--jobs", "1"]) == 0
    assert max(map(len, capsys.readouterr().out.splitlines())) > 100


def test_source_selects_the_entries_of_one_text(capsys):
    """``--source KEY`` keeps exactly the entries whose seed is that text's, across chapters."""
    from photolib.book.textbook import available_chapters, load_chapter, source_seeds
    seeds = source_seeds()
    assert {"chibunichev", "gnss", "hanzl", "mrf", "sementsov"} <= set(seeds)
    expected = {e.id for n in available_chapters() for e in (*load_chapter(n).examples, *load_chapter(n).formulas)
                if e.seed == seeds["gnss"]}
    assert main(["list", "--source", "gnss", "--wide"]) == 0
    out = capsys.readouterr().out
    listed = {line.split()[1] for line in out.splitlines()[1:] if line[:1].isdigit() and " entries;" not in line}
    assert listed == expected and expected
    assert main(["verify", "--source", "gnss", "--json", "--jobs", "1"]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    assert {r["example"] for r in rows} == expected


def test_list_and_show(capsys):
    assert main(["list", "--chapter", "4"]) == 0
    out = capsys.readouterr().out
    assert "4.3-dlt" in out and max(map(len, out.splitlines())) <= 100
    assert main(["show", "4.3-dlt"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("4.3-dlt: §4.3") and "inputs (as printed)" in out
    assert "L4_img1" in out and "input-rounding" in out
    assert main(["show", "4.4.16-essential-matrix"]) == 0          # a formula erratum
    out = capsys.readouterr().out
    assert "printed:" in out and "status: erratum" in out and "diagnosis:" in out


def test_errata_lists_every_erratum_with_its_correction(capsys):
    from photolib.book.errata import errata
    assert main(["errata", "--chapter", "4", "--json"]) == 0
    records = json.loads(capsys.readouterr().out)
    assert len(records) == len(errata([4], recompute=False)) > 0
    assert all(r["status"] in ("erratum", "transcription") and r["diagnosis"] for r in records)
    assert all(r["where"].startswith("§4.") and ", p" in r["where"] for r in records)
    assert main(["errata", "--chapter", "4"]) == 0
    out = capsys.readouterr().out
    assert out.rstrip().endswith(f"{len(records)} errata") and "correct" in out
    assert max(map(len, out.splitlines())) <= 100


def test_errata_marks_transcriptions_and_cites_pages_first(capsys):
    """Both kinds are listed and marked; the page comes first, the OCR lines last; a shared
    diagnosis is printed once."""
    assert main(["errata", "--chapter", "1", "--chapter", "8", "--source", "chibunichev"]) == 0
    out = capsys.readouterr().out
    assert "[transcription]" in out and "[erratum]" in out
    head = next(line for line in out.splitlines() if "(1.8.3) a1 …" in line)
    assert head.startswith("  §1.8, p") and "eq. (1.8.3) a1 … b6 (11 formulas) [erratum]" in head
    assert out.count("The general form is dF_x/dp") == 1
    assert out.index(head) < out.index("lines 572–576")
    transcriptions = [line for line in out.splitlines() if "[transcription]" in line]
    assert len(transcriptions) >= 4 and all(line.lstrip().startswith("§") for line in transcriptions)
    last = out.rstrip().splitlines()[-1]
    assert "errors of the book (erratum)" in last and "defects of the OCR transcription (transcription)" in last


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
