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
#: command -> its options that write a file beside the meshes (a plot, a table)
WRITERS = {"kinematics": ["--plot"], "stairs": ["--plot"], "linkage": ["--csv", "--plot"],
           "trajectory": ["--csv", "--plot"], "mesh-check": ["--plot"]}
#: hostile side files: a design profile (--profile) and a law table (--law-csv)
PROFILE_TEXTS = [b"\xff\xfe not utf-8", b"gears: {z: '48'}\n", b"mechanism: {c: text}\n",
                 b"gears: {thickness: {a: 1}}\n", b"<<: {a: 1}\n", b"p: &p [*p]\n", b"[1, 2", b""]
CSV_TEXTS = [b"\xff\xfe\x00", b"", b"phi,psi\n0,nan\n1,inf\n", b"a,b\nx,y\n", b"0,0\n0,0\n",
             b"0,1e308\n1,1e308\n"]
OUT_SETUPS = ["none", "user-file", "file-as-folder", "read-only"]

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
    out_setup: str = "none"      # OUT_SETUPS or "manifest-claim" (the ``out`` folder's state)


def _value(rng: random.Random) -> str:
    return rng.choice(NUMBERS)


def _command_case(rng: random.Random, allow_slow: bool) -> Invocation:
    names = [c for c in OPTIONS if allow_slow or c not in SLOW]
    command = rng.choice(names)
    args = [command]
    for option in rng.sample(OPTIONS[command], k=min(len(OPTIONS[command]), rng.randint(1, 3))):
        args += [option, _value(rng)]
    if command == "mesh-check":
        meshes = [rng.choice(list(MESH_TEXTS)) for _ in range(2)]
        inv = Invocation(args[:1] + meshes + args[1:], {m: MESH_TEXTS[m] for m in meshes})
        _side_files(rng, command, inv)
        return inv
    if rng.random() < 0.15:
        args.append(rng.choice(["--no-such-option", "--json", "--dry-run", "-q", "--profile"]))
    if rng.random() < 0.3:
        args.append("--json")
    inv = Invocation(args)
    if command in SLOW and rng.random() < 0.5:
        inv.out_setup = rng.choice(OUT_SETUPS[1:])
        inv.args += ["--out", "out"]
    _side_files(rng, command, inv)
    return inv


def _side_files(rng: random.Random, command: str, inv: Invocation) -> None:
    """Sometimes a hostile profile or law table, and an output file in a prepared ``out``."""
    if rng.random() < 0.15 and command in {"gears", "shoe", "pitch", "kinematics", "mesh-check"}:
        inv.files["p.yaml"] = rng.choice(PROFILE_TEXTS)
        inv.args += ["--profile", "p.yaml"]
    if rng.random() < 0.15 and command in {"gears", "mesh-check"}:
        inv.files["law.csv"] = rng.choice(CSV_TEXTS)
        inv.args += ["--law-csv", rng.choice(["law.csv", "missing.csv"])]
    if command in WRITERS and rng.random() < 0.3:
        option = rng.choice(WRITERS[command])
        inv.out_setup = rng.choice(OUT_SETUPS)
        inv.args += [option, "out/" + ("k.png" if option == "--plot" else "k.csv")]


def _batch_case(rng: random.Random) -> Invocation:
    text = rng.choice(BATCH_TEXTS)
    data = text.encode("latin-1") if text.startswith("\xff") else text.encode()
    inv = Invocation(["batch", "b.yaml", "--out", "out"], {"b.yaml": data})
    inv.out_setup = rng.choice(["none", "manifest-claim", "user-file", "file-as-folder", "read-only"])
    return inv


def invocations(seed: int, count: int, slow_share: float = 0.1):
    """``count`` seeded invocations; ``slow_share`` of them may be slow successful part runs."""
    rng = random.Random(seed)
    for _ in range(count):
        draw = rng.random()
        if draw < 0.03:
            yield Invocation(rng.choice([["--help"], [rng.choice(list(OPTIONS)), "--help"]]))
        elif draw < 0.2:
            yield _batch_case(rng)
        else:
            yield _command_case(rng, allow_slow=rng.random() < slow_share)


def option_scan(commands: list[str] | None = None):
    """Every numeric option of every command (or of ``commands``) alone with every value of
    :data:`NUMBERS`: the boundary cases a random campaign may miss, in a fixed order."""
    for command in commands or list(OPTIONS):
        for option in OPTIONS[command]:
            for value in NUMBERS:
                yield Invocation([command, option, value])
