//! The kinetic energy a kinematic contact takes out, booked at `t_n` as section 7 reads the
//! kinetic energy (`ALGORITHM.md` section 5b's kinematic enforcement and 5c's wall).
//!
//! A kinematic contact acts by impulses: at step `n` its force `f` changes a dof's velocity by
//! `h f / m`, from `v_{n-1/2}` to `v_{n+1/2}` (`h` the velocity step). The half-step kinetic
//! energies then differ by exactly `W_n = h f (v_{n-1/2} + v_{n+1/2}) / 2`, the impulse times
//! the mean of the velocities before and after. Section 7 reads the kinetic energy at `t_n` with
//! `v_n = (v_{n-1/2} + v_{n+1/2}) / 2`, half-way through that change: since
//! `m (v_n^2 - v_{n-1/2}^2) / 2 = (h F / 2) (v_{n-1/2} + v_n) / 2` is linear in the step's total
//! force `F`, the contact's part of it, the share of `W_n` already in the kinetic energy at
//! `t_n`, is `(h f / 2) (v_{n-1/2} + v_n) / 2 = h f (3 v_{n-1/2} + v_{n+1/2}) / 8`. At `t_0`
//! the kinetic energy is that of the initial velocity: none of step 0's impulse is in it.
//!
//! The contact's dissipation at `t_n` is `D_n = -(sum_{k<n} W_k + share_n)`: with it the energy
//! balance of a body stopped by impulses closes at every `t_n`, in the step the impulse acts
//! (a landing's loss booked with half of `W_n`, as before, left `m (v_{n+1/2} - v_{n-1/2})^2 /
//! 8` out for one step: a one-step spike of the balance error at each landing).

/// The works of a kinematic contact's impulses, J, for the whole body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpulseLedger {
    /// `sum_{k<n} W_k`, J.
    done: f64,
    /// `W_n`, J.
    now: f64,
    /// The share of `W_n` in the kinetic energy at `t_n`, J (0 at `t_0`).
    now_at_t_n: f64,
    /// Whether step `n` is the first (`t_0`).
    first: bool,
}

impl Default for ImpulseLedger {
    fn default() -> ImpulseLedger {
        ImpulseLedger {
            done: 0.0,
            now: 0.0,
            now_at_t_n: 0.0,
            first: true,
        }
    }
}

impl ImpulseLedger {
    /// Opens step `n`'s book: the last step's work is done.
    pub fn open(&mut self) {
        self.done += self.now;
        self.now = 0.0;
        self.now_at_t_n = 0.0;
    }

    /// Books the impulse `impulse` (N s, along the dof) that takes a dof's half-step velocity
    /// from `before` to `after` (m/s), counted `weight` times (the symmetry factor, or 1).
    #[inline]
    pub fn book(&mut self, weight: f64, impulse: f64, before: f64, after: f64) {
        let j = weight * impulse;
        self.now += j * 0.5 * (before + after);
        if !self.first {
            self.now_at_t_n += j * 0.125 * (3.0 * before + after);
        }
    }

    /// Closes step `n`'s book (the next step is not `t_0`).
    pub fn close(&mut self) {
        self.first = false;
    }

    /// The kinetic energy taken out up to `t_n`, J: `-(sum_{k<n} W_k + share_n)`.
    pub fn dissipated(&self) -> f64 {
        -(self.done + self.now_at_t_n)
    }
}

#[cfg(test)]
mod tests {
    //! Against the kinetic energies themselves: a mass stopped by one impulse, read at `t_n`
    //! with the mean velocity (section 7).
    use super::*;

    #[test]
    fn the_book_at_t_n_is_the_kinetic_energy_the_impulse_removed_from_it() {
        // m = 2 kg at -3 m/s stopped at step 1 (h = 0.1 s): impulse 6 N s, v from -3 to 0.
        let (m, v) = (2.0, -3.0);
        let mut book = ImpulseLedger::default();
        book.open();
        book.close(); // step 0: nothing
        book.open();
        book.book(1.0, -m * v, v, 0.0);
        book.close();
        // At t_1 the mean velocity is -1.5 m/s: kinetic 2.25 J of 9 J, 6.75 J removed.
        let mean = 0.5 * v;
        let removed = 0.5 * m * (v * v - mean * mean);
        // Bounds 1e-15 J: a few roundings of 9 J sums (the formula is exact in reals); the old
        // half-share rule misses by m (3 m/s)^2 / 8 = 2.25 J.
        assert!(
            (book.dissipated() - removed).abs() < 1e-15,
            "{}",
            book.dissipated()
        );
        // At t_2 all of it.
        book.open();
        book.close();
        assert!((book.dissipated() - 0.5 * m * v * v).abs() < 1e-15);
        // At t_0 the impulse of step 0 is not yet in the kinetic energy.
        let mut first = ImpulseLedger::default();
        first.open();
        first.book(2.0, -m * v, v, 0.0);
        first.close();
        assert_eq!(first.dissipated(), 0.0);
    }
}
