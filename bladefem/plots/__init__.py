"""Figures: Campbell diagrams (matplotlib) and mode pictures."""
