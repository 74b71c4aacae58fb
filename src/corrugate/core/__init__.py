"""Infrastructure every layer uses: the errors, units, input limits, files written as one set,
optional extras, the shipped docs and matplotlib figures without pyplot.

Nothing here knows about corrugations; nothing here imports numpy at import time.
"""
