"""Typed records: frozen dataclasses whose fields carry their unit in ``metadata["unit"]``
(``quantity``), so that a table of them is written with columns named ``<field>_<unit>``
(``columns``, ``values``). A test set-up's state (``strand.setups``) and the end reactions
(``strand.model.reactions``) are such records.
"""

from __future__ import annotations

from dataclasses import field, fields

__all__ = ["quantity", "columns", "values"]


def quantity(unit: str, doc: str = ""):
    """A dataclass field of a record, with its unit (for the CSV column name)."""
    return field(metadata={"unit": unit, "doc": doc})


def columns(record_type) -> list[str]:
    """CSV column names ``<name>_<unit>`` of a record dataclass (unit-less fields: ``<name>``)."""
    names = []
    for f in fields(record_type):
        unit = f.metadata.get("unit", "")
        names.append(f"{f.name}_{unit}" if unit else f.name)
    return names


def values(record) -> list:
    """The field values of a record, in ``columns`` order."""
    return [getattr(record, f.name) for f in fields(record)]
