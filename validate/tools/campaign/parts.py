"""A campaign's results on disk: each finished chunk (core.chunks.Chunk) is stored at
once as `parts/<id>.parquet`, atomically (temporary file, then rename), so a killed run
leaves whole parts or none, and a run skips the chunks whose part exists: a finished
campaign run again does no work. The rows are core.summary's; the id is the chunk's
(core.chunks.chunk_id), a hash of what is computed and nothing else."""
from __future__ import annotations

from pathlib import Path

from ...core.summary import COLUMNS, rows_to_table, schema, sort_table
from ...io.output import write_atomic


def write_part(path: Path, rows: list[dict]) -> None:
    import pyarrow.parquet as pq  # lazy: pyarrow only where parts are read or written
    write_atomic(path, lambda tmp: pq.write_table(rows_to_table(rows), tmp))


def part_problem(path: Path, task) -> str | None:
    """Why the part at `path` cannot stand for the chunk `task`'s rows (None: it can):
    unreadable, another schema, or not exactly one row per case of the chunk under its
    engine and setting. A part copied over another, damaged or from another version of
    the table is run again instead of being trusted by its name."""
    import pyarrow.parquet as pq  # lazy: pyarrow only where parts are read or written
    try:
        table = pq.read_table(path)
    except FileNotFoundError:
        return "missing"
    except Exception as e:  # noqa: BLE001 - any unreadable file is a part to run again
        return f"unreadable ({type(e).__name__})"
    if table.schema.remove_metadata() != schema():
        return "another schema"
    want = sorted(c.case for c in task.cases)
    if sorted(table["case"].to_pylist()) != want:
        return f"{table.num_rows} rows whose cases are not the chunk's {len(want)}"
    if set(table["engine"].to_pylist()) != {task.setting.engine} or \
            set(table["setting"].to_pylist()) != {task.setting.label}:
        return "rows of another engine or setting"
    return None


def read_parts(paths) -> "pyarrow.Table":
    import pyarrow as pa  # lazy: pyarrow only where parts are read or written
    import pyarrow.parquet as pq
    tables = [pq.read_table(p, schema=schema()) for p in paths]
    return sort_table(pa.concat_tables(tables) if tables else schema().empty_table())


__all__ = ["COLUMNS", "write_part", "read_parts", "part_problem", "rows_to_table", "sort_table"]
