//! The closing summary of `impact diff`: what moved, largest relative move first, the
//! physical quantities (forces, displacements, energies, stresses, impulse, the run's steps)
//! before the bookkeeping ones (round-off residuals: every `*_error` key and column, such as
//! `impulse_momentum_error` and the energy balance error), so that the headline is the
//! largest physical move, not a residual of 3.5e-15 becoming 9.5e-16 (a 73 % move).

use std::fmt::Write as _;

/// Moves listed per group; the rest are counted (the tables above list everything).
pub const LISTED: usize = 12;

/// One summary key or history column that differs between the runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    pub name: String,
    /// Relative to the column's peak (history) or to max(|A|, |B|) (summary); infinite for a
    /// changed text or a value in one run only.
    pub rel: f64,
    /// Its verdict as the tables print it (`within`, `BEYOND`).
    pub verdict: &'static str,
    /// `A -> B` for a summary key, empty for a column.
    pub values: String,
    pub bookkeeping: bool,
}

impl Move {
    pub fn new(name: &str, rel: f64, verdict: &'static str, values: String) -> Move {
        Move {
            name: name.to_string(),
            rel,
            verdict,
            values,
            bookkeeping: is_bookkeeping(name),
        }
    }
}

/// Whether a quantity is bookkeeping (a round-off residual), not physics. The wall-clock keys
/// are bookkeeping too, but never moves: they are shown, not compared.
pub fn is_bookkeeping(name: &str) -> bool {
    name.ends_with("error")
}

/// `moves` in the order they are listed: physical ones first, each group by relative size,
/// largest first (equal sizes in the tables' order).
pub fn sorted(mut moves: Vec<Move>) -> Vec<Move> {
    moves.sort_by(|x, y| {
        x.bookkeeping
            .cmp(&y.bookkeeping)
            .then(y.rel.total_cmp(&x.rel))
    });
    moves
}

/// The list printed before the closing line (empty when nothing moved).
pub fn listing(moves: &[Move]) -> String {
    let mut s = String::new();
    if moves.is_empty() {
        return s;
    }
    let w = moves.iter().map(|m| m.name.len()).max().unwrap_or(0);
    let _ = writeln!(
        s,
        "\nmoves, largest first (relative to the column's peak, or to the larger of A and B for a summary key):"
    );
    for (bookkeeping, title) in [
        (false, "physical"),
        (true, "bookkeeping (round-off residuals)"),
    ] {
        let group: Vec<&Move> = moves
            .iter()
            .filter(|m| m.bookkeeping == bookkeeping)
            .collect();
        if group.is_empty() {
            continue;
        }
        let _ = writeln!(s, "  {title}:");
        for m in group.iter().take(LISTED) {
            let values = if m.values.is_empty() {
                String::new()
            } else {
                format!("  ({})", m.values)
            };
            let _ = writeln!(
                s,
                "    {:w$}  moved {:>9.3e}  {}{values}",
                m.name, m.rel, m.verdict
            );
        }
        if group.len() > LISTED {
            let _ = writeln!(
                s,
                "    ... and {} more (see the tables)",
                group.len() - LISTED
            );
        }
    }
    s
}

/// The closing line's last part: the largest physical move, else the largest bookkeeping one
/// (said to be so), else that nothing moved. A key or column in one run only, or a changed
/// text, has no size (its `rel` is infinite): it never heads the line as "inf", it is counted
/// after the largest sized move.
pub fn headline(moves: &[Move]) -> String {
    let sized: Vec<&Move> = moves.iter().filter(|m| m.rel.is_finite()).collect();
    let unsized_count = moves.len() - sized.len();
    let largest = match sized.first() {
        None if unsized_count == 0 => return "all compared values bit-identical".to_string(),
        None => "no value moved by a measurable amount".to_string(),
        Some(m) if !m.bookkeeping => {
            format!("largest relative change {:.3e} in {}", m.rel, m.name)
        }
        Some(m) => format!(
            "no physical quantity moved; largest relative change {:.3e} in {} (bookkeeping)",
            m.rel, m.name
        ),
    };
    match unsized_count {
        0 => largest,
        n => format!(
            "{largest}; {n} without a size (in one run only, or a changed text: see the tables)"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The old line read "largest relative change inf in X" for a key in one run only.
    #[test]
    fn a_key_in_one_run_only_never_heads_the_line() {
        let moves = sorted(vec![
            Move::new(
                "wall.final_length_m",
                f64::INFINITY,
                "BEYOND",
                "- -> 0.02".into(),
            ),
            Move::new(
                "peak_contact_force_N",
                2.0e-3,
                "BEYOND",
                "1 -> 1.002".into(),
            ),
        ]);
        assert_eq!(
            headline(&moves),
            "largest relative change 2.000e-3 in peak_contact_force_N; 1 without a size \
             (in one run only, or a changed text: see the tables)"
        );
        let only_unsized = sorted(vec![Move::new(
            "title",
            f64::INFINITY,
            "BEYOND",
            "a -> b".into(),
        )]);
        assert!(headline(&only_unsized).starts_with("no value moved by a measurable amount; 1"));
        assert_eq!(headline(&[]), "all compared values bit-identical");
    }
}
