//! The section families of a network (Pla et al. 1998, §2 and §4: the planar sections a
//! designer reads): stations (planes x = const), waterlines (z = const) and buttocks
//! (y = const) among the network's own curves, grouped by plane and ordered along the family's
//! axis, so that each section has neighbours C[i−1], C[i+1] on either side.

use crate::curve::NurbsCurve;

/// A family of parallel plane sections.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SectionFamily {
    /// Transverse sections, planes x = const.
    Stations,
    /// Horizontal sections, planes z = const.
    Waterlines,
    /// Longitudinal sections, planes y = const.
    Buttocks,
}

impl SectionFamily {
    /// Every family, in the order a lines plan lists them.
    pub const ALL: [SectionFamily; 3] = [
        SectionFamily::Stations,
        SectionFamily::Waterlines,
        SectionFamily::Buttocks,
    ];

    /// The lowercase plural name used in Python (`"stations"`, `"waterlines"`, `"buttocks"`).
    pub fn name(self) -> &'static str {
        match self {
            SectionFamily::Stations => "stations",
            SectionFamily::Waterlines => "waterlines",
            SectionFamily::Buttocks => "buttocks",
        }
    }

    /// The family of a name (case-insensitive), `None` if there is none.
    pub fn from_name(name: &str) -> Option<SectionFamily> {
        let lower = name.to_ascii_lowercase();
        SectionFamily::ALL.into_iter().find(|f| f.name() == lower)
    }

    /// The coordinate axis normal to the family's planes (0 = x, 1 = y, 2 = z).
    pub fn axis(self) -> usize {
        match self {
            SectionFamily::Stations => 0,
            SectionFamily::Waterlines => 2,
            SectionFamily::Buttocks => 1,
        }
    }
}

/// The first of `families` whose plane holds every control point of `curve` within `within`
/// (m), with the plane's offset (the mean of the extreme coordinates along its axis).
pub(crate) fn plane_of(
    curve: &NurbsCurve,
    families: &[SectionFamily],
    within: f64,
) -> Option<(SectionFamily, f64)> {
    let points = curve.control_points();
    families.iter().find_map(|&family| {
        let a = family.axis();
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[a]), hi.max(p[a]))
            });
        (hi - lo <= within).then_some((family, 0.5 * (lo + hi)))
    })
}

/// The curves of one family in one plane (a plane may cut a hull in several pieces: a bulb and
/// the stem, a shaft boss and the counter).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Group {
    /// The plane's offset along the family's axis (m).
    pub offset: f64,
    /// Indices of the curves in the network.
    pub curves: Vec<usize>,
}

/// One family's sections, plane by plane in order of offset.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Family {
    /// Which family.
    pub family: SectionFamily,
    /// Its planes, in increasing offset.
    pub groups: Vec<Group>,
}

/// The families of `planes` (per curve, its family and offset, `None` for a curve that is no
/// movable section), each with its curves grouped by plane: offsets within `same` (m) are one
/// plane. Families with no curve are left out.
pub(crate) fn group_families(
    planes: &[Option<(SectionFamily, f64)>],
    families: &[SectionFamily],
    same: f64,
) -> Vec<Family> {
    families
        .iter()
        .filter_map(|&family| {
            let mut members: Vec<(f64, usize)> = planes
                .iter()
                .enumerate()
                .filter_map(|(i, p)| match p {
                    Some((f, offset)) if *f == family => Some((*offset, i)),
                    _ => None,
                })
                .collect();
            members.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let mut groups: Vec<Group> = Vec::new();
            for (offset, i) in members {
                match groups.last_mut() {
                    Some(g) if offset - g.offset <= same => g.curves.push(i),
                    _ => groups.push(Group {
                        offset,
                        curves: vec![i],
                    }),
                }
            }
            (!groups.is_empty()).then_some(Family { family, groups })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curves_are_grouped_by_plane_in_order() {
        let s = SectionFamily::Stations;
        let w = SectionFamily::Waterlines;
        let planes = [
            Some((s, 2.0)),
            Some((w, 1.0)),
            None,
            Some((s, -1.0)),
            Some((s, 2.0)),
        ];
        let fams = group_families(&planes, &[s, w, SectionFamily::Buttocks], 1e-6);
        assert_eq!(fams.len(), 2, "no buttocks: {fams:?}");
        let offsets: Vec<f64> = fams[0].groups.iter().map(|g| g.offset).collect();
        assert_eq!(offsets, vec![-1.0, 2.0], "stations in order");
        assert_eq!(
            fams[0].groups[1].curves,
            vec![0, 4],
            "two pieces in one plane"
        );
        assert_eq!(fams[1].groups[0].curves, vec![1]);
    }

    #[test]
    fn names_round_trip() {
        for f in SectionFamily::ALL {
            assert_eq!(SectionFamily::from_name(&f.name().to_uppercase()), Some(f));
        }
        assert_eq!(SectionFamily::from_name("diagonals"), None);
    }
}
