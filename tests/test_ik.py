"""Arm IK: both solvers reach reachable targets to 1 mm, refuse unreachable ones with a reason,
never return joints outside their limits. Every answer is checked by MuJoCo's forward
kinematics on sim/models/g1.xml, not by the solvers' own Pinocchio model."""

from __future__ import annotations

import math

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco")
pytest.importorskip("pinocchio")
pytest.importorskip("placo")

from stuart_bt.sim.robot import MJCF_PATH, REACH, shoulder_xyz  # noqa: E402
from stuart_bt.skills.pick.ik import IKResult, check_reachable  # noqa: E402
from stuart_bt.skills.pick.solvers import make_solver  # noqa: E402

SOLVERS = ("pin", "placo")


@pytest.fixture(scope="module")
def mj():
    model = mujoco.MjModel.from_xml_path(str(MJCF_PATH))
    return model, mujoco.MjData(model)


@pytest.fixture(scope="module", params=SOLVERS)
def solver(request):
    return make_solver(request.param)


def mujoco_hand(mj, arm: str, q: dict[str, float]) -> tuple[np.ndarray, np.ndarray]:
    """(hand point, hand rotation) in torso_link by MuJoCo, everything else at zero."""
    model, data = mj
    data.qpos[:] = 0.0
    for name, value in q.items():
        data.qpos[model.jnt_qposadr[model.joint(name).id]] = value
    mujoco.mj_kinematics(model, data)
    torso = model.body("torso_link").id
    rot_t = data.xmat[torso].reshape(3, 3).T
    site = data.site(f"{arm}_hand_point")
    return rot_t @ (site.xpos - data.xpos[torso]), rot_t @ site.xmat.reshape(3, 3)


def within_limits(mj, q: dict[str, float]) -> list[str]:
    model, _ = mj
    out = []
    for name, value in q.items():
        lo, hi = model.jnt_range[model.joint(name).id]
        if not lo - 1e-9 <= value <= hi + 1e-9:
            out.append(f"{name}={value}")
    return out


def grid(step: float = 0.08) -> list[tuple[str, np.ndarray]]:
    """Targets in front of each shoulder, 0.12 m .. 0.9 x reach from it."""
    out = []
    for arm in ("left", "right"):
        shoulder, out_sign = shoulder_xyz(arm), (1.0 if arm == "left" else -1.0)
        for x in np.arange(0.06, 0.37, step):
            for y in np.arange(-0.16, 0.17, step):
                for z in np.arange(-0.34, 0.19, step):
                    offset = np.array([x, out_sign * y, z])
                    inside = 0.12 <= np.linalg.norm(offset) <= 0.9 * REACH
                    if inside and check_reachable(arm, shoulder + offset) is None:
                        out.append((arm, shoulder + offset))
    return out


def test_grid_targets_are_reached_within_a_millimetre(solver, mj) -> None:
    targets = grid()
    assert len(targets) > 100
    misses = []
    for arm, target in targets:
        result = solver.solve(arm, target, None, None)
        assert isinstance(result, IKResult)
        position, _ = mujoco_hand(mj, arm, result.q)
        error = float(np.linalg.norm(position - target))
        if not result.success or error > 1e-3:
            misses.append((arm, target.round(3).tolist(), result.reason, error))
        assert not within_limits(mj, result.q), (arm, target)
        assert error == pytest.approx(result.position_error, abs=1e-6)  # the reported error is the real one
    assert not misses, misses[:5]


def test_random_reachable_targets_respect_limits(solver, mj) -> None:
    """Targets anywhere in the shell around the shoulder, from random seeds: whatever comes
    back is inside the limits, and a success is a success in MuJoCo too."""
    rng = np.random.default_rng(11)
    for _ in range(40):
        arm = "left" if rng.random() < 0.5 else "right"
        direction = rng.normal(size=3)
        target = shoulder_xyz(arm) + direction / np.linalg.norm(direction) * rng.uniform(0.15, 0.4)
        seed = {f"{arm}_elbow_joint": float(rng.uniform(-1.0, 2.0))}
        result = solver.solve(arm, target, seed, None)
        assert not within_limits(mj, result.q)
        if result.success:
            assert np.linalg.norm(mujoco_hand(mj, arm, result.q)[0] - target) <= 1e-3
        else:
            assert result.reason


