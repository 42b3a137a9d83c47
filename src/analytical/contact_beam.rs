//! Planar beam-column in a straight inclined hole with unilateral wall contact along its whole
//! length: the reference for stabilizer blades and bit gauges that touch the wall over a length
//! (docs/theory.md 3.4 and 10.3).
//!
//! **Method.** Small-deflection beam-column theory in the vertical plane of the hole
//! (Timoshenko & Gere 1961, ch. 1; the same equation as Lubinski's pendulum, [`super::pendulum`]):
//! `(EI y'')'' + (P y')' = q`, `x` up-hole from the bit face, `y` toward the **low side**,
//! `q = w_b sin I` the lateral weight, `P(x) = WOB - ∫ w_b cos I dx` the compression (positive).
//! It is discretized by cubic Hermite beam elements with the consistent geometric stiffness of
//! the compression (Przemieniecki 1968, *Theory of Matrix Structural Analysis*, ch. 15: element
//! stiffness `EI/l^3 [12, 6l, ...] - P/(30 l) [36, 3l, ...]`, `P` at the element's middle), on a
//! uniform fine mesh. Every node of a part that can touch the wall is held between the two
//! walls, `-r <= y <= r` (`r` its radial clearance): the contact is unilateral on both the high
//! and the low side, at every node, so a blade of length `b` touches along `b` as finely as the
//! mesh. The bit face is held on the axis (`y(0) = 0`) and free to rotate. The resulting
//! bound-constrained quadratic programme (the equilibrium is the minimum of the potential energy
//! once the contacts are known) is solved by the primal active-set method for convex quadratic
//! programmes (Nocedal & Wright 2006, *Numerical Optimization*, algorithm 16.3): equality
//! steps with the working set of nodes held on a wall, blocking walls added, the wall with the
//! most negative multiplier (a wall pulling) released. Each step factors the band matrix by its
//! own `LDL^T`; a non-positive pivot (a free span beyond buckling) is reported, never divided by.
//!
//! Written only from these sources: no code, constant or helper is shared with the production
//! model (`std` only). Signs as in [`super::pendulum`]: `side_force > 0` when the bit pushes the
//! rock toward the low side (drillpath's build force is `-side_force`), `tilt = y'(0) > 0`
//! toward the high side.

use super::{require_finite, require_non_negative, require_positive, AnalyticalError};

/// A length of uniform string (from the bit upward).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// Length, m; 0 makes a contact point of this clearance at the node where it sits (a
    /// point stabilizer).
    pub length: f64,
    /// Bending stiffness, N.m2.
    pub ei: f64,
    /// Buoyed weight per length, N/m.
    pub weight: f64,
    /// Radial clearance to the wall, m (`None`: never touches, e.g. the bit's body).
    pub clearance: Option<f64>,
}

/// How the top of the modelled length is held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TopEnd {
    /// On the hole axis, free to rotate (a simply supported end).
    Pinned,
    /// On the low-side wall (`y` = the top piece's clearance) and parallel to the hole: a long
    /// string lying on the wall above.
    OnWall,
}

/// The problem: pieces from the bit upward in a straight hole.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactBeam {
    /// Pieces from the bit face upward.
    pub pieces: Vec<Piece>,
    /// Hole inclination, rad.
    pub inclination: f64,
    /// Compression at the bit (weight on bit), N.
    pub wob: f64,
    /// Top condition.
    pub top: TopEnd,
    /// Longest element, m (each piece is divided evenly).
    pub element: f64,
}

/// Solution (signs in the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSolution {
    /// Bit side force, N: positive when the bit pushes the rock toward the low side.
    pub side_force: f64,
    /// Bit tilt `y'(0)`, rad, positive toward the high side.
    pub tilt: f64,
    /// Node positions from the bit, m.
    pub x: Vec<f64>,
    /// Lateral displacement toward the low side, m.
    pub y: Vec<f64>,
    /// Slope `y'`, rad.
    pub slope: Vec<f64>,
    /// Wall force on the string at each node, N: positive from the high-side wall (pushing
    /// toward the low side), negative from the low-side wall, 0 where free.
    pub wall_force: Vec<f64>,
    /// Active-set iterations taken.
    pub iterations: usize,
}

