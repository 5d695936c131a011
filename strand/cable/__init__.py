"""Cables and their wires: the cable description (``description``: wires, layers, the built-in
cables of ``data``), the strand's geometry (``geometry``: helical centre lines, cells and
contact pairs) and the dolfinx meshes of the wires (``mesh``)."""
