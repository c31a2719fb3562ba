"""The pair's picture geometry: assembly phase, pitch curves meeting on the line of centres,
handover poses of the animation."""

from types import SimpleNamespace

import numpy as np
import pytest

from wheelstep_cli.config.resolve import gear_pair_spec
from wheelstep_cli.render.gear_pair_gif import handover_poses
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
