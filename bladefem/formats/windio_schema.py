"""windIO's own schema for the elastic properties of a turbine file's parts, applied when the windio package is
installed (the errors name the line through bladefem's windIO reader)."""

from __future__ import annotations

from pathlib import Path
from typing import Any


def validate_with_windio(r: Any, parts: list[str]) -> None:
    """Validate the elastic_properties objects of ``parts`` against windIO's 'beam' schema when windio and jsonschema
    exist; ``r`` is the windIO reader (its ``get`` by key path and ``error`` naming the line)."""
    try:
        import jsonschema
        import windIO
    except ImportError:
        return
    import yaml
    schema_file = Path(windIO.__file__).parent / "schemas" / "turbine" / "turbine_schema.yaml"
    try:
        schema = yaml.safe_load(schema_file.read_text())
    except (OSError, yaml.YAMLError):
        return
    beam = dict(schema["definitions"]["beam"], definitions=schema["definitions"])
    for part in parts:
        key = ("components", part, "structure", "elastic_properties")
        value = r.get(key, None)
        if value is None:
            continue
        error = jsonschema.exceptions.best_match(jsonschema.Draft7Validator(beam).iter_errors(value))
        if error is not None:
            raise r.error(f"windIO schema: {error.message}", key + tuple(error.absolute_path))
