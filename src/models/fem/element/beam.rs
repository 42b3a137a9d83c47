//! Local beam element in its co-rotated frame: axial, torsion and bending in two planes with the
//! coupling of the axial force to bending (the "shallow arch" local formulation).
//!
//! Local deformational DOFs `p = [u, tA1, tA2, tA3, tB1, tB2, tB3]`: `u = l - l0` the
//! elongation (m), `t*1` twist and `t*2`, `t*3` bending rotations of the end sections
//! relative to the chord frame (rad). Strain energy
//! ```text
//! eps = u/l0 + (1/30) [2 tA2^2 - tA2 tB2 + 2 tB2^2 + (same for 3)]     (mean axial strain)
//! U   = EA l0 eps^2 / 2 + EI/l0 (2 tA^2 + 2 tA tB + 2 tB^2) per plane + GJ/(2 l0) (tB1 - tA1)^2
//! ```
//! `N = EA eps` is the axial force (tension > 0). Its Hessian at `p = 0` gives the elastic
//! stiffness plus the consistent geometric stiffness of docs/theory.md 5.3 (2Nl/15, -Nl/30 on the
//! end rotations; the chord-rotation terms 6N/5l come from the co-rotational frame).

/// Element section and length, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamSection {
    /// Stress-free length, m.
    pub l0: f64,
    /// Axial stiffness, N.
    pub ea: f64,
    /// Bending stiffness, N.m2.
    pub ei: f64,
    /// Torsional stiffness, N.m2.
    pub gj: f64,
}

/// Local internal force (7) and tangent (7x7, row-major) of the element, and its axial force N.
#[derive(Debug, Clone, Copy)]
pub struct LocalResponse {
    /// `dU/dp`: [N, mA1, mA2, mA3, mB1, mB2, mB3] (N, N.m).
    pub force: [f64; 7],
    /// `d2U/dp2`, row-major.
    pub tangent: [[f64; 7]; 7],
    /// Axial force, N (tension positive).
    pub axial_force: f64,
}

/// Evaluate the local element. `with_geometric = false` drops the axial-force/bending coupling
/// (a linear beam), used to show that the geometric stiffness matters.
#[inline(always)]
pub fn local_response(s: &BeamSection, p: &[f64; 7], with_geometric: bool) -> LocalResponse {
    let l0 = s.l0;
    let [u, ta1, ta2, ta3, tb1, tb2, tb3] = *p;
    let c = if with_geometric { 1.0 / 30.0 } else { 0.0 };
    let eps =
        u / l0 + c * (2.0 * ta2 * ta2 - ta2 * tb2 + 2.0 * tb2 * tb2 + 2.0 * ta3 * ta3 - ta3 * tb3 + 2.0 * tb3 * tb3);
    let n = s.ea * eps;
    // gradient of eps
    let mut g = [0.0; 7];
    g[0] = 1.0 / l0;
    g[2] = c * (4.0 * ta2 - tb2);
    g[5] = c * (4.0 * tb2 - ta2);
    g[3] = c * (4.0 * ta3 - tb3);
    g[6] = c * (4.0 * tb3 - ta3);
    let kb = s.ei / l0;
    let kt = s.gj / l0;
    let mut f = [0.0; 7];
    for (fi, gi) in f.iter_mut().zip(g.iter()) {
        *fi = n * l0 * gi;
    }
    f[2] += kb * (4.0 * ta2 + 2.0 * tb2);
    f[5] += kb * (2.0 * ta2 + 4.0 * tb2);
    f[3] += kb * (4.0 * ta3 + 2.0 * tb3);
    f[6] += kb * (2.0 * ta3 + 4.0 * tb3);
    f[1] += -kt * (tb1 - ta1);
    f[4] += kt * (tb1 - ta1);
    let mut k = [[0.0; 7]; 7];
    for i in 0..7 {
        for j in 0..7 {
            k[i][j] = s.ea * l0 * g[i] * g[j];
        }
    }
    let nl = n * l0 * c;
    for (a, b) in [(2usize, 5usize), (3, 6)] {
        k[a][a] += 4.0 * kb + 4.0 * nl;
        k[b][b] += 4.0 * kb + 4.0 * nl;
        k[a][b] += 2.0 * kb - nl;
        k[b][a] += 2.0 * kb - nl;
    }
    k[1][1] += kt;
    k[4][4] += kt;
    k[1][4] -= kt;
    k[4][1] -= kt;
    LocalResponse {
        force: f,
        tangent: k,
        axial_force: n,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_is_the_derivative_of_the_force() {
        let s = BeamSection {
            l0: 0.7,
            ea: 3.6e9,
            ei: 7.3e6,
            gj: 5.6e6,
        };
        let p = [1e-4, 0.01, -0.02, 0.015, 0.03, 0.01, -0.005];
        let r = local_response(&s, &p, true);
        for j in 0..7 {
            let h = 1e-7;
            let mut pp = p;
            let mut pm = p;
            pp[j] += h;
            pm[j] -= h;
            let fp = local_response(&s, &pp, true).force;
            let fm = local_response(&s, &pm, true).force;
            for i in 0..7 {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                assert!(
                    (fd - r.tangent[i][j]).abs() <= 1e-6 * r.tangent[i][j].abs().max(1e3),
                    "K[{i}][{j}]"
                );
            }
        }
    }

    #[test]
    fn geometric_terms_match_physics_md() {
        // docs/theory.md 5.3: rotational block of K_G is N l (2/15, -1/30).
        let s = BeamSection {
            l0: 2.0,
            ea: 1e9,
            ei: 0.0,
            gj: 0.0,
        };
        let n = 1e5;
        let p = [n * 2.0 / 1e9, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let r = local_response(&s, &p, true);
        assert!((r.axial_force - n).abs() < 1e-6);
        assert!((r.tangent[2][2] - 2.0 * n * 2.0 / 15.0).abs() < 1e-6);
        assert!((r.tangent[2][5] + n * 2.0 / 30.0).abs() < 1e-6);
    }
}
