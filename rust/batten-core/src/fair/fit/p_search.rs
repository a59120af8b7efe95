//! The search for Dierckx's smoothing parameter p with `F(p) = S` (fpcurf part 2): bracketing
//! steps and rational interpolation (`fprati`).

use glam::DVec3;

use super::system::System;
use super::{Spline, ZeroCurvature, REL_ACC};

/// Dierckx's maximum number of iterations for p (curfit's `maxit = 20`).
const MAX_P_ITER: usize = 20;
/// Step factors of fpcurf when the bracket on p is not yet found (`con1`, `con4`, `con9`).
const CON1: f64 = 0.1;
const CON4: f64 = 0.04;
const CON9: f64 = 0.9;

/// The smoothing spline of `system` with `F(p) = S` under the end conditions `cons` (fpcurf
/// part 2): p by Dierckx's rational interpolation (`fprati`) between `F(0) = fp0` and the
/// least-squares spline `(coefs, F(∞))`, starting from `p_start` or fpcurf's first guess.
/// Returns the feasible result (`E ≤ S` within tolerance) with the smallest p found, the
/// least-squares spline if no other is.
pub(super) fn find_p(
    system: &System,
    s: f64,
    fp0: f64,
    (ls_coefs, fp_inf): (Vec<DVec3>, f64),
    p_start: Option<f64>,
    cons: &[ZeroCurvature],
) -> Option<Spline> {
    let acc = REL_ACC * s;
    let eval = |p: f64| -> Option<(Vec<DVec3>, f64)> {
        let c = system.smoothing(p, cons)?;
        let fp = system.residuals2(&c).iter().sum();
        Some((c, fp))
    };
    // Best feasible result (E ≤ S) with the smallest p, starting from the LS spline.
    let mut best = (f64::INFINITY, ls_coefs, fp_inf);
    let (mut p1, mut f1) = (0.0, fp0 - s);
    let (mut p3, mut f3) = (-1.0, fp_inf - s);
    let rn = system.ls.unknowns().max(1) as f64;
    let diag = system.ls.diagonal_sum();
    let mut p = match p_start {
        Some(p) if p.is_finite() && p > 0.0 => p,
        _ if diag > 0.0 => rn / diag,
        _ => 1.0,
    };
    let (mut ich1, mut ich3) = (false, false);
    for _ in 0..MAX_P_ITER {
        let Some((c, fp)) = eval(p) else { break };
        let fpms = fp - s;
        if fpms <= acc && p < best.0 {
            best = (p, c, fp);
        }
        if fpms.abs() < acc {
            break;
        }
        let (p2, f2) = (p, fpms);
        if !ich3 {
            if f2 - f3 <= acc {
                // Initial p too large.
                p3 = p2;
                f3 = f2;
                p *= CON4;
                if p <= p1 {
                    p = p1 * CON9 + p2 * CON1;
                }
                continue;
            }
            if f2 < 0.0 {
                ich3 = true;
            }
        }
        if !ich1 {
            if f1 - f2 <= acc {
                // Initial p too small.
                p1 = p2;
                f1 = f2;
                p /= CON4;
                if p3 >= 0.0 && p >= p3 {
                    p = p2 * CON1 + p3 * CON9;
                }
                continue;
            }
            if f2 > 0.0 {
                ich1 = true;
            }
        }
        if f2 >= f1 || f2 <= f3 {
            // Not monotone as theory says (fpcurf ier = 2): keep the best feasible result.
            break;
        }
        p = fprati(&mut p1, &mut f1, p2, f2, &mut p3, &mut f3);
    }
    let (p, coefs, fp) = best;
    Some(system.spline(coefs, p, fp, s))
}

/// Dierckx's `fprati`: the zero of the rational function `R(p) = (u·p + v)/(p + w)` through
/// `(p1, f1)`, `(p2, f2)`, `(p3, f3)` (`p3 < 0` meaning ∞), then narrowing the bracket so that
/// `f1 > 0 > f3`.
fn fprati(p1: &mut f64, f1: &mut f64, p2: f64, f2: f64, p3: &mut f64, f3: &mut f64) -> f64 {
    let p = if *p3 > 0.0 {
        let h1 = *f1 * (f2 - *f3);
        let h2 = f2 * (*f3 - *f1);
        let h3 = *f3 * (*f1 - f2);
        -(*p1 * p2 * h3 + p2 * *p3 * h1 + *p3 * *p1 * h2) / (*p1 * h1 + p2 * h2 + *p3 * h3)
    } else {
        (*p1 * (*f1 - *f3) * f2 - p2 * (f2 - *f3) * *f1) / ((*f1 - f2) * *f3)
    };
    if f2 < 0.0 {
        *p3 = p2;
        *f3 = f2;
    } else {
        *p1 = p2;
        *f1 = f2;
    }
    p
}
