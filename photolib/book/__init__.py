"""Adapters from the inputs recorded in ``textbook/`` to library calls, one module per chapter.

Each function takes an example's ``inputs`` table and returns ``{quantity name: value}``; the
work itself is done by the library modules named in the example's ``calls`` field.
"""
