"""Mesh files: OBJ (polygon faces), OFF and PLY, through maintained parsers."""

def load(path):  # placeholder until the io module lands
    raise NotImplementedError
