"""Sheet materials: the bundled library (``data/materials.toml``) and inline materials
(:mod:`.library`)."""
