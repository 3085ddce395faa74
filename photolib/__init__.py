"""photolib — companion library to A.G. Chibunichev, *Фотограмметрия* (MIIGAiK, 2022).

Modules mirror the book's chapters:

* :mod:`photolib.rotation` — rotation matrices and quaternions (§1.3)
* :mod:`photolib.camera` — interior and exterior orientation, Brown distortion (§1.2–§1.3)
* :mod:`photolib.single_image` — central projection, collinearity, horizontal and tilted images (§1.1, §1.4–§1.7)
* :mod:`photolib.resection` — space resection (§1.8, §1.9)
* :mod:`photolib.digital` — pixel coordinates and resampling (§1.10)
* :mod:`photolib.interior` — interior orientation from fiducial marks (§1.11)
* :mod:`photolib.scanners` — photogrammetric scanners, Table 1.1 (§1.12)
* :mod:`photolib.image_pair` — image pair: intersection, relative and absolute orientation (Chapter 2)
* :mod:`photolib.bundle`, :mod:`photolib.synthetic` — bundle adjustment (§3.5) and synthetic aerial blocks
* :mod:`photolib.conventions` — conversions to Western, Hanzl's and OpenCV's conventions
* :mod:`photolib.book.errata` — the errata list generated from ``textbook/``
* :mod:`photolib.lsq` — the one least-squares engine, (1.8.5)–(1.8.10), with the block reduction of §3.5
* :mod:`photolib.derivations` — sympy models and the Jacobians derived from them
* :mod:`photolib.book.textbook`, :mod:`photolib.book.verify` — the book's published numbers and their check
"""

__version__ = "0.1.0"
