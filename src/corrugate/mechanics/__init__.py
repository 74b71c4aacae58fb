"""The stiffness, strength and mass models of an OADLC panel (docs/theory.md sections 3-4, 9).

* :mod:`.moduli`: the equivalent moduli of one layer, as named variants (paper, xia, refined);
* :mod:`.springs`: facets to layer springs (section 3.2);
* :mod:`.offaxis`: the assembly's directional stiffness under each support condition (3.3);
* :mod:`.behaviours`: the registry of support conditions and load cases, each one entry with its
  model, its solver bounds, its FE fixture and its label; :mod:`.supports`: the built-in entries
  (free, frame), one module each;
* :mod:`.buckling`: buckling estimates; :mod:`.strength`: the peak facet stress under a load and its
  margin against the material's allowable stress (section 9); :mod:`.mass`: the mass of every cut
  part (section 4);
* :mod:`.profiles`: Xia's general equivalent-plate theory, a cross-check of the zig-zag moduli.
"""
