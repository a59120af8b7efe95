//! The cubic Hermite basis, shared by the blends along sides and edges and the Gregory patch.

/// The cubic Hermite basis at `x ∈ [0, 1]`: the weights of the start value, start slope (per
/// unit `x`), end value and end slope.
#[inline]
pub(crate) fn hermite_basis(x: f64) -> [f64; 4] {
    let (x2, x3) = (x * x, x * x * x);
    [
        2.0 * x3 - 3.0 * x2 + 1.0,
        x3 - 2.0 * x2 + x,
        -2.0 * x3 + 3.0 * x2,
        x3 - x2,
    ]
}
