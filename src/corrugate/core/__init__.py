"""Infrastructure every layer uses: the errors, units (read by a grammar of our own,
:mod:`.unit_grammar`), input limits, files written as one set, optional extras, the shipped docs,
matplotlib figures without pyplot, and the one table of design and output parameters
(:mod:`.parameters`).

Nothing here knows about corrugations; nothing here imports numpy at import time.
"""
