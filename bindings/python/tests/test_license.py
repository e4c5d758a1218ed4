"""The MIT license text travels with every distribution of the package.

The license asks that its text accompany every copy; the wheel carries the
compiled library and programs, so it must carry the text too. setuptools puts
bindings/python/LICENSE (a link to the top LICENSE, not a second copy) in the
sdist and in the wheel's .dist-info/licenses/ (License-File: LICENSE)."""

from __future__ import annotations

from pathlib import Path

HERE = Path(__file__).resolve().parent.parent  # bindings/python


def test_the_package_has_the_tree_license_text() -> None:
    lic = HERE / "LICENSE"
    assert lic.is_file(), "bindings/python/LICENSE is missing: the wheel would carry no license"
    text = lic.read_text()
    assert text.startswith("MIT License") and "Permission is hereby granted" in text
    top = HERE.parent.parent / "LICENSE"
    if top.is_file():  # in a checkout: the same text as the top of the tree
        assert text == top.read_text()


def test_setuptools_picks_it_up_by_its_name() -> None:
    # pyproject.toml gives no license-files, so setuptools' default patterns
    # apply (PEP 639 / setuptools >= 77): LICEN[CS]E* among them
    pyproject = (HERE / "pyproject.toml").read_text()
    assert "license-files" not in pyproject or '"LICENSE"' in pyproject
    assert 'license = "MIT"' in pyproject
