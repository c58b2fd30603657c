"""Figures: Campbell diagrams (matplotlib) and mode pictures."""

__all__: list[str] = []

