"""Moved to :mod:`softimpact.formats.scaling_json` (read and written there); kept so old imports work."""

from ..formats.scaling_json import read_scaling_law, scaling_json, scaling_summary

__all__ = ["scaling_summary", "scaling_json", "read_scaling_law"]
