"""Choose an IK solver by name. Apart from :mod:`.ik` (the base every solver builds on) so that
module never imports its own subclasses; each solver is imported only when asked for, so a
caller loads only the library it uses."""

from __future__ import annotations

from stuart_bt.core.suggest import did_you_mean

from .ik import SOLVERS, IKSolver


def make_solver(name: str) -> IKSolver:
    """``"pin"`` (Pinocchio) or ``"placo"`` (PlaCo)."""
    if name == "pin":
        from .ik_pin import PinSolver

        return PinSolver()
    if name == "placo":
        from .ik_placo import PlacoSolver

        return PlacoSolver()
    raise ValueError(f"unknown IK solver {name!r}{did_you_mean(name, SOLVERS)}; choose from {', '.join(SOLVERS)}")
