//! Numbers, names and dates as the CAD exchange formats write them.

/// When a file was made: year, month, day, hour, minute, second (UTC).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Timestamp {
    /// Year (four digits).
    pub year: u16,
    /// Month, 1–12.
    pub month: u8,
    /// Day of the month, 1–31.
    pub day: u8,
    /// Hour, 0–23.
    pub hour: u8,
    /// Minute, 0–59.
    pub minute: u8,
    /// Second, 0–59.
    pub second: u8,
}

/// What a CAD file says about itself.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CadHeader {
    /// The model's name (the hull collection).
    pub name: String,
    /// The file's own name (without folders).
    pub file_name: String,
    /// Who made it (may be empty).
    pub author: String,
    /// When it was made.
    pub timestamp: Timestamp,
}

/// The name of the program writing the files, with its version.
pub(crate) fn system() -> String {
    format!("batten {}", env!("CARGO_PKG_VERSION"))
}

/// A real number with a decimal point and an exponent, the shortest that reads back as the
/// same f64 (`1.0E0`, `-2.5E-3`): both IGES and STEP (ISO 10303-21) require the point.
pub(crate) fn real(x: f64) -> String {
    let s = format!("{x:E}");
    if s.contains('.') {
        s
    } else {
        s.replacen('E', ".0E", 1)
    }
}

/// `text` in printable ASCII (anything else becomes `_`), as both formats' strings must be.
pub(crate) fn ascii(text: &str) -> String {
    text.chars()
        .map(|c| if (' '..='~').contains(&c) { c } else { '_' })
        .collect()
}

/// The distinct knots of a knot vector and their multiplicities.
pub(crate) fn knot_multiplicities(knots: &[f64]) -> (Vec<f64>, Vec<usize>) {
    let mut values: Vec<f64> = Vec::new();
    let mut mults: Vec<usize> = Vec::new();
    for &k in knots {
        if values.last() == Some(&k) {
            *mults.last_mut().expect("a multiplicity per value") += 1;
        } else {
            values.push(k);
            mults.push(1);
        }
    }
    (values, mults)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_have_a_point_and_read_back() {
        for x in [0.0, 1.0, -2.5e-3, 1.0 / 3.0, 123456.789, -0.0, 1e-300] {
            let s = real(x);
            assert!(s.contains('.') && s.contains('E'), "{s}");
            assert_eq!(s.parse::<f64>().expect("parses"), x, "{s} reads back");
        }
    }

    #[test]
    fn knots_come_with_their_multiplicities() {
        let (v, m) = knot_multiplicities(&[0.0, 0.0, 0.5, 1.0, 1.0, 1.0]);
        assert_eq!(
            (v, m),
            (vec![0.0, 0.5, 1.0], vec![2, 1, 3]),
            "runs of knots"
        );
    }
}
