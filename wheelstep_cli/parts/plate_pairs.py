"""Gear pairs found on written plates (3MF) by their object metadata: ``wheelstep:part``
(pinion, wheel) and ``wheelstep:pair`` (the same id on both gears of a pair), each object
read in its own frame, its design rebuilt from the metadata. Lengths in mm."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from wheelstep_cli.config.schema import limit_text
from wheelstep_cli.config.specs import GearPairSpec
from wheelstep_cli.errors import DesignError, file_problem, require
from wheelstep_cli.formats.mesh_read import MeshObject, read_3mf_objects, split_mesh_spec
from wheelstep_cli.parts.gear_laws import require_plate_law_csv

GEARS = ("pinion", "wheel")


@dataclass(frozen=True)
class PlatePair:
    """A pinion and a wheel sharing a ``wheelstep:pair`` id, with the design they carry."""

    pair: str
    pinion: MeshObject
    wheel: MeshObject
    files: tuple[str, str]     # the files holding the pinion and the wheel
    spec: GearPairSpec
    inset: float = 0.0         # mm a fit drew both tooth outlines smaller (metadata outline_inset)


def is_plate_input(pinion: str, wheel: str | None) -> bool:
    """Whether mesh-check finds the pair by metadata: one 3MF file, or two 3MF files (no
    ``:NAME``) whose objects carry ``wheelstep:part``."""
    specs = [pinion] if wheel is None else [pinion, wheel]
    paths = [split_mesh_spec(s) for s in specs]
    if wheel is None:
        # one mesh alone is a plate only as a whole 3MF file (a named object or an STL is half a pair)
        return paths[0][1] is None and paths[0][0].suffix.lower() == ".3mf"
    if any(name is not None or path.suffix.lower() != ".3mf" or not path.is_file()
           for path, name in paths):
        return False
    return all(any("part" in o.metadata for o in read_3mf_objects(path, param))
               for (path, _), param in zip(paths, GEARS))


def named_plate_pair(pinion: str, wheel: str) -> PlatePair | None:
    """The pair of two 3MF objects named ``FILE.3mf:NAME`` whose metadata marks them the
    pinion and the wheel (``wheelstep:part``), with the design they carry (refused when the two
    carry different designs); None when either is not such an object (an STL, an object of
    another tool): its design then comes from the options."""
    objects, read = [], {}
    for given, param in zip((pinion, wheel), GEARS):
        path, name = split_mesh_spec(given)
        if name is None or not path.is_file():
            return None
        if path.resolve() not in read:     # both objects of one plate: the plate read once
            read[path.resolve()] = read_3mf_objects(path, param)
        named = [o for o in read[path.resolve()] if o.name == name]
        if len(named) != 1 or named[0].metadata.get("part") not in GEARS:
            return None
        # the file as the user typed it (the plate check names each object FILE:NAME)
        objects.append((str(given).rpartition(":")[0], named[0]))
    parts = tuple(obj.metadata["part"] for _, obj in objects)
    # the plate's word for which gear is which, as a plate's pair is held to it
    require(parts != ("wheel", "pinion"), "pinion", pinion, "is a wheel by its wheelstep:part metadata (and "
            f"{wheel} a pinion): give the pinion first, then the wheel (PINION WHEEL)")
    for given, param, part in zip((pinion, wheel), GEARS, parts):
        require(part == param, param, given, f"is a {part} by its wheelstep:part metadata, as is the "
                f"{'wheel' if param == 'pinion' else 'pinion'} given: name a {param}'s object (FILE.3mf:NAME)")
    pair_id = objects[0][1].metadata.get("pair", f"{objects[0][1].name} + {objects[1][1].name}")
    return _plate_pair(pair_id, dict(zip(GEARS, objects)), (pinion, wheel))


def find_plate_pairs(files: list[str], pair: str | None = None) -> list[PlatePair]:
    """The gear pairs of the plates ``files`` (each pair once, in file order: on one plate or
    with a gear on each), or the one named ``pair``; refused (DesignError) when there is
    none or the meshes are not a pair."""
    groups: dict[str, dict[str, tuple[str, MeshObject]]] = {}
    read: set[Path] = set()
    for file, param in zip(files, GEARS):
        path = Path(file)
        if not split_mesh_spec(file)[0].exists():       # FILE.3mf:NAME names a file too
            raise DesignError(param, file, file_problem(split_mesh_spec(file)[0]))
        if path.suffix.lower() != ".3mf" or not path.is_file():
            raise DesignError(param, file, "must be a 3MF plate written by wheelstep (or name two "
                                           "meshes, the pinion and the wheel)")
        if path.resolve() in read:
            continue        # one plate named twice (./a.3mf a.3mf): its pairs once
        read.add(path.resolve())
        own: dict[str, dict[str, tuple[str, MeshObject]]] = {}
        for obj in read_3mf_objects(path, param):
            part, pair_id = obj.metadata.get("part"), obj.metadata.get("pair")
            if part in GEARS and pair_id:
                gears = own.setdefault(pair_id, {})
                # two of one gear: which meshes with the other is not the plate's to say
                if part in gears:
                    raise DesignError(param, file, f"holds two {part}s of pair '{pair_id}' (objects "
                                      f"'{gears[part][1].name}' and '{obj.name}'): remove one, or give it "
                                      "its own wheelstep:pair id")
                gears[part] = (file, obj)
        for pair_id, gears in own.items():
            if len(gears) == 2 and pair_id in groups:
                # two plates each holding a pair of one id (two `gears` runs): both checked
                groups[f"{pair_id} ({file})"] = gears
            else:       # a pair on this plate, or a gear whose mate is on the other plate
                mates = groups.setdefault(pair_id, {})
                for part, gear in gears.items():
                    mates.setdefault(part, gear)
    complete = [k for k, g in groups.items() if len(g) == 2]
    where = " + ".join(files)
    if not complete:
        what = "are not a gear pair" if len(files) == 2 else "holds no gear pair"
        halves = sorted(f"the {next(iter(g))} of pair '{k}'" for k, g in groups.items() if len(g) == 1)
        # a batch packs a pair's gears onto different plates when they do not fit one together
        found = (f"; it holds only {', '.join(halves)}: name the plate with the other gear too "
                 f"(mesh-check PLATE PLATE)" if halves and len(files) == 1 else "")
        raise DesignError(GEARS[len(files) - 1], where, f"{what}: no pinion and wheel share a "
                          f"wheelstep:pair id in the 3MF metadata{found}")
    if pair is not None:
        if pair not in complete:
            raise DesignError("pair", pair, f"must be one of {', '.join(complete)}")
        complete = [pair]
    # every plate named takes part: one without a gear of these pairs was named by mistake
    used = {Path(gear[0]).resolve() for k in complete for gear in groups[k].values()}
    for file, param in zip(files, GEARS):
        require(Path(file).resolve() in used, param, file,
                f"holds no gear of pair '{pair}' (--pair): name only the plates that hold it"
                if pair is not None else
                "holds no gear of a gear pair: no pinion or wheel with a wheelstep:pair id in its 3MF "
                "metadata that meshes with one on these plates")
    return [_plate_pair(k, groups[k]) for k in complete]


def _plate_pair(pair: str, group: dict[str, tuple[str, MeshObject]], given: tuple[str, str] | None = None
                ) -> PlatePair:
    """The pair of ``group`` (part -> (file, object)); ``given``: the pinion and wheel as the
    user named them, for the refusals (else the files)."""
    (p_file, pinion), (w_file, wheel) = group["pinion"], group["wheel"]
    p_said, w_said = given or (p_file, w_file)
    # the design, and the fit's inset the check draws both outlines with
    keys = set(GearPairSpec.model_fields) | {"outline_inset"}
    design = {k: v for k, v in pinion.metadata.items() if k in keys}
    other = {k: v for k, v in wheel.metadata.items() if k in keys}
    if design != other:
        differ = sorted(k for k in design.keys() | other.keys() if design.get(k) != other.get(k))
        said = "; ".join(f"{k} = {other.get(k, '(none)')} (the pinion's {design.get(k, '(none)')})"
                         for k in differ)
        raise DesignError("wheel", w_said, f"carries another design than the pinion of pair '{pair}': {said}")
    design.pop("outline_inset", None)
    spec = spec_from_metadata(design, p_said)
    require_plate_law_csv(spec, pinion.metadata, p_said)
    return PlatePair(pair, pinion, wheel, (p_file, w_file), spec, _inset(pinion.metadata, p_said))


def _inset(metadata: dict[str, str], file: str) -> float:
    """The fit's inset (mm) a gear's metadata states, 0 when none."""
    text = metadata.get("outline_inset", "0")
    try:
        inset = float(text)
    except ValueError:
        inset = -1.0
    require(inset >= 0.0, "pinion", file, f"metadata outline_inset = {text}: must be a length >= 0 mm")
    return inset


def spec_from_metadata(values: dict[str, str], file: str) -> GearPairSpec:
    """The design stored as metadata text (numbers as %g), checked by its model."""
    from pydantic import ValidationError

    typed = {}
    for key, text in values.items():
        typed[key] = text
        for kind in (int, float):
            try:
                typed[key] = kind(text)
                break
            except ValueError:
                continue
        if text in ("True", "False"):      # a switch (--lighten) is written as str(bool)
            typed[key] = text == "True"
    if isinstance(typed.get("law_csv"), (int, float)):
        typed["law_csv"] = values["law_csv"]
    try:
        return GearPairSpec(**typed)
    except ValidationError as err:
        first = err.errors()[0]
        cause = first.get("ctx", {}).get("error")
        if not first["loc"] and isinstance(cause, DesignError):
            # a rule between fields (the model's own check): the field it names, not the dict
            raise DesignError("pinion", file, f"metadata {cause.param} = {cause.shown_value}: "
                                              f"{cause.limit}") from None
        raise DesignError("pinion", file, f"metadata {'.'.join(map(str, first['loc']))} = "
                          f"{first.get('input')!r}: {limit_text(GearPairSpec, first)}") from None
