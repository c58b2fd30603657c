"""Independent structural models that share only the section-property input with the finite elements."""

__all__: list[str] = []