/// Semi-bandwidth of the Hermite element's matrix (2 DOFs per node).
const BAND: usize = 3;

/// Symmetric band matrix, lower part: `rows[i][d] = K[i][i - d]`.
struct Band {
    rows: Vec<[f64; BAND + 1]>,
}

impl Band {
    fn zeros(n: usize) -> Band {
        Band {
            rows: vec![[0.0; BAND + 1]; n],
        }
    }
    fn get(&self, i: usize, j: usize) -> f64 {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        if i - j > BAND {
            0.0
        } else {
            self.rows[i][i - j]
        }
    }
    fn add(&mut self, i: usize, j: usize, v: f64) {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        self.rows[i][i - j] += v;
    }
    fn set(&mut self, i: usize, j: usize, v: f64) {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        self.rows[i][i - j] = v;
    }
    fn mul(&self, v: &[f64]) -> Vec<f64> {
        let n = self.rows.len();
        (0..n)
            .map(|i| {
                let lo = i.saturating_sub(BAND);
                let hi = (i + BAND).min(n - 1);
                (lo..=hi).map(|j| self.get(i, j) * v[j]).sum()
            })
            .collect()
    }
    /// Solve `K u = b` by `LDL^T`; `Err` at a non-positive pivot (row).
    fn solve(&self, b: &[f64]) -> Result<Vec<f64>, usize> {
        let n = self.rows.len();
        let mut l = self.rows.clone();
        let mut d = vec![0.0; n];
        for i in 0..n {
            let lo = i.saturating_sub(BAND);
            for j in lo..i {
                let mut s = l[i][i - j];
                for k in lo.max(j.saturating_sub(BAND))..j {
                    s -= l[i][i - k] * d[k] * l[j][j - k];
                }
                l[i][i - j] = s / d[j];
            }
            let mut s = l[i][0];
            for k in lo..i {
                s -= l[i][i - k] * l[i][i - k] * d[k];
            }
            if s.is_nan() || s <= 0.0 {
                return Err(i);
            }
            d[i] = s;
        }
        let mut u = b.to_vec();
        for i in 0..n {
            for k in i.saturating_sub(BAND)..i {
                u[i] -= l[i][i - k] * u[k];
            }
        }
        for i in 0..n {
            u[i] /= d[i];
        }
        for i in (0..n).rev() {
            for k in i + 1..(i + BAND + 1).min(n) {
                u[i] -= l[k][k - i] * u[k];
            }
        }
        Ok(u)
    }
}

/// The assembled problem: stiffness, load, node positions and clearances.
struct Assembled {
    k: Band,
    f: Vec<f64>,
    x: Vec<f64>,
    clearance: Vec<Option<f64>>,
    /// Fixed DOFs other than the contacts: (dof, value).
    fixed: Vec<(usize, f64)>,
    scale: f64,
}

fn check(problem: &ContactBeam) -> Result<(), AnalyticalError> {
    if problem.pieces.iter().map(|p| p.length).sum::<f64>() <= 0.0 {
        return Err(AnalyticalError::InvalidInput("pieces", "no length".into()));
    }
    for p in &problem.pieces {
        require_non_negative("length", p.length)?;
        require_positive("ei", p.ei)?;
        require_finite("weight", p.weight)?;
        if let Some(r) = p.clearance {
            require_non_negative("clearance", r)?;
        }
    }
    require_finite("inclination", problem.inclination)?;
    require_finite("wob", problem.wob)?;
    require_positive("element", problem.element)?;
    if problem.top == TopEnd::OnWall && problem.pieces.last().and_then(|p| p.clearance).is_none() {
        return Err(AnalyticalError::InvalidInput(
            "top",
            "a top on the wall needs a clearance on the top piece".into(),
        ));
    }
    Ok(())
}

