"""The physics notes travel with the code: every pointer into docs/physics.md names a section that exists."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _anchor(heading: str) -> str:
    """GitHub's anchor of a markdown heading: lower case, punctuation dropped, spaces as hyphens."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def test_every_pointer_into_the_physics_notes_exists():
    notes = (ROOT / "docs" / "physics.md").read_text()
    anchors = {_anchor(line.lstrip("#")) for line in notes.splitlines() if line.startswith("#")}
    sources = [*ROOT.glob("fricgen/**/*.py"), *ROOT.glob("derive/**/*.py"), *ROOT.glob("tests/**/*.py"), ROOT / "README.md"]
    cited = {}
    for path in sources:
        text = path.read_text()
        for match in re.finditer(r"docs/physics\.md((?:#[\w-]+)?(?:(?: and|,) #[\w-]+)*)", text):
            for anchor in re.findall(r"#([\w-]+)", match.group(1)):
                cited.setdefault(anchor, path.relative_to(ROOT))
    assert len(cited) >= 8, cited
    missing = {anchor: str(path) for anchor, path in cited.items() if anchor not in anchors}
    assert not missing, missing


def test_no_pointer_to_a_file_users_do_not_have():
    for path in [*ROOT.glob("fricgen/**/*.py"), *ROOT.glob("derive/**/*.py"), ROOT / "README.md", *ROOT.glob("docs/*.md")]:
        assert "PHYSICS.md" not in path.read_text(), path
