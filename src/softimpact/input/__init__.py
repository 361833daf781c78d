"""Files in: the TOML reader (:mod:`.toml`) and one module per file format —
bar cases (:mod:`.bar_case`), beam cases (:mod:`.beam_case`), series
(:mod:`.series`) and records (:mod:`.records`). Errors name the file's keys."""
