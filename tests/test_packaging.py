"""The install layout: one import root. pyproject.toml lists every package explicitly (derive/ and
generated/ are mapped to fricgen.derive and fricgen.generated), so a package added to the tree but
not to the list would be missing from a wheel; this test catches that."""

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CONFIG = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]


def _folder(package: str) -> Path:
    """The repository folder of a package, through the longest package-dir entry that holds it."""
    top = max((p for p in CONFIG["package-dir"] if package == p or package.startswith(p + ".")), key=len)
    return ROOT / CONFIG["package-dir"][top] / package.removeprefix(top).lstrip(".").replace(".", "/")


def _packages_in_tree() -> set[str]:
    return {
        ".".join([package, *init.parent.relative_to(ROOT / folder).parts])
        for package, folder in CONFIG["package-dir"].items()
        for init in (ROOT / folder).rglob("__init__.py")
    }


def test_every_package_of_the_tree_is_listed_once():
    assert sorted(CONFIG["packages"]) == sorted(_packages_in_tree())


def test_one_import_root():
    assert {name.split(".")[0] for name in CONFIG["packages"]} == {"fricgen"}
    assert CONFIG["package-dir"] == {"fricgen": "fricgen", "fricgen.derive": "derive", "fricgen.generated": "generated"}


def test_package_data_lies_in_listed_packages():
    for package, patterns in CONFIG["package-data"].items():
        assert package in CONFIG["packages"]
        assert all(list(_folder(package).glob(pattern)) for pattern in patterns), (package, patterns)
