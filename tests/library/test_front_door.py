"""`import photolib` offers the main entry points, lazily (importing the package stays light)."""

import subprocess
import sys

import photolib


def test_every_entry_point_resolves_and_is_listed():
    for name in photolib.__all__:
        assert getattr(photolib, name) is not None, name
    assert set(photolib.__all__) <= set(dir(photolib))
    for name in ("space_resection", "forward_intersection", "relative_orientation", "absolute_orientation",
                 "bundle_adjustment", "dlt_resection", "fundamental_matrix", "essential_matrix",
                 "homography_dlt", "rotation_matrix", "rotation_angles"):
        assert name in photolib.__all__, name


def test_entry_points_are_the_modules_own_functions():
    from photolib import image_pair, resection, rotation
    assert photolib.space_resection is resection.space_resection
    assert photolib.relative_orientation is image_pair.relative_orientation
    assert photolib.rotation_matrix is rotation.rotation_matrix


def test_unknown_attribute_is_an_attribute_error():
    try:
        photolib.no_such_function
    except AttributeError as exc:
        assert "no_such_function" in str(exc)
    else:
        raise AssertionError("no AttributeError")


def test_importing_the_package_loads_neither_sympy_nor_scipy():
    code = "import sys, photolib; print(sorted(m for m in ('sympy', 'scipy') if m in sys.modules))"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_no_entry_point_shadows_a_module():
    """`from photolib import <module>` must give the module, so no entry point may share its name."""
    assert not set(photolib._ENTRY_POINTS) & set(photolib._MODULES)
