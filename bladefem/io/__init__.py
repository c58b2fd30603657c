"""Readers and writers of wind-energy input files (ElastoDyn, BModes, windIO) and the input-format dispatcher.

Each format has its own module; :func:`bladefem.io.detect.read_model` chooses the reader by extension and content.
"""
