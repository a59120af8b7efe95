//! Roots of 1-D Bernstein polynomials on `[0, 1]` (the crossings of a cell's edges and columns
//! with a plane): sign changes on a fine sampling, each closed in by the Illinois variant of
//! regula falsi to full precision.

use super::bernstein::{eval1, N};

/// Samples per unit interval when looking for sign changes: several per possible root of a
/// degree-7 polynomial.
const ROOT_SAMPLES: usize = 32;
/// Iterations of the Illinois method (it converges superlinearly; 60 is a safe cap).
const ROOT_ITERATIONS: usize = 60;

/// The root of `f` in `[a, b]`, where `f(a)` and `f(b)` differ in sign (Illinois regula falsi:
/// the end kept twice in a row has its value halved, so both ends close in). When the
/// iterate can no longer move, the end with the smaller `|f|` is the root.
pub(crate) fn bracketed(
    f: impl Fn(f64) -> f64,
    mut a: f64,
    mut b: f64,
    mut fa: f64,
    mut fb: f64,
) -> f64 {
    let mut side = 0i8;
    for _ in 0..ROOT_ITERATIONS {
        if fa == 0.0 {
            return a;
        }
        if fb == 0.0 {
            return b;
        }
        let x = (a * fb - b * fa) / (fb - fa);
        let width = b - a;
        if !(x > a && x < b) || width <= 4.0 * f64::EPSILON * (a.abs() + b.abs()).max(1.0) {
            break;
        }
        let fx = f(x);
        if fx == 0.0 {
            return x;
        }
        if (fx < 0.0) == (fb < 0.0) {
            b = x;
            fb = fx;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        } else {
            a = x;
            fa = fx;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        }
    }
    // fa, fb may have been halved; compare the true values.
    if f(a).abs() <= f(b).abs() {
        a
    } else {
        b
    }
}

/// The roots in the open interval `(0, 1)` of the Bernstein polynomial `c` where it changes
/// sign, ascending (a root of even multiplicity, where the sign does not change, is not one).
pub(crate) fn sign_changes(c: &[f64; N], out: &mut Vec<f64>) {
    let lo = c.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = c.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if lo > 0.0 || hi < 0.0 {
        return;
    }
    let f = |s: f64| eval1(c, s);
    let mut a = 0.0;
    let mut fa = c[0];
    for k in 1..=ROOT_SAMPLES {
        let b = k as f64 / ROOT_SAMPLES as f64;
        let fb = if k == ROOT_SAMPLES { c[N - 1] } else { f(b) };
        if (fa < 0.0) != (fb < 0.0) && fa != 0.0 && fb != 0.0 {
            let r = bracketed(f, a, b, fa, fb);
            if r > 0.0 && r < 1.0 {
                out.push(r);
            }
        }
        a = b;
        fa = fb;
    }
}
