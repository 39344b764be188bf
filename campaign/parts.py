"""A campaign's results on disk: each finished chunk (core.executor.Chunk) is stored at
once as `parts/<id>.parquet`, atomically (temporary file, then rename), so a killed run
leaves whole parts or none, and a run skips the chunks whose part exists: a finished
campaign run again does no work. The rows are core.summary's; the id is the chunk's
(core.executor.chunk_id), a hash of what is computed and nothing else."""
from __future__ import annotations

from pathlib import Path

from isorock.validate.core.summary import COLUMNS, rows_to_table, schema, sort_table


def write_part(path: Path, rows: list[dict]) -> None:
    import pyarrow.parquet as pq
    from isorock.validate.io.output import write_atomic
    write_atomic(path, lambda tmp: pq.write_table(rows_to_table(rows), tmp))


def read_parts(paths) -> "pyarrow.Table":
    import pyarrow as pa
    import pyarrow.parquet as pq
    tables = [pq.read_table(p, schema=schema()) for p in paths]
    return sort_table(pa.concat_tables(tables) if tables else schema().empty_table())


__all__ = ["COLUMNS", "write_part", "read_parts", "rows_to_table", "sort_table"]
