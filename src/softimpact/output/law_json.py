"""Moved to :mod:`softimpact.formats.law_json` (read and written there); kept so old imports work."""

from ..formats.law_json import FAMILY, law_json, law_summary, read_law

__all__ = ["FAMILY", "law_summary", "law_json", "read_law"]
