"""Adapters from the inputs recorded in ``textbook/`` to library calls, one module per chapter part
(``ch01.py``, ``ch01_rotation.py``, ``ch01_geometry.py``, ``ch01_resection.py``, ``ch01_digital.py``).

Each function takes an example's ``inputs`` table and returns ``{quantity name: value}``; the
work itself is done by the library modules named in the example's ``calls`` field.
"""