/// The smaller of two optional clearances (the wider part touches first).
fn tighter(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

fn assemble(problem: &ContactBeam) -> Assembled {
    let (s, c) = problem.inclination.sin_cos();
    let mut x = vec![0.0];
    let mut clearance: Vec<Option<f64>> = vec![None];
    // elements: (length, EI, weight)
    let mut elements: Vec<(f64, f64, f64)> = Vec::new();
    for (k, p) in problem.pieces.iter().enumerate() {
        let start = *x.last().expect("the bit node");
        if k > 0 || p.length == 0.0 {
            let last = clearance.len() - 1;
            clearance[last] = tighter(clearance[last], p.clearance);
        }
        if p.length == 0.0 {
            continue;
        }
        let n = ((p.length / problem.element) - 1e-9).ceil().max(1.0) as usize;
        let l = p.length / n as f64;
        for j in 1..=n {
            x.push(start + l * j as f64);
            clearance.push(p.clearance);
            elements.push((l, p.ei, p.weight));
        }
    }
    clearance[0] = None;
    let nodes = x.len();
    let mut k = Band::zeros(2 * nodes);
    let mut f = vec![0.0; 2 * nodes];
    let mut compression = problem.wob;
    let mut total_weight = 0.0;
    for (e, &(l, ei, w)) in elements.iter().enumerate() {
        let p_mid = compression - 0.5 * w * c * l;
        compression -= w * c * l;
        total_weight += w.abs() * l;
        let ke = [
            [12.0, 6.0 * l, -12.0, 6.0 * l],
            [6.0 * l, 4.0 * l * l, -6.0 * l, 2.0 * l * l],
            [-12.0, -6.0 * l, 12.0, -6.0 * l],
            [6.0 * l, 2.0 * l * l, -6.0 * l, 4.0 * l * l],
        ];
        let kg = [
            [36.0, 3.0 * l, -36.0, 3.0 * l],
            [3.0 * l, 4.0 * l * l, -3.0 * l, -l * l],
            [-36.0, -3.0 * l, 36.0, -3.0 * l],
            [3.0 * l, -l * l, -3.0 * l, 4.0 * l * l],
        ];
        let q = w * s;
        let fe = [q * l / 2.0, q * l * l / 12.0, q * l / 2.0, -q * l * l / 12.0];
        let dofs = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3];
        for a in 0..4 {
            f[dofs[a]] += fe[a];
            for b in 0..=a {
                let v = ei / l.powi(3) * ke[a][b] - p_mid / (30.0 * l) * kg[a][b];
                k.add(dofs[a], dofs[b], v);
            }
        }
    }
    let top = nodes - 1;
    let mut fixed = vec![(0, 0.0)];
    match problem.top {
        TopEnd::Pinned => fixed.push((2 * top, 0.0)),
        TopEnd::OnWall => {
            fixed.push((2 * top, clearance[top].unwrap_or(0.0)));
            fixed.push((2 * top + 1, 0.0));
        }
    }
    clearance[top] = None;
    Assembled {
        k,
        f,
        x,
        clearance,
        fixed,
        scale: total_weight + problem.wob.abs() + 1.0,
    }
}

/// Displacements with the DOFs of `held` (dof, value) prescribed.
fn equality_solve(a: &Assembled, held: &[(usize, f64)]) -> Result<Vec<f64>, AnalyticalError> {
    let n = a.f.len();
    let mut k = Band { rows: a.k.rows.clone() };
    let mut b = a.f.clone();
    for &(i, v) in held {
        let lo = i.saturating_sub(BAND);
        for (j, bj) in b.iter_mut().enumerate().take((i + BAND + 1).min(n)).skip(lo) {
            if j != i {
                *bj -= a.k.get(j, i) * v;
                k.set(i, j, 0.0);
            }
        }
    }
    for &(i, v) in held {
        k.set(i, i, 1.0);
        b[i] = v;
    }
    k.solve(&b).map_err(|row| {
        AnalyticalError::Buckled(format!(
            "non-positive pivot at x = {:.3} m: a free span is beyond buckling",
            a.x[row / 2]
        ))
    })
}

