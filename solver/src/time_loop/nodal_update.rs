//! The central differences' nodal updates (steps 2-3 and the displacement update of
//! `ALGORITHM.md` section 6), compiled as [`Kernel`]s for the element kernels' instruction set.

use crate::lanes::simd::{each_lane, Kernel, Lanes, LANES};

/// Steps 2-3: `v += h a` with `a = -f_int / m` per dof (`h`: the velocity step, s); `run`
/// returns `sum m v_n^2` (kg m^2/s^2) with `v_n` the mean of the old and new velocity, summed
/// as [`LANES`] partial sums (dof `d` into sum `d % LANES`) then added in order: a fixed
/// order (the same bits on every run and thread count) that lets the loop run in vectors
/// instead of waiting on one chain of additions. A [`Kernel`], compiled for the element kernels'
/// instruction set (the same bits on any: no operation here is fused or reordered).
pub(crate) struct VelocityUpdate<'a> {
    pub(crate) v: &'a mut [f64],
    pub(crate) f_int: &'a [f64],
    /// Per dof, 1/kg.
    pub(crate) inverse_mass: &'a [f64],
    /// Per node, kg.
    pub(crate) mass: &'a [f64],
    pub(crate) h: f64,
}

impl Kernel for VelocityUpdate<'_> {
    type Output = f64;
    #[inline(always)]
    fn run(self) -> f64 {
        let (v, h) = (self.v, self.h);
        let (f_int, inverse_mass) = (&self.f_int[..v.len()], &self.inverse_mass[..v.len()]);
        let mass = &self.mass[..v.len() / 2];
        let group =
            |v: &mut [f64], f: &[f64], im: &[f64], m: &[f64]| velocity_group(v, f, im, m, h);
        let mut sums = Lanes::splat(0.0);
        let groups = v
            .chunks_exact_mut(LANES)
            .zip(f_int.chunks_exact(LANES))
            .zip(inverse_mass.chunks_exact(LANES))
            .zip(mass.chunks_exact(LANES / 2));
        for (((v, f), im), m) in groups {
            sums += group(v, f, im, m);
        }
        // The last dofs (fewer than LANES), padded with zeros that add 0 to their sums.
        let whole = v.len() - v.len() % LANES;
        let mut tail = [[0.0; LANES]; 3];
        let mut tail_mass = [0.0; LANES / 2];
        for d in whole..v.len() {
            let i = d - whole;
            (tail[0][i], tail[1][i], tail[2][i]) = (v[d], f_int[d], inverse_mass[d]);
            tail_mass[i / 2] = mass[d / 2];
        }
        let [mut tv, tf, tim] = tail;
        sums += group(&mut tv, &tf, &tim, &tail_mass);
        let n = v.len() - whole;
        v[whole..].copy_from_slice(&tv[..n]);
        sums.0.iter().sum()
    }
}

/// [`VelocityUpdate`] of a group of [`LANES`] dofs `v` (m/s) with their forces `f` (N) and
/// inverse masses `inverse_mass` (1/kg) and their nodes' masses `m` (kg), in lanes; returns
/// `v_n^2 m` per dof. (A function, not a closure: a closure may be left out of line,
/// compiled for the baseline.)
#[inline(always)]
fn velocity_group(v: &mut [f64], f: &[f64], inverse_mass: &[f64], m: &[f64], h: f64) -> Lanes {
    let lanes = |x: &[f64]| Lanes(each_lane(|i| x[i]));
    let (old, f, im) = (lanes(v), lanes(f), lanes(inverse_mass));
    let m = Lanes(each_lane(|i| m[i / 2]));
    let new = old + h * (f.map(|x| -x) * im);
    let mean = 0.5 * (old + new);
    v.copy_from_slice(&new.0);
    m * mean * mean
}

/// `u += dt v` per dof (m; `dt` s, `v` m/s), compiled as [`VelocityUpdate`].
pub(crate) struct Displace<'a> {
    pub(crate) u: &'a mut [f64],
    pub(crate) v: &'a [f64],
    pub(crate) dt: f64,
}

impl Kernel for Displace<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        for (u, v) in self.u.iter_mut().zip(self.v) {
            *u += self.dt * v;
        }
    }
}
