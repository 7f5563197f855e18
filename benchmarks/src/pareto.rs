//! The Pareto front of work-precision points: the configurations that no other configuration
//! beats in both error and wall time.

/// Indices of the non-dominated points of `points` = (error, wall time s): no other point is
/// at least as good in both and strictly better in one. Points with a non-finite coordinate
/// are left out. Sorted from the fastest to the most accurate (time ascending, then error
/// descending).
pub fn front(points: &[(f64, f64)]) -> Vec<usize> {
    let finite = |&(e, t): &(f64, f64)| e.is_finite() && t.is_finite();
    let dominated = |&(e, t): &(f64, f64)| {
        points
            .iter()
            .filter(|p| finite(p))
            .any(|&(e2, t2)| (e2 < e && t2 <= t) || (e2 <= e && t2 < t))
    };
    let mut idx: Vec<usize> = (0..points.len())
        .filter(|&i| finite(&points[i]) && !dominated(&points[i]))
        .collect();
    idx.sort_by(|&a, &b| {
        let (pa, pb) = (points[a], points[b]);
        pa.1.total_cmp(&pb.1).then(pb.0.total_cmp(&pa.0))
    });
    idx
}

#[cfg(test)]
mod tests {
    use super::front;

    #[test]
    fn front_keeps_exactly_the_non_dominated_points() {
        // (error, time s), hand-made: the front is 3 -> 0 -> 4 (fastest to most accurate).
        let points = [
            (1e-2, 2.0),           // 0: front
            (5e-2, 2.5),           // 1: dominated by 0 (worse in both)
            (1e-2, 3.0),           // 2: dominated by 0 (same error, slower)
            (1e-1, 1.0),           // 3: front, the fastest
            (1e-3, 9.0),           // 4: front, the most accurate
            (2e-3, 9.5),           // 5: dominated by 4
            (f64::NAN, 0.1),       // 6: no error measured: left out
            (1e-1, f64::INFINITY), // 7: left out
        ];
        assert_eq!(front(&points), vec![3, 0, 4]);
    }

    #[test]
    fn a_single_point_and_no_points() {
        assert_eq!(front(&[(1.0, 1.0)]), vec![0]);
        assert!(front(&[]).is_empty());
    }

    #[test]
    fn a_faster_and_more_accurate_point_removes_all_others() {
        let points = [(1e-2, 2.0), (1e-3, 0.5), (1e-1, 1.0)];
        assert_eq!(front(&points), vec![1]);
    }
}