/// Solve the contact problem (module docs).
pub fn solve(problem: &ContactBeam) -> Result<ContactSolution, AnalyticalError> {
    check(problem)?;
    let a = assemble(problem);
    if let Some((side, y)) = warm_start(problem, &a) {
        if let Ok(s) = active_set(&a, side, y) {
            return Ok(s);
        }
    }
    // cold: every node that can touch on the low-side wall, the rest in equilibrium with it
    let side: Vec<i8> = a.clearance.iter().map(|c| i8::from(c.is_some())).collect();
    let y = equality_solve(&a, &held(&a, &side))?;
    active_set(&a, side, y)
}

/// The prescribed DOFs of working set `side`: the supports and the nodes held on a wall.
fn held(a: &Assembled, side: &[i8]) -> Vec<(usize, f64)> {
    let mut h = a.fixed.clone();
    for (i, &sd) in side.iter().enumerate() {
        if sd != 0 {
            h.push((2 * i, f64::from(sd) * a.clearance[i].unwrap_or(0.0)));
        }
    }
    h
}

/// The primal active-set iteration from the working set `side` (+1 on the low-side wall, -1
/// on the high-side wall, 0 free) and the start `y` (all DOFs; made feasible: held nodes on
/// their wall, free nodes beyond a wall put on it and held there).
fn active_set(a: &Assembled, mut side: Vec<i8>, mut y: Vec<f64>) -> Result<ContactSolution, AnalyticalError> {
    let nodes = a.x.len();
    for i in 0..nodes {
        let Some(r) = a.clearance[i] else {
            continue;
        };
        if side[i] == 0 && y[2 * i].abs() > r {
            side[i] = if y[2 * i] > 0.0 { 1 } else { -1 };
        }
        if side[i] != 0 {
            y[2 * i] = f64::from(side[i]) * r;
        }
    }
    for &(dof, v) in &a.fixed {
        y[dof] = v;
    }
    let max_iterations = 20 * nodes + 100;
    let length_tol = 1e-13;
    for iteration in 0..max_iterations {
        let target = equality_solve(a, &held(a, &side))?;
        let step: Vec<f64> = target.iter().zip(&y).map(|(t, v)| t - v).collect();
        if step.iter().all(|d| d.abs() <= length_tol) {
            y = target;
            let reaction: Vec<f64> = a.k.mul(&y).iter().zip(&a.f).map(|(ky, f)| ky - f).collect();
            // multiplier of a held wall: the push it exerts, >= 0 at equilibrium
            let worst = (0..nodes)
                .filter(|&i| side[i] != 0)
                .map(|i| (i, -f64::from(side[i]) * reaction[2 * i]))
                .min_by(|p, q| p.1.total_cmp(&q.1));
            match worst {
                Some((i, m)) if m < -1e-10 * a.scale => side[i] = 0,
                _ => return Ok(finish(a, &side, y, reaction, iteration + 1)),
            }
            continue;
        }
        // longest feasible fraction of the step, and the wall that blocks it
        let mut alpha = 1.0;
        let mut blocking = None;
        for i in 0..nodes {
            let (Some(r), 0) = (a.clearance[i], side[i]) else {
                continue;
            };
            let (v, p) = (y[2 * i], step[2 * i]);
            if p == 0.0 {
                continue;
            }
            let sd: i8 = if p > 0.0 { 1 } else { -1 };
            let t = ((f64::from(sd) * r - v) / p).max(0.0);
            if t < alpha {
                alpha = t;
                blocking = Some((i, sd));
            }
        }
        for (v, p) in y.iter_mut().zip(&step) {
            *v += alpha * p;
        }
        if let Some((i, sd)) = blocking {
            side[i] = sd;
            y[2 * i] = f64::from(sd) * a.clearance[i].unwrap_or(0.0);
        }
    }
    Err(AnalyticalError::NoConvergence(format!(
        "active set: {max_iterations} iterations"
    )))
}

