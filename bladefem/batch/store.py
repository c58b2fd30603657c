"""Results of a batch as a Parquet dataset: a folder of part files, each written whole (temporary file, then
rename) as results arrive, so an interrupted batch loses nothing that finished. One row per case and mode (or
family and speed, or requirement)."""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..files import atomic_path

PART_PREFIX = "part-"


class ResultStore:
    """The folder ``path`` of Parquet part files."""

    def __init__(self, path: str | os.PathLike) -> None:
        self.path = Path(path)
        if self.path.exists() and not self.path.is_dir():
            raise InputError("exists and is not a folder", file=str(self.path), field="-o")

    def parts(self) -> list[Path]:
        return sorted(self.path.glob(f"{PART_PREFIX}*.parquet")) if self.path.is_dir() else []

    def table(self) -> Any:
        """All rows as one pyarrow Table (empty when there are none); columns missing in a part are null."""
        import pyarrow as pa
        import pyarrow.parquet as pq
        parts = self.parts()
        if not parts:
            return pa.table({})
        return pa.concat_tables([pq.read_table(part) for part in parts], promote_options="default")

    def done_hashes(self) -> set[str]:
        """Hashes of the cases already in the results (finished or failed)."""
        import pyarrow.parquet as pq
        return {h for part in self.parts() for h in pq.read_table(part, columns=["case_hash"])["case_hash"]
                .to_pylist()}

    def drop_failed(self) -> int:
        """Remove the rows of failed cases (each part rewritten whole, or removed when nothing is left), so that a
        resumed batch runs them again; returns how many cases were dropped."""
        import pyarrow.compute as pc
        import pyarrow.parquet as pq
        dropped: set[str] = set()
        for part in self.parts():
            table = pq.read_table(part)
            failed = pc.not_equal(table["status"], "ok")
            if not pc.any(failed).as_py():
                continue
            dropped.update(table.filter(failed)["case_hash"].to_pylist())
            kept = table.filter(pc.invert(failed))
            if kept.num_rows:
                with atomic_path(part) as temporary:
                    pq.write_table(kept, temporary)
            else:
                part.unlink()
        return len(dropped)

    def append(self, rows: Iterable[dict[str, Any]]) -> Path | None:
        """Write the rows as the next part file, whole or not at all."""
        import pyarrow as pa
        import pyarrow.parquet as pq
        rows = list(rows)
        if not rows:
            return None
        self.path.mkdir(parents=True, exist_ok=True)
        numbers = [int(p.stem[len(PART_PREFIX):]) for p in self.parts() if p.stem[len(PART_PREFIX):].isdigit()]
        target = self.path / f"{PART_PREFIX}{max(numbers, default=0) + 1:06d}.parquet"
        columns = list(dict.fromkeys(key for row in rows for key in row))
        table = pa.table({key: [row.get(key) for row in rows] for key in columns})
        with atomic_path(target) as temporary:
            pq.write_table(table, temporary)
        return target
