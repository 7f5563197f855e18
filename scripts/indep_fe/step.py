"""The step re-estimated at every step (ALGORITHM.md section 6b, `time.dt.update: every-step`),
written from that text: dt_{n+1/2} = cfl * dt_crit,n, dt_crit,n the plate's section 4 estimate
on the mesh as made times min_e sqrt(S_ref / S_cur) on u_n (section 3c's ratio), then the
surface coupling's penalty springs on it (section 5b); the velocity step h_n the mean of the
two steps (dt_{1/2} / 2 at n = 0); the run's end landed on by cutting the step. Times in s."""
from __future__ import annotations

from dataclasses import dataclass, field

# section 6b: the estimate may not fall below this fraction of the first step
FLOOR = 1e-3
# section 6b: t_n within this fraction of dt_{n+1/2} of a target time counts as reaching it
REACH = 1e-9


class StepTooSmall(RuntimeError):
    pass


@dataclass
class StepPlan:
    cfl: float
    dt_plate: float          # the plate's critical step on the mesh as made, s
    finite: object           # FiniteKinematics | FiniteRing: its step_factor(u)
    nose: object = None      # SurfaceNose: its penalty springs (stable_step)
    first: float | None = None                 # dt_{1/2}, s
    taken: list = field(default_factory=list)  # the estimates used uncut, s

    def estimate(self, u, n: int) -> float:
        """dt_{n+1/2} on u_n (s); StepTooSmall below FLOOR of the first step."""
        factor, e = self.finite.step_factor(u)
        crit = self.dt_plate * factor
        if self.nose is not None:
            crit = self.nose.stable_step(crit)
        dt = self.cfl * crit
        if self.first is None:
            self.first = dt
        elif dt < FLOOR * self.first:
            raise StepTooSmall(f"at step {n} the re-estimated step {dt:.6e} s is below "
                               f"{FLOOR:g} of the first {self.first:.6e} s (element {e}, "
                               f"sqrt(S_ref / S_cur) = {factor:.6e})")
        return dt


def reached(t: float, target: float, dt: float) -> bool:
    """t_n at or past target, within REACH dt_{n+1/2} (section 6b)."""
    return t >= target - REACH * dt


def cut(t: float, end: float, dt: float) -> float:
    """The step from t_n, cut to land on the run's end (section 6b)."""
    return min(dt, end - t)


def velocity_step(dt_prev: float | None, dt: float) -> float:
    """h_n = (dt_{n-1/2} + dt_{n+1/2}) / 2; dt_{1/2} / 2 at n = 0 (dt_prev None)."""
    return 0.5 * dt if dt_prev is None else 0.5 * (dt_prev + dt)


def summary_keys(plan: StepPlan) -> dict:
    """summary.json's dt_update, dt_min_s, dt_max_s: over the steps the estimate gave, the last
    step's uncut estimate (its velocity step) included, the step cut to land on the end not."""
    steps = plan.taken or [plan.first]
    return {"dt_update": "every-step", "dt_min_s": min(steps), "dt_max_s": max(steps)}

