"""The built-in catalogue of friction laws as a table, read from the law files when the site is built.

``{fricgen-laws}`` renders one row per law file of ``fricgen.derive.CATALOGUE``: its name and
reference, the friction expression f and weight as written, the calculi, the parameters with their
defaults and units, and the description. A law added to the catalogue appears without an edit here.
The files are read as TOML data (never evaluated), as fricgen itself reads them.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from docutils import nodes
from sphinx.util.docutils import SphinxDirective

COLUMNS = ("law", "f(u, w, r)", "weight", "calculi", "parameters (default, unit)", "description")


def _cell(*children: nodes.Node) -> nodes.entry:
    entry = nodes.entry()
    paragraph = nodes.paragraph()
    paragraph.extend(children)
    entry += paragraph
    return entry


def _parameters(table: dict) -> list[nodes.Node]:
    parts: list[nodes.Node] = []
    for name, spec in table.items():
        if parts:
            parts.append(nodes.Text("; "))
        unit = f", {spec['unit']}" if spec.get("unit") else ""
        bounds = f", in {spec['range']}" if spec.get("range") else ""
        parts += [nodes.literal(text=name), nodes.Text(f" = {spec.get('default')}{unit}{bounds}")]
    return parts or [nodes.Text("none")]


def law_rows(folder: Path) -> list[dict]:
    """The law files of a catalogue folder, parsed, in name order."""
    return [tomllib.loads(path.read_text(encoding="utf-8-sig")) for path in sorted(folder.glob("*.toml"))]


class FricgenLaws(SphinxDirective):
    """``{fricgen-laws}``: the table of the built-in catalogue."""

    def run(self) -> list[nodes.Node]:
        from fricgen.derive import CATALOGUE

        folder = Path(CATALOGUE)
        for path in folder.glob("*.toml"):
            self.env.note_dependency(str(path))
        table = nodes.table(classes=["fricgen-laws"])
        group = nodes.tgroup(cols=len(COLUMNS))
        table += group
        group.extend(nodes.colspec(colwidth=width) for width in (12, 22, 6, 12, 26, 30))
        head = nodes.thead()
        head += nodes.row("", *(_cell(nodes.Text(title)) for title in COLUMNS))
        body = nodes.tbody()
        for law in law_rows(folder):
            name = [nodes.literal(text=law["name"])] + ([nodes.Text(f" ({law['reference']})")] if law.get("reference") else [])
            weight = law.get("weight") or "none"
            row = nodes.row(
                "",
                _cell(*name),
                _cell(nodes.literal(text=law["friction"])),
                _cell(nodes.literal(text=weight)),
                _cell(nodes.Text(", ".join(law.get("calculi", ["ito", "stratonovich", "hk"])))),
                _cell(*_parameters(law.get("parameters", {}))),
                _cell(nodes.Text(law.get("description", ""))),
            )
            body += row
        group += head
        group += body
        return [table]


def setup(app):
    app.add_directive("fricgen-laws", FricgenLaws)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
