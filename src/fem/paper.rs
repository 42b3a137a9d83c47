//! The seed paper's contact solution scheme (`[solver] method = "paper"`): modified Newton
//! iteration with gap-element springs in the stiffness matrix `K1`, contact-state checks per
//! Table 1 and the approximate-gradient update of the gap "additional forces" P (eq. 15).
//! physics.md 4.1-4.5; the reading of the paper is an **interpretation** (the paper is terse).
//!
//! # How this implementation reads the paper
//! - Gap element: each gap node has a radial spring `k_g` (the paper's `[A]`) and an
//!   additional force `P = p n` along its outward contact normal `n`. The wall force on the
//!   string is `k_g`-spring plus P, i.e. a reaction `R = k_g s - p` (s: radial distance from the
//!   hole axis). It is stored as the model's augmented-Lagrangian multiplier
//!   `lambda = k_g EO - p`, so that `R = lambda + k_g (s - EO)` and `Model::evaluate` computes
//!   it (closed status); friction `T = f R`, `m = (D/2) T` is recomputed from this R at every
//!   evaluation (Table 1), i.e. it is part of the right-hand side like P.
//! - Eq. 15, `P2 = P1 + alpha (dP1/dS1) dS2`: `dS2 = EO - s` is the radial correction still
//!   needed, `dP1` the previous increment of p and `dS1` the radial move of the node that
//!   followed it, so `dP1/dS1` is a secant estimate of the gap's radial stiffness and (15) a
//!   damped diagonal secant update. It is applied to every closed gap after each full modified
//!   Newton step (interleaved with the structural iteration; the paper's K1 solves are exact
//!   because its model is linear). Zero-clearance gaps (full-gauge stabilizers) get the vector
//!   form with target offset 0.
//! - Table 1: an open gap whose penetration exceeds the tolerance band closes (with `lambda =
//!   0`, i.e. the spring anchored at the wall); a closed gap whose reaction is negative opens.
//!   Converged when no state changes, every closed gap is within the band, no open gap
//!   penetrates beyond it and the residual is below its tolerance.
//! - The starting contact state is the soft-string one (`soft_string_start`).
//!
//! # Safeguards beyond the paper (needed to converge; each one found by failing cases)
//! - `k_g` = [`GAP_SPRING_FACTOR`] x the string's own lateral stiffness at the node (diagonal
//!   of the structural stiffness at the start), at least the model's penalty stiffness.
//! - Springs only at closed gaps (radial, `k_g n n^T`): the paper puts one in K1 for every gap
//!   and cancels it with `P = k_g x lateral displacement` at open gaps, which makes the free
//!   spans of a modified Newton iteration crawl (rate ~ `k_g` over the span's stiffness).
//!   K1 is therefore refactored whenever a contact state changes and refreshed (co-rotational
//!   tangent with the current axial forces) every [`REFRESH_EVERY`] steps.
//! - The secant is clamped to `[k_g, min(K1 radial diagonal, k_g/alpha)]`: in a line contact
//!   the uniform radial mode has stiffness ~`k_g`, and a larger secant overshoots it, which
//!   opens and closes gaps; the first secant, and the fallback when `|dS1|` is below
//!   [`SECANT_MIN_STEP`] of the band, is `k_g` itself (the paper suggests K1's diagonal, which
//!   oscillates). With this clamp the secant changes the update by at most `1/alpha`.
//! - `lambda >= 0`: P never moves the spring's anchor beyond the wall (without this, gaps that
//!   should open are pulled outward by ever larger P and the iteration blew up).
//! - Contacts are checked and P updated only after full (uncapped) steps; steps are capped to
//!   [`MAX_LATERAL_STEP`] of the clearance laterally and `MAX_BENDING_ROTATION_STEP` in
//!   bending rotation.
//! - A gap that changed state [`MAX_FLIPS`] times is frozen to the unilateral law
//!   `R = max(0, lambda + k_g (s - EO))`, and K1 is refreshed whenever such a gap switches
//!   (a stale K1 there made the iteration diverge).
//! - K1 is assembled without friction (lagged friction; with it K1 is unsymmetric and badly
//!   conditioned), with LU and the consistent co-rotational tangent when the string carries
//!   torque; a moving string with friction is solved in two load steps, friction and bit torque
//!   off, then on ([`FRICTION_STAGES`]).
//!
//! # Status (honest)
//! Converges on frictionless problems: the Lubinski pendulum (agreement with the default scheme
//! ~1e-5 at a gap tolerance of 1e-6) and a curved 3D well with a stabilized BHA. It does **not**
//! converge yet with rotary friction (the friction stage diverges: tangential friction moves
//! closed gaps around the wall faster than the radial spring tracks), nor on any example well
//! (docs/performance.md); such solves end flagged `converged == false`. Use `method = "newton"`.

