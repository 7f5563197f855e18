//! The size of each time step (`ALGORITHM.md` section 6b): fixed for the run (`time.dt.update:
//! once`, the paper's model), or re-estimated at every step from the deformed mesh
//! (`every-step`, finite deformation), as Abaqus/Explicit's and LS-DYNA's element-by-element
//! estimates are.
//!
//! Central differences with unequal steps (Belytschko, Liu & Moran 2000, section 6.2.1): with
//! `dt_{n+1/2} = t_{n+1} - t_n`, the velocity step at `t_n` is the mean of the two steps
//! around it, `h_n = (dt_{n-1/2} + dt_{n+1/2}) / 2` (`dt_{1/2} / 2` at the first), so that
//! `v_{n+1/2} = v_{n-1/2} + h_n a_n` and `u_{n+1} = u_n + dt_{n+1/2} v_{n+1/2}`. With equal
//! steps `h_n = dt` exactly (`(dt + dt) / 2` rounds to `dt`): a fixed run keeps its bits.

/// The smallest step an adaptive run may take, as a fraction of its first: below it the run
/// stops, naming the element whose crushing took the step there. The Taylor bar's foot
/// element, crushed to 1/50 of its length, takes the step to ~2e-2 of the first; 1e-3 keeps
/// a run bounded (at most ~1000x the steps of its first estimate) and leaves room for meshes
/// crushed 20x further.
pub const SMALLEST_STEP_FRACTION: f64 = 1e-3;

/// Whether `t` (s) is the end `end` (s) of a run whose next step would be `step` (s): within
/// 1e-9 of a step (as [`crate::input::estimate::time_step::steps_to`] counts a fixed run's steps).
pub(crate) fn at_end(end: f64, t: f64, step: f64) -> bool {
    end - t <= 1e-9 * step
}

/// The velocity step `h_n` (s) at step `n` between the steps `previous` (`dt_{n-1/2}`) and
/// `next` (`dt_{n+1/2}`), s.
pub(crate) fn velocity_step(n: u64, previous: f64, next: f64) -> f64 {
    if n == 0 {
        0.5 * next
    } else {
        0.5 * (previous + next)
    }
}

/// The step re-estimated at every step (`time.dt.update: every-step`).
#[derive(Debug, Clone)]
pub(crate) struct EveryStep {
    /// `time.dt.cfl`.
    pub cfl: f64,
    /// The plate's stable estimate on the mesh as made (without contact springs), s.
    pub dt_plate: f64,
    /// The first step, s.
    pub first: f64,
    /// `t_n`, s.
    pub time: f64,
    /// The smallest and the largest step the estimate gave, s (a step cut to land on the end
    /// is not counted: it says nothing about the mesh).
    pub range: [f64; 2],
}

impl EveryStep {
    pub fn new(cfl: f64, dt_plate: f64, first: f64) -> EveryStep {
        EveryStep {
            cfl,
            dt_plate,
            first,
            time: 0.0,
            range: [first, first],
        }
    }

    /// The step to take from `t_n` to the run's `end` (s) with the current stable estimate
    /// `stable` (s, contact included): `cfl stable`, cut to land on the end; at the end (the
    /// run stops after this step) the uncut step, whose velocity step closes the energies as
    /// every other step's does. `Err(step)` when the step fell below
    /// [`SMALLEST_STEP_FRACTION`] of the first.
    pub fn next(&mut self, stable: f64, end: f64) -> Result<f64, f64> {
        let step = self.cfl * stable;
        if !(step >= SMALLEST_STEP_FRACTION * self.first) {
            return Err(step);
        }
        self.range = [self.range[0].min(step), self.range[1].max(step)];
        if at_end(end, self.time, step) {
            Ok(step)
        } else {
            Ok(step.min(end - self.time))
        }
    }
}

#[cfg(test)]
mod tests {
    //! The step controller against hand-worked sequences: equal steps keep `h = dt` to the
    //! bit, the last step lands on the end, the collapse bound.
    use super::*;

    #[test]
    fn equal_steps_give_the_step_itself_as_velocity_step() {
        // A mean of two equal steps that rounded would shift every fixed run's bits.
        for dt in [1e-7, 3.3e-8, 0.1, 7.77e-9] {
            assert_eq!(velocity_step(5, dt, dt), dt);
            assert_eq!(velocity_step(0, dt, dt), 0.5 * dt);
        }
        assert_eq!(velocity_step(3, 1.0, 3.0), 2.0);
    }

    #[test]
    fn the_last_step_lands_on_the_end_and_a_collapse_is_refused() {
        let mut s = EveryStep::new(0.5, 2.0, 1.0);
        assert_eq!(s.next(2.0, 10.0), Ok(1.0));
        s.time = 9.75;
        assert_eq!(s.next(2.0, 10.0), Ok(0.25));
        s.time = 10.0;
        assert_eq!(s.next(2.0, 10.0), Ok(1.0), "at the end: the uncut step");
        assert_eq!(s.range, [1.0, 1.0], "the cut step is not counted");
        // 0.5 x 1.9e-3 = 9.5e-4 of the first step: below the bound.
        assert_eq!(s.next(1.9e-3, 20.0), Err(0.5 * 1.9e-3));
        assert!(s.next(f64::NAN, 20.0).is_err());
    }
}
