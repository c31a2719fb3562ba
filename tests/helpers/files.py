"""Small file helpers shared by the tests that write input files."""

from __future__ import annotations

from pathlib import Path


def write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def line_of(path: Path, needle: str) -> int:
    """1-based line of the first line containing ``needle`` (independent of the tool)."""
    for number, line in enumerate(path.read_text().splitlines(), start=1):
        if needle in line:
            return number
    raise AssertionError(needle)


#: A small batch: a desk-demo gear pair (PLA) and three desk-demo shoes (resin).
SMALL_BATCH = """\
parts:
  - name: pair
    kind: gear-pair
    design: desk-demo
    printer: fdm-0.4-pla
    overrides: {thickness: 2}
  - name: shoes
    kind: shoe
    design: desk-demo
    printer: resin-0.05-standard
    quantity: 3
    overrides: {width: 12}
"""


def printer_profile_without_band(folder: Path) -> Path:
    """The FDM PLA printer preset with its ``band:`` block left out, written into ``folder``."""
    profiles = Path(__file__).resolve().parents[2] / "profiles"
    kept, skipping = [], False
    for line in (profiles / "fdm-0.4-pla.yaml").read_text(encoding="utf-8").splitlines():
        if line.startswith("band:"):
            skipping = True
            continue
        if skipping and (line.startswith(" ") or line.startswith("#")):
            continue
        skipping = False
        kept.append(line)
    path = folder / "no-band.yaml"
    path.write_text("\n".join(kept) + "\n", encoding="utf-8")
    return path