use super::band_lu::{BandLu, GeneralBand};
use super::model::{Model, State, HALF_BANDWIDTH};
use super::solve::{
    constrain_and_factor, load_scale, residual_norm, soft_string_start, Linear, Solution, SolveControls, SolveError,
    SolveStats, MAX_BENDING_ROTATION_STEP,
};
use crate::contact::gap::ZERO_CLEARANCE_M;
use std::time::Instant;

/// Gap spring `k_g` of a node as a multiple of the string's own lateral stiffness there (the
/// diagonal of the structural stiffness at the start, at least the model's penalty stiffness).
pub const GAP_SPRING_FACTOR: f64 = 1.0;

/// Iterations between refreshes of the structural part of `K1` (co-rotational tangent with
/// the current axial forces); `K1` is also refactored whenever a contact state changes.
pub const REFRESH_EVERY: usize = 5;

/// State changes after which a gap is frozen to the unilateral law (chattering).
pub const MAX_FLIPS: usize = 3;

/// Nodes whose state changed within this many iterations of the end are reported as chattering
/// when the solve does not converge.
pub const CHATTER_WINDOW: usize = 10;

/// Largest lateral move of a gap node per iteration, fraction of its clearance (physics.md 4.5).
pub const MAX_LATERAL_STEP: f64 = 0.5;

/// A secant `dP/dS` is only trusted when the radial move `dS` exceeds this fraction of the
/// gap tolerance band; below it the first-secant (diagonal) estimate is used.
pub const SECANT_MIN_STEP: f64 = 0.1;

/// Closed gaps open when their reaction is below minus this fraction of the residual
/// tolerance (times the load scale).
pub const RELEASE_FRACTION: f64 = 0.1;

/// Capped (partial) modified Newton steps allowed before the contact states are checked anyway:
/// normally they are checked after every full step and at equilibrium.
pub const INNER_STEPS: usize = 20;

/// Check contacts and update P after every full step (true) or only at equilibrium (false).
pub const INTERLEAVED: bool = false;

/// Friction (and bit torque) fractions of the load steps of a moving string with friction.
pub const FRICTION_STAGES: [f64; 2] = [0.0, 1.0];

/// Kind of contact node.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    /// No gap element.
    None,
    /// Gap with clearance: open/closed states of Table 1.
    Gap,
    /// Zero clearance (full-gauge stabilizer): always closed, radial displacement must vanish.
    Pin,
}

