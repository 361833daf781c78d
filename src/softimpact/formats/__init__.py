"""Files both read and written: the one place each layout lives, imported by input/ and output/.

- :mod:`.law_json` — law.json, a soft projectile's contact law identified by ``softimpact identify``;
- :mod:`.scaling_json` — scaling.json, the scaling constants α1–α4 of eqs (4)–(7) from ``softimpact fit``;
- :mod:`._json` — JSON text as every softimpact file writes it (numpy → plain values, the version added).
"""
