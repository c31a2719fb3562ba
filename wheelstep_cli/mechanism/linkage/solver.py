"""Planar linkages solved as a chain of two-circle (RRR dyad) steps (SPEC §7).

A linkage is an ordered tuple of steps, each defining one named joint from joints
defined before it: a fixed pivot, a crank tip, a dyad (the intersection of two circles
about known joints, with an explicit assembly branch +1/-1) or a point attached rigidly
to a link. All crank angles are solved at once (numpy arrays over the angles).

Branch continuity: a dyad's branch is the sign of the joint's offset to the left of the
line from its first to its second centre. With a fixed sign the solution moves
continuously as long as the two circles cut in two distinct points; where they become
tangent (a dead point) the two branches meet and the real mechanism may switch. The
solver checks, between every two successive crank angles, that each joint stays nearer
to its own branch than to the other one, and raises DesignError naming the crank angle
where a loop cannot close or the branches meet.

Units: millimetres and radians; crank angles count counter-clockwise from +x.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from wheelstep_cli.errors import DesignError


@dataclass(frozen=True)
class Fixed:
    """A frame pivot at (x, y) mm."""

    name: str
    x: float
    y: float


@dataclass(frozen=True)
class Crank:
    """Crank tip: ``center + length (cos(theta + phase), sin(theta + phase))``."""

    name: str
    center: str
    length: float
    phase: float = 0.0


@dataclass(frozen=True)
class Dyad:
    """Joint at distance ``rp`` from joint ``p`` and ``rq`` from joint ``q`` (two links, RRR).

    ``branch`` +1 puts it to the left of the directed line p -> q, -1 to the right.
    """

    name: str
    p: str
    rp: float
    q: str
    rq: float
    branch: int = 1


@dataclass(frozen=True)
class Attached:
    """Point rigidly on link p-q: ``p + length * rot(angle) * unit(q - p)``."""

    name: str
    p: str
    q: str
    length: float
    angle: float = 0.0


Step = Fixed | Crank | Dyad | Attached


@dataclass(frozen=True)
class Linkage:
    """A one-degree-of-freedom leg: steps in solving order, the foot joint, the ground side.

    ``ground`` is -1 if the ground lies toward -y of the linkage's frame (foot below),
    +1 if toward +y. ``links`` lists joint pairs drawn as bars (for plots).
    """

    name: str
    description: str
    steps: tuple
    foot: str
    ground: int = -1
    rpm: float = 60.0
    links: tuple = field(default_factory=tuple)

    def with_branches(self, flips: dict) -> "Linkage":
        """Copy with the named dyads' branches set (name -> +1/-1)."""
        steps = []
        for s in self.steps:
            if isinstance(s, Dyad) and s.name in flips:
                s = Dyad(s.name, s.p, s.rp, s.q, s.rq, int(flips[s.name]))
            steps.append(s)
        return Linkage(self.name, self.description, tuple(steps), self.foot, self.ground, self.rpm, self.links)

    def scaled(self, factor: float) -> "Linkage":
        """Copy with every length multiplied by ``factor``."""
        out = []
        for s in self.steps:
            if isinstance(s, Fixed):
                s = Fixed(s.name, s.x * factor, s.y * factor)
            elif isinstance(s, Crank):
                s = Crank(s.name, s.center, s.length * factor, s.phase)
            elif isinstance(s, Dyad):
                s = Dyad(s.name, s.p, s.rp * factor, s.q, s.rq * factor, s.branch)
            else:
                s = Attached(s.name, s.p, s.q, s.length * factor, s.angle)
            out.append(s)
        # the description states the preset's own numbers: say they are scaled
        described = f"{self.description}; every length x {factor:g} (--scale)"
        return Linkage(self.name, described, tuple(out), self.foot, self.ground, self.rpm, self.links)


@dataclass(frozen=True)
class Solution:
    """Joint positions over crank angles: ``joints[name]`` is (N, 2) mm; residual in mm.

    ``rates[name]`` is the joint's velocity per unit crank angle, d(joint)/d(theta) in
    mm/rad (exact velocity analysis, see :func:`solve`).
    """

    theta: np.ndarray
    joints: dict
    residual: float
    branches: dict
    rates: dict


def _circle_intersections(p, rp, q, rq):
    """Both intersections of circle(p, rp) and circle(q, rq) over rows; (left, right, h2, dist)."""
    d = q - p
    dist = np.hypot(d[:, 0], d[:, 1])
    safe = np.where(dist > 0, dist, 1.0)
    along = (rp**2 - rq**2 + dist**2) / (2 * safe)
    h2 = rp**2 - along**2
    h = np.sqrt(np.clip(h2, 0.0, None))
    u = d / safe[:, None]
    perp = np.column_stack([-u[:, 1], u[:, 0]])
    base = p + along[:, None] * u
    return base + h[:, None] * perp, base - h[:, None] * perp, h2, dist


def _deg(theta) -> float:
    return round(float(np.degrees(theta)) % 360.0, 3)


