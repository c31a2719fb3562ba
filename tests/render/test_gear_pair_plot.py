"""The pair's picture geometry: assembly phase, pitch curves meeting on the line of centres,
handover poses of the animation."""

from types import SimpleNamespace

import numpy as np
import pytest

from wheelstep_cli.config.resolve import gear_pair_spec
from wheelstep_cli.render.gear_pair_gif import _readout, handover_poses, turning_through
from wheelstep_cli.render.gear_pair_plot import assembly_phase, handover_angle, pitch_curve, posed

D = 144.0


@pytest.fixture(scope="module")
def law():
    return gear_pair_spec(None).law()


def test_assembly_phase_is_carrier_zero_and_the_handover_a_corner(law):
    assert assembly_phase(law) == (0.0, 0.0)
    assert handover_angle(law) == pytest.approx(np.pi / 4)


@pytest.mark.parametrize("phi", [0.0, 0.3, np.pi / 4, 1.0])
def test_pitch_curves_touch_on_the_line_of_centres_at_every_pose(law, phi):
    theta = float(law.pinion_angle(np.array([phi]))[0])
    pinion, p_phi = pitch_curve("pinion", law, D, samples=32768)
    wheel, w_phi = pitch_curve("wheel", law, D, samples=32768)
    p_world = posed("pinion", pinion, theta, phi, D)
    w_world = posed("wheel", wheel, theta, phi, D)
    # the points of carrier angle phi land on one point of the line of centres
    i = int(np.argmin(np.abs(p_phi - phi)))
    j = int(np.argmin(np.abs(w_phi - phi)))
    assert abs(p_phi[i] - phi) < 2e-4 and abs(w_phi[j] - phi) < 2e-4
    assert p_world[i, 1] == pytest.approx(0.0, abs=0.02) and w_world[j, 1] == pytest.approx(0.0, abs=0.02)
    assert p_world[i, 0] == pytest.approx(w_world[j, 0], abs=0.02)
    assert 0.0 < p_world[i, 0] < D


def test_handover_poses_span_one_tooth_pitch_each_side_in_order(law):
    samples, teeth = 1536, 48
    report = SimpleNamespace(theta=law.theta_period * np.arange(samples) / samples,
                             period=law.theta_period, teeth=teeth)
    poses = handover_poses(report, law, frames=60)
    assert 40 <= len(poses) <= 60 and len(set(poses.tolist())) == len(poses)
    theta_c = float(law.pinion_angle(np.array([np.pi / 4]))[0])
    span = report.theta[poses] - theta_c
    assert np.all(np.diff(span) > 0)
    assert span[0] == pytest.approx(-2 * np.pi / teeth, abs=0.01)
    assert span[-1] == pytest.approx(2 * np.pi / teeth, abs=0.01)


def test_the_animation_says_what_it_turns_through_and_whose_speed_it_reads(law):
    """The crank law's corners are shoe handovers and its speed the hub's; a law CSV's gears
    carry no shoes and drive no hub: the GIF says the law's corner (or the period's start,
    without one) and the output speed."""
    assert turning_through(law) == "a shoe handover"
    assert turning_through(law, "output speed") == "the law's first corner"
    assert turning_through(SimpleNamespace(corners=()), "output speed") == "the start of the law's period"
    report = SimpleNamespace(drive=SimpleNamespace(error_um=np.array([1.5])), hub_speed=np.array([1.01]),
                             hub_speed_law=np.array([1.0]), theta=np.array([0.1]), phi_law=np.array([0.05]),
                             interference=np.array([False]))
    assert "output speed +1.00 % of the mean" in _readout(report, 0, "output speed")
    assert "hub speed" not in _readout(report, 0, "output speed")
    assert "carrier" not in _readout(report, 0, "output speed") and "carrier" in _readout(report, 0)


@pytest.mark.parametrize("points, expect", [(3, [0, 1, 2]), (12, list(range(12))),
                                            (23, [0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22])])
def test_a_pareto_front_names_its_points_or_twelve_spread_along_it_with_both_ends(points, expect):
    from wheelstep_cli.render.sweep_plot import labelled

    best = [(float(k), float(-k), f"z {k}") for k in range(points)]
    assert [name for _, _, name in labelled(best)] == [f"z {k}" for k in expect]