/// Nodes above which a problem is first solved on a mesh four times coarser, whose solution
/// starts the fine one (the active-set method then only moves the contact zones' ends).
const WARM_START_NODES: usize = 400;

/// A start for a fine mesh from the solution on a mesh four times coarser: its displacement
/// and slope interpolated by the cubic Hermite shape functions, and the walls it touches at
/// each node (at a zero-clearance node, the side of the nearest coarse node's wall force).
/// None on a mesh of few nodes or when the coarse problem fails.
fn warm_start(problem: &ContactBeam, a: &Assembled) -> Option<(Vec<i8>, Vec<f64>)> {
    if a.x.len() <= WARM_START_NODES {
        return None;
    }
    let coarse = ContactBeam {
        element: 4.0 * problem.element,
        ..problem.clone()
    };
    let c = solve(&coarse).ok()?;
    let last = c.x.len() - 1;
    let mut side = Vec::with_capacity(a.x.len());
    let mut y = Vec::with_capacity(2 * a.x.len());
    for (&x, r) in a.x.iter().zip(&a.clearance) {
        let j = c.x.partition_point(|&xc| xc < x).clamp(1, last);
        let h = c.x[j] - c.x[j - 1];
        let t = ((x - c.x[j - 1]) / h).clamp(0.0, 1.0);
        let (h00, h10, h01, h11) = (
            (1.0 + 2.0 * t) * (1.0 - t) * (1.0 - t),
            t * (1.0 - t) * (1.0 - t),
            t * t * (3.0 - 2.0 * t),
            t * t * (t - 1.0),
        );
        let v = h00 * c.y[j - 1] + h * h10 * c.slope[j - 1] + h01 * c.y[j] + h * h11 * c.slope[j];
        let d = 6.0 * t * (t - 1.0) / h * (c.y[j - 1] - c.y[j])
            + (1.0 - t) * (1.0 - 3.0 * t) * c.slope[j - 1]
            + t * (3.0 * t - 2.0) * c.slope[j];
        y.push(v);
        y.push(d);
        let Some(r) = *r else {
            side.push(0);
            continue;
        };
        let nearest = if t < 0.5 { j - 1 } else { j };
        let tol = 1e-9 * r.max(1e-6);
        side.push(match (v >= r - tol, v <= -r + tol) {
            (true, true) if c.wall_force[nearest] > 0.0 => -1,
            (true, _) => 1,
            (false, true) => -1,
            (false, false) => 0,
        });
    }
    Some((side, y))
}

fn finish(a: &Assembled, side: &[i8], y: Vec<f64>, reaction: Vec<f64>, iterations: usize) -> ContactSolution {
    let nodes = a.x.len();
    let wall_force = (0..nodes)
        .map(|i| if side[i] != 0 { reaction[2 * i] } else { 0.0 })
        .collect();
    ContactSolution {
        side_force: -reaction[0],
        tilt: y[1],
        x: a.x.clone(),
        y: (0..nodes).map(|i| y[2 * i]).collect(),
        slope: (0..nodes).map(|i| y[2 * i + 1]).collect(),
        wall_force,
        iterations,
    }
}

#[cfg(test)]
mod tests {
    use super::super::beam_column::max_deflection;
    use super::super::pendulum::{axial_gradient, constant_compression, lateral_load, variable_compression};
    use super::*;
    use std::f64::consts::PI;

    const INCH: f64 = 0.0254;