/// Solve the static problem with the paper's scheme; see the module documentation.
/// Returns a flagged (`converged == false`) solution when the iteration limit is reached.
pub fn solve_paper(model: &Model, ctl: &SolveControls) -> Result<Solution, SolveError> {
    let t0 = Instant::now();
    let nn = model.nodes();
    let n = model.dofs();
    let constrained = model.constrained_dofs();
    let bit_ax = model.dof(0, 0);
    let top_ax = model.dof(nn - 1, 0);
    let bordered = model.loads.hook_load_n.is_none();
    let scale = load_scale(model);
    let alpha = ctl.alpha;
    // a closed gap opens when its reaction is below -release (Table 1: R >= 0); dropping a
    // reaction smaller than that keeps the residual within its tolerance
    let release = RELEASE_FRACTION * ctl.residual_tolerance * scale;
    let kind: Vec<Kind> = (0..nn)
        .map(|i| {
            if !model.mesh.nodes[i].has_gap {
                Kind::None
            } else if model.clearance(i, model.md_ref[i]) <= ZERO_CLEARANCE_M {
                Kind::Pin
            } else {
                Kind::Gap
            }
        })
        .collect();
    let mut lin = Linear::for_model(model);

    // 1. gap springs: a multiple of the string's lateral stiffness at each gap node
    let mut work = model.clone();
    {
        let mut bare = model.clone();
        bare.k_n.iter_mut().for_each(|k| *k = 0.0);
        let mut s0 = model.initial_state();
        s0.closed = Some(vec![false; nn]);
        bare.evaluate(&mut s0, Some(lin.sink()));
        for (i, k) in kind.iter().enumerate() {
            if *k != Kind::None {
                let s_ii =
                    0.5 * (lin.get(model.dof(i, 1), model.dof(i, 1)) + lin.get(model.dof(i, 2), model.dof(i, 2)));
                work.k_n[i] = GAP_SPRING_FACTOR * s_ii.max(model.k_n[i]);
            }
        }
    }
    let k_g = work.k_n.clone();
    // K1 is assembled without friction: the paper updates the friction forces with the other
    // "additional forces" (lagged), and their dependence on the gap springs would make K1
    // unsymmetric and badly conditioned
    let mut frictionless = work.clone();
    frictionless.friction.iter_mut().for_each(|f| *f = 0.0);
    // under torque the co-rotational tangent needs its frame-variation terms (unsymmetric: LU)
    let torque = work.needs_unsymmetric() || model.loads.bit_torque_nm != 0.0;
    let mut lin = if torque {
        Linear::General(GeneralBand::zeros(n, HALF_BANDWIDTH), BandLu::new(n, HALF_BANDWIDTH))
    } else {
        Linear::for_model(&frictionless)
    };

    // 2. assumed contact state: soft-string contact sides
    let mut state = model.initial_state();
    soft_string_start(model, &mut state, false);
    let mut closed: Vec<bool> = (0..nn).map(|i| kind[i] == Kind::Gap && state.lambda[i] > 0.0).collect();
    let mut frozen = vec![false; nn];
    let mut frozen_active = vec![false; nn];
    for i in 0..nn {
        if kind[i] == Kind::Pin {
            state.lambda[i] = 0.0;
        }
        if kind[i] == Kind::Gap && !closed[i] {
            state.lambda[i] = 0.0;
        }
    }
    state.closed = Some(closed.clone());
    state.free_law = Some(frozen.clone());
    state.exact_multipliers = false;

    let mut stats = SolveStats::default();
    let mut converged = false;
    let mut need_refresh;
    let mut since_refresh = 0usize;
    let mut kb: Vec<(usize, f64)> = Vec::new();
    let mut k1_radial = vec![0.0; nn];
    let mut flips = vec![0usize; nn];
    let mut last_change = vec![None::<usize>; nn];
    // eq. 15 history per gap: previous increment of P (N) and radial distance after it (m)
    let mut last_dp = vec![0.0f64; nn];
    let mut last_s = vec![f64::NAN; nn];
    let mut ev = work.evaluate(&mut state.clone(), None);
    let mut passes = 0usize;
    // modified Newton steps since the last contact check / P update
    let mut inner;
    let mut outer = 0usize;
    let mut last_full = false;
    // load stepping: a moving string with friction is first solved without friction and bit
    // torque, then with them (friction is lagged in K1, so it is added to a settled state)
    let stages: &[f64] = if torque { &FRICTION_STAGES } else { &[1.0] };
    for &frac in stages {
        work.friction = model.friction.iter().map(|f| f * frac).collect();
        work.loads.bit_torque_nm = model.loads.bit_torque_nm * frac;
        frictionless.loads.bit_torque_nm = work.loads.bit_torque_nm;
        frictionless.consistent_tangent = frac > 0.0 && torque;
        converged = false;
        need_refresh = true;
        inner = 0;
        tracing::debug!(frac, "paper scheme: friction stage");
        loop {
            // 3. residual of K1 d = F0 + P at the current state (K1 refreshed when due)
            if need_refresh {
                frictionless.evaluate(&mut state, Some(lin.sink()));
                ev = work.evaluate(&mut state, None);
                kb = (0..6)
                    .map(|c| model.dof(0, c))
                    .chain((0..6).map(|c| model.dof(1, c)))
                    .filter(|d| !constrained.contains(d))
                    .map(|d| (d, lin.get(bit_ax, d)))
                    .collect();
                for i in 0..nn {
                    if kind[i] != Kind::None {
                        // radial diagonal of K1 in the current contact direction (node basis)
                        let nrm = model.basis[i].transpose() * state.normal[i];
                        let mut kr = 0.0;
                        for a in 0..3 {
                            for b in 0..3 {
                                kr += nrm[a] * lin.get(model.dof(i, a), model.dof(i, b)) * nrm[b];
                            }
                        }
                        k1_radial[i] = kr.max(k_g[i]);
                    }
                }
                constrain_and_factor(model, &mut lin, &constrained)?;
                stats.factorizations += 1;
                need_refresh = false;
                since_refresh = 0;
            } else {
                ev = work.evaluate(&mut state, None);
            }
            let mut r = ev.residual.clone();
            for &d in &constrained {
                r[d] = 0.0;
            }
            let c = if bordered {
                ev.residual[bit_ax] + model.loads.wob_n
            } else {
                0.0
            };
            let rn = residual_norm(&r, scale).max(c.abs() / scale);
            passes += 1;
            if !rn.is_finite() {
                tracing::warn!("paper scheme: residual not finite; stopping");
                stats.residual_history.push(rn);
                break;
            }
            if stats.iterations >= ctl.max_iterations || passes > 3 * ctl.max_iterations + 10 {
                stats.residual_history.push(rn);
                break;
            }
            // frozen gaps follow the unilateral law: K1 is refreshed when one of them switches
            let mut switched = false;
            for i in 0..nn {
                if frozen[i] {
                    let on = ev.gaps[i].as_ref().is_some_and(|g| g.normal_force > 0.0);
                    switched |= on != frozen_active[i];
                    frozen_active[i] = on;
                }
            }
            if switched && !need_refresh {
                need_refresh = true;
                continue;
            }
            // 4. at equilibrium for the current P: contact-state checks (Table 1), then eq. 15
            let check = rn < ctl.residual_tolerance || inner >= INNER_STEPS || (last_full && inner > 0);
            if check {
                let mut in_band = true;
                let mut pen: f64 = 0.0;
                let mut to_open = Vec::new();
                let mut to_close = Vec::new();
                for i in 0..nn {
                    let Some(g) = &ev.gaps[i] else { continue };
                    let eo = ev.clearance[i].max(1e-3);
                    let tol = ctl.gap_tolerance * eo;
                    match kind[i] {
                        Kind::None => {}
                        Kind::Pin => {
                            let s = g.penetration + ev.clearance[i];
                            pen = pen.max(s / eo);
                            in_band &= s <= tol;
                        }
                        Kind::Gap => {
                            let e = g.penetration;
                            if frozen[i] {
                                // unilateral law: R = max(0, lambda + k_g (s - EO))
                                let err = if g.normal_force > 0.0 { e.abs() } else { e.max(0.0) };
                                pen = pen.max(err / eo);
                                in_band &= err <= tol;
                            } else if closed[i] {
                                pen = pen.max(e.abs() / eo);
                                in_band &= e.abs() <= tol;
                                if g.normal_force < -release {
                                    to_open.push(i);
                                }
                            } else {
                                pen = pen.max(e.max(0.0) / eo);
                                if e > tol {
                                    to_close.push(i);
                                }
                            }
                        }
                    }
                }
                stats.max_penetration = pen;
                tracing::debug!(
                    outer,
                    iteration = stats.iterations,
                    residual = rn,
                    penetration = pen,
                    opening = to_open.len(),
                    closing = to_close.len(),
                    hook_load = state.hook_load_n,
                    "paper contact check"
                );
                let changes = to_open.len() + to_close.len();
                if changes == 0 && in_band && rn < ctl.residual_tolerance {
                    converged = true;
                    stats.residual_history.push(rn);
                    break;
                }
                if changes > 0 {
                    for &i in to_open.iter().chain(&to_close) {
                        if let Some(g) = &ev.gaps[i] {
                            tracing::trace!(
                                node = i,
                                s_m = model.mesh.nodes[i].s_m,
                                reaction = g.normal_force,
                                penetration = g.penetration,
                                lambda = state.lambda[i],
                                closing = !closed[i],
                                "contact state change"
                            );
                        }
                        closed[i] = !closed[i];
                        state.lambda[i] = 0.0;
                        last_dp[i] = 0.0;
                        flips[i] += 1;
                        last_change[i] = Some(stats.iterations);
                        if flips[i] >= MAX_FLIPS {
                            frozen[i] = true;
                            frozen_active[i] = closed[i];
                        }
                    }
                    state.closed = Some(closed.clone());
                    state.free_law = Some(frozen.clone());
                    need_refresh = true;
                    inner = 0;
                    continue;
                }
                // eq. 15: P2 = P1 + alpha (dP1/dS1) dS2 for every closed gap
                let mut updated = false;
                for i in 0..nn {
                    let Some(g) = &ev.gaps[i] else { continue };
                    let eo = ev.clearance[i].max(1e-3);
                    let tol = ctl.gap_tolerance * eo;
                    match kind[i] {
                        Kind::None => {}
                        Kind::Pin => {
                            // vector form: drive the lateral offset to zero
                            let d = g.normal * (g.penetration + ev.clearance[i]);
                            if d.norm() > 1e-3 * tol {
                                state.lambda_vec[i] += d * (alpha * k_g[i]);
                                updated = true;
                            }
                        }
                        Kind::Gap if frozen[i] => {
                            let e = g.penetration;
                            if g.normal_force > 0.0 || e > 0.0 {
                                let new = (state.lambda[i] + alpha * k_g[i] * e).max(0.0);
                                updated |= new != state.lambda[i];
                                state.lambda[i] = new;
                            }
                        }
                        Kind::Gap if closed[i] => {
                            let s = g.penetration + ev.clearance[i];
                            let ds1 = s - last_s[i];
                            let k_max = k1_radial[i].min(k_g[i] / alpha);
                            let secant = if last_dp[i] != 0.0 && ds1.is_finite() && ds1.abs() > SECANT_MIN_STEP * tol {
                                (last_dp[i] / ds1).clamp(k_g[i], k_max)
                            } else {
                                k_g[i]
                            };
                            let ds2 = -g.penetration; // EO - s: radial correction still needed
                                                      // P = k_g EO - lambda along the outward normal (R = k_g s - P); P never
                                                      // moves the spring's anchor beyond the wall (lambda >= 0)
                            let dp = (alpha * secant * ds2).min(state.lambda[i]);
                            state.lambda[i] -= dp;
                            updated |= dp != 0.0;
                            last_dp[i] = dp;
                            last_s[i] = s;
                        }
                        Kind::Gap => {}
                    }
                }
                outer += 1;
                inner = 0;
                if updated {
                    continue;
                }
            }
            // 5. modified Newton step with the factored K1 (bordered with the hook-load equation)
            stats.iterations += 1;
            stats.residual_history.push(rn);
            inner += 1;
            let mut a: Vec<f64> = r.iter().map(|v| -v).collect();
            lin.solve(&mut a);
            let (du, dh) = if bordered {
                let mut b = vec![0.0; n];
                b[top_ax] = 1.0;
                lin.solve(&mut b);
                let kba: f64 = kb.iter().map(|&(d, v)| v * a[d]).sum();
                let kbb: f64 = kb.iter().map(|&(d, v)| v * b[d]).sum();
                let dh = if kbb.abs() > 1e-30 { (c + kba) / kbb } else { 0.0 };
                (a.iter().zip(&b).map(|(x, y)| x - dh * y).collect::<Vec<f64>>(), dh)
            } else {
                (a, 0.0)
            };
            let mut ratio: f64 = 0.0;
            for i in 0..nn {
                if kind[i] != Kind::None {
                    let lat = du[model.dof(i, 1)].hypot(du[model.dof(i, 2)]);
                    ratio = ratio.max(lat / (MAX_LATERAL_STEP * ev.clearance[i].max(2e-3)));
                }
                let rot = du[model.dof(i, 4)].hypot(du[model.dof(i, 5)]);
                ratio = ratio.max(rot / MAX_BENDING_ROTATION_STEP);
            }
            let beta = if ratio > 1.0 { 1.0 / ratio } else { 1.0 };
            last_full = beta >= 1.0;
            tracing::debug!(iteration = stats.iterations, residual = rn, beta, "paper step");
            state.hook_load_n += beta * dh;
            work.update(&mut state, &du, beta);
            since_refresh += 1;
            if since_refresh >= REFRESH_EVERY {
                need_refresh = true;
            }
        }
        if !converged {
            break;
        }
    }
    stats.chattering_nodes = (0..nn)
        .filter(|&i| frozen[i] || (!converged && last_change[i].is_some_and(|k| k + CHATTER_WINDOW > stats.iterations)))
        .collect();
    // final evaluation with the original model: closed gaps carry exactly their wall reaction
    let mut fin: State = state;
    let mut closed_final = vec![false; nn];
    for i in 0..nn {
        match (kind[i], &ev.gaps[i]) {
            (Kind::Gap, Some(g)) => {
                let on = (closed[i] || frozen[i]) && g.normal_force > 0.0;
                closed_final[i] = on;
                fin.lambda[i] = if on { g.normal_force } else { 0.0 };
            }
            (Kind::Pin, Some(_)) => {
                // same pin force with the model's penalty stiffness
                let md = work.path.nearest_md(&fin.x[i], fin.md[i]);
                let p = work.path.point_at(md);
                let d = fin.x[i] - p.position;
                let d = d - p.tangent * p.tangent.dot(&d);
                fin.lambda_vec[i] += d * (k_g[i] - model.k_n[i]);
            }
            _ => {}
        }
    }
    fin.closed = Some(closed_final);
    fin.free_law = None;
    fin.lcp_nodes = None;
    fin.implicit_friction = false;
    fin.exact_multipliers = true;
    let eval = model.evaluate(&mut fin, None);
    stats.attempts = 1;
    stats.seconds = t0.elapsed().as_secs_f64();
    Ok(Solution {
        state: fin,
        eval,
        converged,
        stats,
    })
}
