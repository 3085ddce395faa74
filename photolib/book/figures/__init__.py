"""Figures for the notebooks, one module per chapter part (matplotlib is imported only here)."""