def solve(linkage: Linkage, theta) -> Solution:
    """Positions of every joint at crank angles ``theta`` (rad, increasing, one cycle).

    Raises DesignError (param ``crank-angle``) at the first angle where a dyad cannot
    close, its centres coincide, or its branches meet / the joint would jump branch.
    """
    theta = np.asarray(theta, dtype=float)
    n = theta.size
    joints: dict = {}
    branches: dict = {}
    residual = 0.0
    for s in linkage.steps:
        if isinstance(s, Fixed):
            joints[s.name] = np.tile([s.x, s.y], (n, 1)).astype(float)
        elif isinstance(s, Crank):
            ang = theta + s.phase
            joints[s.name] = joints[s.center] + s.length * np.column_stack([np.cos(ang), np.sin(ang)])
        elif isinstance(s, Attached):
            p, q = joints[s.p], joints[s.q]
            d = q - p
            dist = np.hypot(d[:, 0], d[:, 1])
            if np.any(dist <= 0):
                k = int(np.argmax(dist <= 0))
                raise DesignError("crank-angle", _deg(theta[k]), f"joints {s.p} and {s.q} coincide")
            u = d / dist[:, None]
            c, si = np.cos(s.angle), np.sin(s.angle)
            rot = np.column_stack([c * u[:, 0] - si * u[:, 1], si * u[:, 0] + c * u[:, 1]])
            joints[s.name] = p + s.length * rot
        else:
            joints[s.name] = _solve_dyad(s, joints, theta)
            branches[s.name] = s.branch
            for centre, r in ((s.p, s.rp), (s.q, s.rq)):
                gap = joints[s.name] - joints[centre]
                residual = max(residual, float(np.max(np.abs(np.hypot(gap[:, 0], gap[:, 1]) - r))))
    return Solution(theta=theta, joints=joints, residual=residual, branches=branches,
                    rates=joint_rates(linkage, theta, joints))


def _rot(v, angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]])


def joint_rates(linkage: Linkage, theta: np.ndarray, joints: dict) -> dict:
    """d(joint)/d(theta), mm/rad, by differentiating each step's constraints (vectorised).

    Crank: the tangent of its circle. Attached point: the link's direction turns with
    its end points. Dyad joint P on circles about p and q: the two length constraints
    give (P - p).(P' - p') = 0 and (P - q).(P' - q') = 0, a 2 x 2 system per angle
    (regular away from dead points, which :func:`solve` has already excluded).
    """
    rates: dict = {}
    for s in linkage.steps:
        if isinstance(s, Fixed):
            rates[s.name] = np.zeros((theta.size, 2))
        elif isinstance(s, Crank):
            ang = theta + s.phase
            rates[s.name] = rates[s.center] + s.length * np.column_stack([-np.sin(ang), np.cos(ang)])
        elif isinstance(s, Attached):
            d = joints[s.q] - joints[s.p]
            dd = rates[s.q] - rates[s.p]
            dist = np.hypot(d[:, 0], d[:, 1])[:, None]
            u = d / dist
            du = (dd - u * (u * dd).sum(axis=1, keepdims=True)) / dist
            rates[s.name] = rates[s.p] + s.length * _rot(du, s.angle)
        else:
            a = joints[s.name] - joints[s.p]
            b = joints[s.name] - joints[s.q]
            ra = (a * rates[s.p]).sum(axis=1)
            rb = (b * rates[s.q]).sum(axis=1)
            det = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
            rates[s.name] = np.column_stack([(ra * b[:, 1] - rb * a[:, 1]) / det,
                                             (a[:, 0] * rb - b[:, 0] * ra) / det])
    return rates


def _solve_dyad(s: Dyad, joints: dict, theta: np.ndarray) -> np.ndarray:
    if s.branch not in (1, -1):
        raise DesignError(f"branch of {s.name}", s.branch, "must be +1 or -1")
    if not (s.rp > 0 and s.rq > 0):
        raise DesignError(f"link {s.name}", min(s.rp, s.rq), "link lengths must be > 0")
    p, q = joints[s.p], joints[s.q]
    left, right, h2, dist = _circle_intersections(p, s.rp, q, s.rq)
    bad = dist <= 1e-12 * (s.rp + s.rq)
    if np.any(bad):
        k = int(np.argmax(bad))
        raise DesignError("crank-angle", _deg(theta[k]),
                          f"joints {s.p} and {s.q} coincide, joint {s.name} is undetermined")
    tol = 1e-9 * (s.rp + s.rq)
    tight = h2 < tol**2
    if np.any(tight):
        k = int(np.argmax(tight))
        if h2[k] < -(tol**2):
            reach = "too far apart" if dist[k] > s.rp + s.rq else "too close"
            raise DesignError("crank-angle", _deg(theta[k]),
                              f"loop through {s.name} cannot close: {s.p}-{s.q} = {dist[k]:.4g} mm is {reach} "
                              f"for links {s.rp:.4g} and {s.rq:.4g} mm")
        raise DesignError("crank-angle", _deg(theta[k]),
                          f"dead point: the two assembly branches of {s.name} meet here (branch may switch)")
    mine, other = (left, right) if s.branch == 1 else (right, left)
    if theta.size > 1:
        prev = np.roll(mine, 1, axis=0)
        if not is_full_cycle(theta):
            prev[0] = mine[0]
        step_same = np.hypot(*(mine - prev).T)
        step_other = np.hypot(*(other - prev).T)
        jump = step_other <= step_same
        jump[0] &= is_full_cycle(theta)
        if np.any(jump):
            k = int(np.argmax(jump))
            raise DesignError("crank-angle", _deg(theta[k]),
                              f"joint {s.name} comes nearer its other assembly branch than its own "
                              f"(branch switch near a dead point; use more --samples or change the links)")
    return mine


def is_full_cycle(theta: np.ndarray) -> bool:
    span = theta[-1] - theta[0] + (theta[1] - theta[0] if theta.size > 1 else 0.0)
    return bool(np.isclose(span, 2 * np.pi))


def cycle_angles(samples: int) -> np.ndarray:
    """``samples`` crank angles evenly over one turn, starting at 0, without repeating 2 pi."""
    return np.arange(samples) * (2 * np.pi / samples)
