//! B-rep validation: one invariant per file, each failure a small error struct carrying the
//! evidence (the fornjot `validation/checks/` practice; H-rep paper §3.1 "topological
//! integrity and validity").

mod edge_faces;
mod euler;
mod next_prev;
mod twins;

use thiserror::Error;

pub use edge_faces::EdgeFacesError;
pub use euler::EulerPoincareError;
pub use next_prev::NextPrevError;
pub use twins::TwinError;

use super::brep::Brep;

/// A failed B-rep invariant (H-rep paper §3.1): which check and its evidence.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ValidationError {
    /// See [`TwinError`].
    #[error(transparent)]
    Twin(#[from] TwinError),
    /// See [`NextPrevError`].
    #[error(transparent)]
    NextPrev(#[from] NextPrevError),
    /// See [`EdgeFacesError`].
    #[error(transparent)]
    EdgeFaces(#[from] EdgeFacesError),
    /// See [`EulerPoincareError`].
    #[error(transparent)]
    EulerPoincare(#[from] EulerPoincareError),
}

impl Brep {
    /// Run every B-rep check (twins, next/prev, edge use by faces, Euler–Poincaré per shell)
    /// and return all failures; an empty list means the B-rep is valid (H-rep paper §3.1).
    pub fn validate(&self) -> Vec<ValidationError> {
        let mut out: Vec<ValidationError> = Vec::new();
        out.extend(twins::check(self).into_iter().map(Into::into));
        out.extend(next_prev::check(self).into_iter().map(Into::into));
        out.extend(edge_faces::check(self).into_iter().map(Into::into));
        out.extend(euler::check(self).into_iter().map(Into::into));
        out
    }
}

#[cfg(test)]
pub(crate) mod fixture {
    //! A small valid B-rep for the check tests: a 2 × 2 grid of straight lines.
    use glam::DVec3;

    use crate::curve::NurbsCurve;
    use crate::network::{Network, NetworkCurve, Role};
    use crate::tolerance::Tolerance;
    use crate::topo::brep::Brep;
    use crate::topo::topology::Topology;

    fn line(name: &str, a: [f64; 3], b: [f64; 3]) -> NetworkCurve {
        let curve = NurbsCurve::try_new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![DVec3::from_array(a), DVec3::from_array(b)],
            None,
        )
        .expect("a valid line");
        NetworkCurve {
            name: name.to_owned(),
            role: Role::Free,
            curve,
        }
    }

    /// Three horizontal and three vertical lines: 9 nodes, 12 edges, 4 faces, 1 boundary.
    pub(crate) fn grid() -> Brep {
        let mut curves = Vec::new();
        for i in 0..3 {
            let c = i as f64;
            curves.push(line(&format!("h{i}"), [0.0, c, 0.0], [2.0, c, 0.0]));
            curves.push(line(&format!("v{i}"), [c, 0.0, 0.0], [c, 2.0, 0.0]));
        }
        let network = Network::try_new("grid", curves).expect("unique names");
        let topo = Topology::build(&network, Tolerance::DEFAULT).expect("builds");
        assert_eq!(topo.brep.faces.len(), 4, "fixture has four faces");
        topo.brep
    }
}
