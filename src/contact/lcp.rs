//! Small dense linear complementarity problems: find `R >= 0` with `w = C R - d >= 0` and
//! `R . w = 0`. Used to settle all uncertain contacts of one linearized step at once, so that
//! the contact zone boundary moves to its place in one Newton iteration instead of one node per
//! iteration.
//!
//! Method: primal-dual active set on the dense system (Hintermueller, Ito & Kunisch 2002),
//! with a projected Gauss-Seidel fallback if it cycles. `C` need not be symmetric (friction).

use nalgebra::{DMatrix, DVector};

/// Solve the LCP; returns `None` if neither method reaches `tol` (relative complementarity).
pub fn solve_lcp(c: &DMatrix<f64>, d: &DVector<f64>, tol: f64) -> Option<DVector<f64>> {
    let m = d.len();
    if m == 0 {
        return Some(DVector::zeros(0));
    }
    let scale = d.amax().max(1e-30);
    let mut active: Vec<bool> = d.iter().map(|&x| x > 0.0).collect();
    let mut seen: Vec<Vec<bool>> = Vec::new();
    for _ in 0..100 {
        let idx: Vec<usize> = (0..m).filter(|&i| active[i]).collect();
        let mut r = DVector::zeros(m);
        if !idx.is_empty() {
            let caa = DMatrix::from_fn(idx.len(), idx.len(), |a, b| c[(idx[a], idx[b])]);
            let da = DVector::from_fn(idx.len(), |a, _| d[idx[a]]);
            let sol = caa.lu().solve(&da)?;
            for (a, &i) in idx.iter().enumerate() {
                r[i] = sol[a];
            }
        }
        let w = c * &r - d;
        let next: Vec<bool> = (0..m).map(|i| r[i] - w[i] > 0.0).collect();
        if next == active && r.iter().all(|&x| x >= -tol * scale) && w.iter().all(|&x| x >= -tol * scale) {
            return Some(r.map(|x| x.max(0.0)));
        }
        if seen.contains(&next) {
            break;
        }
        seen.push(active.clone());
        active = next;
    }
    projected_gauss_seidel(c, d, tol)
}

fn projected_gauss_seidel(c: &DMatrix<f64>, d: &DVector<f64>, tol: f64) -> Option<DVector<f64>> {
    let m = d.len();
    let mut r = DVector::zeros(m);
    let scale = d.amax().max(1e-30);
    for _ in 0..20_000 {
        let mut change: f64 = 0.0;
        for i in 0..m {
            let cii = c[(i, i)];
            if cii <= 0.0 {
                return None;
            }
            let wi = (c.row(i) * &r)[0] - d[i];
            let new = (r[i] - wi / cii).max(0.0);
            change = change.max((new - r[i]).abs() * cii);
            r[i] = new;
        }
        if change < tol * scale {
            return Some(r);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_small_contact_lcp() {
        // Two supports under a load: C spd, one contact active.
        let c = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0]);
        let d = DVector::from_vec(vec![1.0, -1.0]);
        let r = solve_lcp(&c, &d, 1e-12).unwrap();
        let w = &c * &r - &d;
        assert!((r[0] - 0.5).abs() < 1e-12 && r[1] == 0.0);
        assert!(w.iter().all(|&x| x >= -1e-12));
        assert!((r[0] * w[0]).abs() < 1e-12 && (r[1] * w[1]).abs() < 1e-12);
    }
}
