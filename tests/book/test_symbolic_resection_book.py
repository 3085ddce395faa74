"""The book adapter of §1.9: the reconstructed angle equation against the printed partials."""

from photolib.book.ch01_resection import angle_reconstruction_check


def test_reconstructed_angle_equation_gives_printed_partials():
    for eq in ("1.9.1", "1.9.2"):
        assert angle_reconstruction_check({"equation": eq}) == {"printed_equals_derived": False}
