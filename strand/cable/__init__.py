"""Cables and their wires: the cable description (``description``: wires, layers, the built-in
cables of ``data``, read with ``input_file``), the strand's geometry (``geometry``: helical
centre lines, cells and contact pairs; ``facing``: the facing stations of its layers), the
dolfinx meshes of the wires (``mesh``) and pictures of them (``pictures``: off-screen, wires as
tubes)."""