    /// (EI, w_b) of a steel 6.5 in x 2-13/16 in collar (207 GPa, 7850 kg/m3) in 1.2 sg mud.
    fn collar() -> (f64, f64) {
        let (d_o, d_i) = (6.5 * INCH, 2.8125 * INCH);
        let ei = 207e9 * PI * (d_o.powi(4) - d_i.powi(4)) / 64.0;
        let w_b = 7850.0 * 9.80665 * PI * (d_o * d_o - d_i * d_i) / 4.0 * (1.0 - 1200.0 / 7850.0);
        (ei, w_b)
    }

    /// A slick collar `length` long, 1 in of radial clearance, above a bit of zero length.
    fn slick(length: f64, inclination_deg: f64, wob: f64, element: f64) -> ContactBeam {
        let (ei, w_b) = collar();
        ContactBeam {
            pieces: vec![Piece {
                length,
                ei,
                weight: w_b,
                clearance: Some(INCH),
            }],
            inclination: inclination_deg.to_radians(),
            wob,
            top: TopEnd::OnWall,
            element,
        }
    }

    /// The first node above the bit on the wall, m.
    fn tangency(s: &ContactSolution) -> f64 {
        let i = s.wall_force.iter().position(|&f| f != 0.0).unwrap();
        s.x[i]
    }

    /// Reference: Lubinski's pendulum with constant compression (analytical::pendulum,
    /// docs/theory.md 9.2): at 90 deg the axial weight vanishes, so P = WOB. Slick 6.5 in collar
    /// in 8.5 in hole, 0 and 100 kN, 5 mm elements. Tolerance: side force and tilt 0.05%, the
    /// tangency point within one element (contact is only checked at the nodes).
    #[test]
    fn contact_beam_matches_the_constant_compression_pendulum() {
        let (ei, w_b) = collar();
        for wob in [0.0, 100e3] {
            let s = solve(&slick(40.0, 90.0, wob, 0.005)).unwrap();
            let r = constant_compression(ei, lateral_load(w_b, PI / 2.0), INCH, wob).unwrap();
            println!(
                "WOB {wob} ({} iterations): F {} vs {}, tilt {} vs {}, L {} vs {}",
                s.iterations,
                s.side_force,
                r.side_force,
                s.tilt,
                r.tilt,
                tangency(&s),
                r.tangency_length
            );
            assert!((s.side_force / r.side_force - 1.0).abs() < 5e-4);
            assert!((s.tilt / r.tilt - 1.0).abs() < 5e-4);
            assert!((tangency(&s) - r.tangency_length).abs() < 0.005 + 1e-9);
            // on the wall from the tangency point up: no wall force below it
            assert!(s.y.iter().all(|y| (-INCH - 1e-12..=INCH + 1e-12).contains(y)));
        }
    }

    /// Reference: the pendulum with the compression falling with the axial weight,
    /// P(x) = WOB - w_b cos I x (analytical::pendulum::variable_compression, RK4 shooting),
    /// 30 and 60 deg, 100 kN. Tolerance 0.05% on side force and tilt.
    #[test]
    fn contact_beam_matches_the_variable_compression_pendulum() {
        let (ei, w_b) = collar();
        for inc in [30.0f64, 60.0] {
            let s = solve(&slick(60.0, inc, 100e3, 0.005)).unwrap();
            let i = inc.to_radians();
            let r = variable_compression(ei, lateral_load(w_b, i), axial_gradient(w_b, i), 100e3, INCH).unwrap();
            println!(
                "{inc} deg: F {} vs {}, tilt {} vs {}",
                s.side_force, r.side_force, s.tilt, r.tilt
            );
            assert!((s.side_force / r.side_force - 1.0).abs() < 5e-4);
            assert!((s.tilt / r.tilt - 1.0).abs() < 5e-4);
        }
    }

