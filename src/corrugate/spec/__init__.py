"""What a user asks for: the spec schema and parser (:mod:`.schema`), its generated reference
(:mod:`.reference`), the options of one design from the command line or web form
(:mod:`.inputs`) and the shipped example specs (:mod:`.examples`)."""
