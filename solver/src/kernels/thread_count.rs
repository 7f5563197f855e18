//! How many threads a run may be given (`impact simulate --threads N`, the Python package's
//! `threads=`): 1 to [`max_threads`], 4 x the cores this process may use and at most
//! [`THREADS_CAP`]. The element loop's team gives each thread a contiguous share of the
//! elements, so threads beyond the cores only take turns on them: 4 x leaves room to test
//! oversubscription (and 2 threads on a 1-core machine), and the cap keeps the start-up of
//! the threads (and of rayon's pool) to milliseconds (issue 28: `--threads 65535` sat in
//! thread start-up for minutes, `threads=10**9` hung).

/// The most threads on any machine.
pub const THREADS_CAP: usize = 256;

/// Cores this process may use (1 when unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The most threads a run may be given on this machine: 4 x [`cores`], at most [`THREADS_CAP`].
pub fn max_threads() -> usize {
    (4 * cores()).min(THREADS_CAP)
}

/// `what = value: must be an integer from 1 to N (...)`, for a refused thread count.
pub fn refusal(what: &str, value: &str) -> String {
    format!(
        "{what} = {value}: must be an integer from 1 to {} (4 x the {} cores this machine gives the process, at most {THREADS_CAP}; more threads only take turns on the cores)",
        max_threads(),
        cores()
    )
}

/// `n` as a thread count, or the message naming `what`, the value and what is allowed.
pub fn check_threads(what: &str, n: u64) -> Result<usize, String> {
    match usize::try_from(n) {
        Ok(k) if (1..=max_threads()).contains(&k) => Ok(k),
        _ => Err(refusal(what, &n.to_string())),
    }
}

#[cfg(test)]
mod tests {
    //! The bound: 1 to 4 x the cores (at most 256) pass, 0 and anything above are refused
    //! with the name, the value and the range.
    use super::*;

    #[test]
    fn thread_counts_from_1_to_the_bound_pass_and_others_are_refused() {
        let max = max_threads();
        assert!((4..=THREADS_CAP).contains(&max), "{max}");
        assert_eq!(max, (4 * cores()).min(256));
        assert_eq!(check_threads("--threads", 1), Ok(1));
        assert_eq!(check_threads("--threads", max as u64), Ok(max));
        for n in [0, max as u64 + 1, 257, 65535, 1_000_000_000, u64::MAX] {
            let e = check_threads("threads", n).unwrap_err();
            assert!(
                e.starts_with(&format!(
                    "threads = {n}: must be an integer from 1 to {max} "
                )),
                "{e}"
            );
        }
    }
}