def test_far_targets_fail_with_how_far(solver) -> None:
    target = shoulder_xyz("left") + np.array([0.6, 0.0, 0.0])
    result = solver.solve("left", target, None, None)
    assert not result.success and result.iterations == 0
    assert "beyond" in result.reason and "0.181 m" in result.reason  # 0.6 - 0.4185
    assert result.position_error > 0.18


def test_precheck_catches_far_and_impossible_targets() -> None:
    just_out = shoulder_xyz("right") + np.array([0.0, 0.0, -(REACH + 0.01)])
    assert "0.010 m beyond the right arm's reach" in check_reachable("right", just_out)
    assert check_reachable("right", shoulder_xyz("right") + np.array([REACH - 0.01, 0.0, 0.0])) is None
    assert "right hip" in check_reachable("right", shoulder_xyz("right") + np.array([0.0, 0.0, -(REACH - 0.01)]))
    assert "inside the robot's chest" in check_reachable("left", np.array([0.0, 0.0, 0.2]))
    assert "inside the robot's head" in check_reachable("left", np.array([0.0, 0.0, 0.42]))
    behind = check_reachable("left", np.array([-0.15, -0.05, 0.1]))
    assert behind and "behind the back" in behind
    assert check_reachable("left", np.array([0.3, 0.15, 0.1])) is None  # an ordinary grasp


def test_unreachable_targets_fail_with_a_reason(solver, mj) -> None:
    inside = solver.solve("right", np.array([0.0, -0.02, 0.15]), None, None)
    assert not inside.success and "inside" in inside.reason
    # past the pre-check (called directly), the solver itself gives up, within limits, saying so
    chain = solver.chain("left")
    q, iterations, note = solver._solve("left", shoulder_xyz("left") + np.array([0.7, 0, 0]), chain.neutral, None)
    assert iterations > 0 and "did not converge" in note
    assert not within_limits(mj, chain.named(q))


@pytest.mark.parametrize("orientation,axis,wanted", [("down", "palm", (0, 0, -1)), ("forward", "fingers", (1, 0, 0))])
def test_orientation_wish_is_granted_when_possible(solver, mj, orientation, axis, wanted) -> None:
    for arm, target in (("left", np.array([0.30, 0.15, 0.05])), ("right", np.array([0.28, -0.10, 0.10]))):
        result = solver.solve(arm, target, None, orientation)
        assert result.success, result.reason
        position, rotation = mujoco_hand(mj, arm, result.q)
        assert np.linalg.norm(position - target) <= 1e-3
        local = {"palm": (0, 1 if arm == "right" else -1, 0), "fingers": (1, 0, 0)}[axis]
        angle = math.degrees(math.acos(np.clip(rotation @ np.array(local, float) @ np.array(wanted, float), -1, 1)))
        assert angle < 3.0, f"{arm} {axis} {angle:.1f} deg off"


def test_a_solved_seed_comes_straight_back(solver) -> None:
    target = np.array([0.25, 0.2, 0.0])
    first = solver.solve("left", target, None, None)
    again = solver.solve("left", target, first.q, None)
    assert again.success and again.iterations <= 1
    assert solver.solve("left", target, None, None).q == first.q  # deterministic


def test_bad_arguments_are_named() -> None:
    with pytest.raises(ValueError, match="did you mean 'placo'"):
        make_solver("placco")
    solver = make_solver("pin")
    with pytest.raises(ValueError, match="did you mean 'left_elbow_joint'"):
        solver.solve("left", np.array([0.3, 0.1, 0.0]), {"left_elbo_joint": 0.3}, None)
    with pytest.raises(ValueError, match="'left' or 'right'"):
        solver.solve("middle", np.array([0.3, 0.1, 0.0]), None, None)  # type: ignore[arg-type]
    # joints of the other arm, the hands or the waist in a seed are ignored, not refused
    assert solver.solve("left", np.array([0.3, 0.1, 0.0]), {"right_elbow_joint": 0.3, "left_hand_index_0_joint": -0.2},
                        None).success
