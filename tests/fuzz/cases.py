"""Seeded invocations of every command: valid, boundary, zero, negative, huge, tiny, NaN, inf,
non-numbers, unicode and unknown options; hostile batch files; corrupt meshes; output paths
that are files or hold a user's files."""

from __future__ import annotations

import random
from dataclasses import dataclass, field

NUMBERS = ["0", "-1", "-0.0", "1e-300", "5e-324", "1e308", "1e30", "nan", "inf", "-inf", "abc",
           "½", "１２", "", "1,5", "0x10", "2147483648", "1e9", "3", "48", "0.5", "20", "144"]

#: command -> options it takes that carry a number (the fuzz picks values from NUMBERS or these)
OPTIONS = {
    "pitch": ["--a", "--b", "--c", "--z", "--turns", "--center-distance"],
    "teeth": ["--a", "--b", "--c", "--z", "--module", "--backlash"],
    "gears": ["--z", "--turns", "--module", "--backlash", "--thickness", "--bore", "--pressure-angle",
              "--addendum", "--dedendum", "--fillet", "--blend", "--tilt", "--install-distance",
              "--center-distance", "--a", "--b", "--c"],
    "shoe": ["--a", "--b", "--c", "--rmin", "--width", "--strut-diameter", "--socket-depth", "--rim"],
    "kinematics": ["--a", "--b", "--rmin", "--motor-rpm", "--points", "--rows"],
    "stairs": ["--run", "--rise", "--sole-radius", "--landing-angle", "--step", "--tol"],
    "linkage": ["--l1", "--l2", "--l3", "--l4", "--beta", "--rpm"],
    "trajectory": ["-H", "--r1", "--r2", "--r3", "--h-max", "--y0"],
    "mesh-check": ["--distance", "--samples", "--window"],
}
SLOW = {"gears", "shoe"}      # a successful run writes meshes: seconds, not milliseconds

BATCH_TEXTS = [
    "parts: &p [*p]\n",
    "base: &b {kind: shoe}\nparts:\n  - <<: *b\n    printer: fdm-0.4-pla\n",
    "parts:\n  - kind: [shoe]\n    printer: fdm-0.4-pla\n",
    "parts:\n  - kind: gear-pair\n    printer: fdm-0.4-pla\n    overrides: {z: 1000000000}\n",
    "parts:\n  - kind: shoe\n    printer: fdm-0.4-pla\n    overrides: {width: .nan}\n",
    "parts:\n  - kind: shoe\n    printer: fdm-0.4-pla\n    overrides: {thickness: {a: 1}}\n",
    "parts:\n  - name: '" + "x" * 300 + "'\n    kind: shoe\n    printer: fdm-0.4-pla\n",
    "a: &a [1,1,1,1,1,1,1,1,1]\nb: &b [*a,*a,*a,*a,*a,*a,*a,*a,*a]\nc: &c [*b,*b,*b,*b,*b,*b,*b,*b,*b]\n"
    "d: &d [*c,*c,*c,*c,*c,*c,*c,*c,*c]\ne: &e [*d,*d,*d,*d,*d,*d,*d,*d,*d]\nparts: [*e,*e,*e,*e,*e]\n",
    "\xff\xfe not utf-8",
    "parts:\n  - kind: shoe\n    quantity: 1: 2\n",
    "[1, 2",
    "",
]
MESH_TEXTS = {"empty.stl": b"", "junk.stl": b"solid x\nfacet normal 0 0 0\nendsolid\n",
              "png.stl": b"\x89PNG\r\n\x1a\n" + b"\0" * 64, "huge.stl":
              b"solid h\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1e30 0 0\n"
              b"vertex 0 1e30 0\nendloop\nendfacet\nendsolid h\n",
              "bad.3mf": b"PK\x03\x04 not a zip"}


@dataclass
class Invocation:
    """One command line and the files it needs in its folder (name -> bytes)."""

    args: list[str]
    files: dict[str, bytes] = field(default_factory=dict)
    out_setup: str = "none"      # "none", "user-file", "file-as-folder", "manifest-claim"


def _value(rng: random.Random) -> str:
    return rng.choice(NUMBERS)


def _command_case(rng: random.Random, allow_slow: bool) -> Invocation:
    names = [c for c in OPTIONS if allow_slow or c not in SLOW]
    command = rng.choice(names)
    args = [command]
    for option in rng.sample(OPTIONS[command], k=min(len(OPTIONS[command]), rng.randint(1, 3))):
        args += [option, _value(rng)]
    if command == "mesh-check":
        mesh = rng.choice(list(MESH_TEXTS))
        return Invocation(args[:1] + [mesh, mesh] + args[1:], {mesh: MESH_TEXTS[mesh]})
    if rng.random() < 0.15:
        args.append(rng.choice(["--no-such-option", "--json", "--dry-run", "-q", "--profile"]))
    if rng.random() < 0.3:
        args.append("--json")
    inv = Invocation(args)
    if command in SLOW and rng.random() < 0.5:
        inv.out_setup = rng.choice(["user-file", "file-as-folder"])
        inv.args += ["--out", "out"]
    return inv


def _batch_case(rng: random.Random) -> Invocation:
    text = rng.choice(BATCH_TEXTS)
    data = text.encode("latin-1") if text.startswith("\xff") else text.encode()
    inv = Invocation(["batch", "b.yaml", "--out", "out"], {"b.yaml": data})
    inv.out_setup = rng.choice(["none", "manifest-claim", "user-file"])
    return inv


def invocations(seed: int, count: int, slow_share: float = 0.1):
    """``count`` seeded invocations; ``slow_share`` of them may be slow successful part runs."""
    rng = random.Random(seed)
    for _ in range(count):
        if rng.random() < 0.2:
            yield _batch_case(rng)
        else:
            yield _command_case(rng, allow_slow=rng.random() < slow_share)
