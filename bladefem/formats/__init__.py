"""File formats: parse files into plain records and write them back, with no physics and no model.

One module (or small group) per format: OpenFAST's label-keyed files share one tolerant reader
(:mod:`._fast_format`, :mod:`._labels`); ElastoDyn main files (:mod:`.elastodyn_main`); BModes decks and section
files (:mod:`.bmodes`, :mod:`.bmodes_support`, :mod:`.bmodes_writer`); windIO turbine files (:mod:`.windio`);
BeamDyn primary and blade files (:mod:`.beamdyn`); HAWC2 structural ``.st`` files, isotropic and fully populated
(:mod:`.hawc2_st`), and the ``c2_def`` reference axis and ``timoschenko_input`` of a HAWC2 main body
(:mod:`.hawc2_htc`); line-numbered YAML (:mod:`.yamlnodes`); rotor-speed schedules (:mod:`.schedule`). Errors name
the file, line and field. The records are mapped onto models in :mod:`bladefem.builders`.
"""

__all__: list[str] = []
