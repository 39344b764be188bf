"""The block on its base in Drake (pydrake): the third contact engine (docs/drake.md)."""
