"""Readers and writers of wind-energy input files (ElastoDyn, BModes, windIO, the OpenFAST deck: .fst, AeroDyn,
airfoil polars, InflowWind, ServoDyn) and the input-format dispatcher.

Each format has its own module; :func:`bladefem.io.detect.read_model` chooses the reader by extension and content;
:func:`bladefem.io.openfast_fst.read_openfast_deck` reads a whole OpenFAST deck.
"""

__all__: list[str] = []