    /// Reference: the simply supported beam-column (analytical::beam_column, Timoshenko & Gere
    /// 1961; docs/theory.md 10.3 example: 6.5 in collar, 9 m, 388.1 N/m, 100 kN): no contact,
    /// horizontal (P constant). Tolerance 1e-5 relative on the mid-span deflection (0.1 m
    /// elements; the consistent geometric stiffness converges as h^2).
    #[test]
    fn contact_beam_matches_the_simply_supported_beam_column() {
        let (ei, _) = collar();
        let problem = ContactBeam {
            pieces: vec![Piece {
                length: 9.0,
                ei,
                weight: 388.1,
                clearance: None,
            }],
            inclination: PI / 2.0,
            wob: 100e3,
            top: TopEnd::Pinned,
            element: 0.1,
        };
        let s = solve(&problem).unwrap();
        let mid = s.y[s.y.len() / 2];
        let r = max_deflection(ei, 9.0, 388.1, 100e3).unwrap();
        println!("mid-span {mid} vs {r}");
        assert!((mid / r - 1.0).abs() < 1e-5);
    }

    /// Reference: a full-gauge blade (zero clearance along its length) clamps the string. With
    /// no compression the bit to the blade's lower end `a` is a propped cantilever: the pinned
    /// end carries `3qa/8` (the support holds the beam up, so the bit pushes the rock toward
    /// the low side, side force `+3qa/8`) and turns by `q a^3/(48 EI)` toward the high side
    /// (Timoshenko & Gere 1961; any strength-of-materials table). The discrete contacts (every
    /// node along the blade) converge to the clamp as the element shrinks, linearly (a chain
    /// of pins `h` apart restrains the rotation with a stiffness of order `EI/h`). Tolerance:
    /// 0.1% on the force and 0.3% on the tilt at 2.5 mm elements, both errors at least 1.8
    /// times smaller at each halving.
    #[test]
    fn contact_beam_full_gauge_blade_is_a_clamp() {
        let (ei, w_b) = collar();
        let (a, blade) = (1.2, 0.4);
        let piece = |length, clearance| Piece {
            length,
            ei,
            weight: w_b,
            clearance,
        };
        let (force, tilt) = (3.0 * w_b * a / 8.0, w_b * a.powi(3) / (48.0 * ei));
        let (mut last_f, mut last_t) = (f64::INFINITY, f64::INFINITY);
        for element in [0.02, 0.01, 0.005, 0.0025] {
            let problem = ContactBeam {
                pieces: vec![piece(a, None), piece(blade, Some(0.0)), piece(20.0, Some(INCH))],
                inclination: PI / 2.0,
                wob: 0.0,
                top: TopEnd::OnWall,
                element,
            };
            let s = solve(&problem).unwrap();
            let (e_f, e_t) = (s.side_force / force - 1.0, s.tilt / tilt - 1.0);
            println!(
                "clamp, {element} m elements ({} iterations): side force {:+.4}%, tilt {:+.4}%",
                s.iterations,
                100.0 * e_f,
                100.0 * e_t
            );
            assert!(e_f.abs() < last_f / 1.8 && e_t.abs() < last_t / 1.8, "{e_f} {e_t}");
            (last_f, last_t) = (e_f.abs(), e_t.abs());
        }
        assert!(last_f < 1e-3 && last_t < 3e-3, "{last_f} {last_t}");
    }

    /// The reference refuses a free span beyond buckling instead of dividing by a zero pivot:
    /// a 30 m simply supported column under twice its Euler load.
    #[test]
    fn contact_beam_reports_buckling() {
        let (ei, w_b) = collar();
        let problem = ContactBeam {
            pieces: vec![Piece {
                length: 30.0,
                ei,
                weight: w_b,
                clearance: None,
            }],
            inclination: PI / 2.0,
            wob: 2.0 * PI * PI * ei / 900.0,
            top: TopEnd::Pinned,
            element: 0.5,
        };
        assert!(matches!(solve(&problem), Err(AnalyticalError::Buckled(_))));
    }
}
