//! The live rebuild: a hull kept with everything its build computed, rebuilt after an edit by
//! computing again only the edges, ribbons, patches and patch meshes that the moved curves
//! reach, and rewriting only their vertices in the welded mesh it keeps (where the weld is
//! shown to be what welding afresh gives, `build::reassemble`), with the same result as a full
//! build bit for bit. The report's quality sampling
//! (gaps, normal jumps, holes, folds) is the slow part of a build; a rebuild leaves it for
//! [`LiveHull::settle`], which the caller runs once the edits pause.

use std::sync::Arc;

use rayon::prelude::*;

use super::build::{assemble_welded, built_in_full, into_surface, measure, reassemble, Stages};
use super::patched::PatchedFace;
use super::{HullOptions, HullSurface};
use crate::error::Error;
use crate::network::Network;
use crate::patch::Weld;

/// What the last build or rebuild of a [`LiveHull`] did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Rebuild {
    /// Everything was built from scratch: the first build, or `reason` why a rebuild could not
    /// keep anything (the network's connectivity changed).
    Full {
        /// Why the rebuild was full (`None` for the first build).
        reason: Option<String>,
    },
    /// Only the faces reached by the moved curves were built again.
    Incremental {
        /// How many faces were patched and meshed again.
        faces: usize,
        /// How many faces the hull has.
        of: usize,
    },
}

/// A hull surface that rebuilds incrementally (see the module documentation).
#[derive(Clone, Debug)]
pub struct LiveHull {
    network: Network,
    options: HullOptions,
    stages: Stages,
    surface: Arc<HullSurface>,
    measured: bool,
    last: Rebuild,
    /// The topology faces the last rebuild patched again (`None` after a full build).
    rebuilt: Option<Vec<usize>>,
    /// How the surface's mesh was welded from its faces' meshes: a rebuild rewrites only the
    /// vertices of the faces it patched again.
    weld: Weld,
}

impl LiveHull {
    /// Build `network` in full, report included (as [`build_hull`](super::build_hull), whose
    /// errors it returns).
    pub fn new(network: &Network, options: &HullOptions) -> Result<LiveHull, Error> {
        let (stages, surface, weld) = built_in_full(network, options)?;
        Ok(LiveHull {
            network: network.clone(),
            options: *options,
            surface: Arc::new(surface),
            stages,
            measured: true,
            last: Rebuild::Full { reason: None },
            rebuilt: None,
            weld,
        })
    }

    /// Rebuild for `network`, the same hull with curves moved: incrementally when its
    /// connectivity is unchanged, else in full. The mesh and patches are then exactly those of
    /// [`build_hull`](super::build_hull) on `network`; the report is not measured again
    /// ([`LiveHull::is_measured`] turns false) until [`LiveHull::settle`]. On an error nothing
    /// changes: the hull keeps its previous surface.
    pub fn rebuild(&mut self, network: &Network) -> Result<&Rebuild, Error> {
        let (stages, last) = match self.stages.updated(&self.network, network, &self.options)? {
            Ok((stages, faces)) => {
                let of = stages.topology.faces.len();
                (stages, Rebuild::Incremental { faces, of })
            }
            Err(reason) => (
                Stages::full(network, &self.options)?,
                Rebuild::Full {
                    reason: Some(reason),
                },
            ),
        };
        let incremental = matches!(last, Rebuild::Incremental { .. });
        // Rewritten in place where few faces were patched again: `reassemble` changes the weld
        // only when it gives the surface. Where most were (a change of breadth moves every
        // curve off the centreplane), checking the weld of each of them costs more than
        // welding afresh, which gives the same mesh.
        let few = matches!(last, Rebuild::Incremental { faces, of } if 2 * faces <= of);
        let kept = few
            .then(|| reassemble(&stages, &self.stages, &self.surface, &mut self.weld))
            .flatten();
        let surface = match kept {
            Some(kept) => kept,
            None => {
                let (patched, mesh, outward, weld) = assemble_welded(network, &stages)?;
                self.weld = weld;
                into_surface(
                    patched,
                    mesh,
                    outward,
                    self.surface.report.clone(),
                    &stages,
                    self.options.resolution,
                )
            }
        };
        // A kept face shares its outcome with the stages it was kept from.
        let rebuilt = incremental.then(|| {
            (0..stages.faces.len())
                .filter(|&f| !Arc::ptr_eq(&stages.faces[f], &self.stages.faces[f]))
                .collect()
        });
        self.surface = Arc::new(surface);
        let old = std::mem::replace(&mut self.stages, stages);
        // The faces' patches and meshes are most of what is freed (30,000 allocations for
        // KCS): freed on both threads.
        old.faces.into_par_iter().for_each(drop);
        self.network = network.clone();
        self.measured = false;
        self.last = last;
        self.rebuilt = rebuilt;
        Ok(&self.last)
    }

    /// Measure the report of the current surface if a rebuild left it unmeasured (gaps,
    /// normal jumps, creases, holes, folds, warnings): the report of a full build of the same
    /// network. On an error (figures that overflow) the report stays unmeasured.
    pub fn settle(&mut self) -> Result<&HullSurface, Error> {
        if !self.measured {
            let surface = &self.surface;
            let index_of: std::collections::HashMap<usize, u32> = surface
                .patch_faces
                .iter()
                .enumerate()
                .map(|(i, &f)| (f, i as u32))
                .collect();
            let patched: Vec<PatchedFace> = surface
                .patch_faces
                .iter()
                .zip(&surface.patches)
                .zip(&surface.layouts)
                .map(|((&face, patch), layout)| PatchedFace {
                    face,
                    patch: patch.clone(),
                    layout: layout.clone(),
                })
                .collect();
            let mut mesh = surface.mesh.clone();
            for p in &mut mesh.face_patch {
                *p = index_of[&(*p as usize)];
            }
            let report = measure(&self.network, &self.options, &self.stages, &patched, &mesh)?;
            Arc::make_mut(&mut self.surface).report = report;
            self.measured = true;
        }
        Ok(&self.surface)
    }

    /// The current surface. Its mesh and patches are always current; its report is the last
    /// measured one ([`LiveHull::is_measured`] says whether that is of the current surface).
    pub fn surface(&self) -> &HullSurface {
        &self.surface
    }

    /// The current surface, shared: what [`LiveHull::surface`] gives, without a copy (a later
    /// rebuild replaces the hull's surface and leaves this one as it is).
    pub fn shared_surface(&self) -> Arc<HullSurface> {
        Arc::clone(&self.surface)
    }

    /// True when the surface's report was measured on the current surface.
    pub fn is_measured(&self) -> bool {
        self.measured
    }

    /// What the last build or rebuild did.
    pub fn last_rebuild(&self) -> &Rebuild {
        &self.last
    }

    /// The topology faces (`HullSurface::patch_faces` values) the last rebuild patched again,
    /// in order, or `None` when it built everything: the other faces' patches are those of the
    /// surface before, bit for bit, so whatever was made of them (cells for hydrostatics,
    /// [`HullSurface::hydro_model_after`]) can be kept.
    pub fn rebuilt_faces(&self) -> Option<&[usize]> {
        self.rebuilt.as_deref()
    }

    /// The network the current surface was built from.
    pub fn network(&self) -> &Network {
        &self.network
    }

    /// The options the hull is built with.
    pub fn options(&self) -> &HullOptions {
        &self.options
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::network::NetworkCurve;
    use glam::DVec3;

    fn frigate() -> Network {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../examples/frigate_network.json"
        );
        Network::from_json(&std::fs::read_to_string(path).expect("example")).expect("network")
    }

    /// `net` with control point `index` of its curve `curve` moved by `by`.
    fn moved(net: &Network, curve: usize, index: usize, by: DVec3) -> Network {
        let mut curves: Vec<NetworkCurve> = net.curves().to_vec();
        let c = &curves[curve].curve;
        let mut points = c.control_points();
        points[index] += by;
        curves[curve].curve = c.with_control_points(points).expect("curve");
        Network::try_new(net.name.clone(), curves).expect("network")
    }

    #[test]
    fn a_small_move_rewrites_the_kept_mesh_to_exactly_a_fresh_weld() {
        let net = frigate();
        let options = HullOptions::try_new(1e-4, 8).expect("options");
        let hull = LiveHull::new(&net, &options).expect("builds");
        let deck = net
            .curves()
            .iter()
            .position(|c| c.role.name() == "deck")
            .expect("deck");
        let after = moved(&net, deck, 2, DVec3::new(0.0, 2e-5, 0.0));
        let (stages, rebuilt) = hull
            .stages
            .updated(&net, &after, &options)
            .expect("no error")
            .expect("connectivity kept");
        assert!(
            rebuilt > 0 && rebuilt < stages.faces.len(),
            "{rebuilt} faces patched again"
        );
        let mut weld = hull.weld.clone();
        let kept = reassemble(&stages, &hull.stages, &hull.surface, &mut weld)
            .expect("the kept mesh is rewritten");
        let (_, fresh, outward, _) = assemble_welded(&after, &stages).expect("assembles");
        assert_eq!(
            kept.mesh.positions, fresh.positions,
            "positions bit for bit"
        );
        assert_eq!(kept.mesh.face_vertices, fresh.face_vertices, "polygons");
        assert_eq!(kept.patches_outward, outward, "orientation");
        // Against the kept hull's own stages (nothing patched again) it is the same mesh.
        let mut weld = hull.weld.clone();
        let same = reassemble(&hull.stages, &hull.stages, &hull.surface, &mut weld)
            .expect("nothing to rewrite");
        assert_eq!(same.mesh, hull.surface.mesh, "unchanged");
    }

    /// A change that patches most faces again (a breadth change: every curve off the
    /// centreplane moves) welds afresh, and small moves after it that reach few faces rewrite
    /// that weld in place: each gives the mesh a full build gives, bit for bit.
    #[test]
    fn a_change_of_most_faces_is_welded_afresh_and_the_next_small_one_in_place() {
        let net = frigate();
        let options = HullOptions::try_new(1e-4, 8).expect("options");
        let wide = {
            let curves = net
                .curves()
                .iter()
                .map(|c| {
                    let points = c.curve.control_points().into_iter();
                    let points = points.map(|p| p * DVec3::new(1.0, 1.05, 1.0)).collect();
                    let curve = c.curve.with_control_points(points).expect("curve");
                    NetworkCurve { curve, ..c.clone() }
                })
                .collect();
            Network::try_new(net.name.clone(), curves).expect("network")
        };
        let full = |n: &Network| {
            LiveHull::new(n, &options)
                .expect("builds")
                .surface
                .mesh
                .clone()
        };
        let mut hull = LiveHull::new(&net, &options).expect("builds");
        let last = hull.rebuild(&wide).expect("rebuilds").clone();
        let Rebuild::Incremental { faces, of } = last else {
            panic!("an incremental rebuild, not {last:?}");
        };
        assert!(2 * faces > of, "{faces} of {of} faces patched again");
        assert_eq!(
            hull.surface().mesh,
            full(&wide),
            "welded afresh, bit for bit"
        );
        // Then one control point after another moved a little, each from the widened hull:
        // those that reach few faces are rewritten in place, the others welded afresh.
        let mut in_place = 0;
        for curve in 0..wide.curves().len() {
            for index in [0, 2] {
                for after in [
                    moved(&wide, curve, index, DVec3::new(0.0, 2e-5, 0.0)),
                    wide.clone(),
                ] {
                    let last = hull.rebuild(&after).expect("rebuilds").clone();
                    if matches!(last, Rebuild::Incremental { faces, of } if 2 * faces <= of) {
                        in_place += 1;
                    }
                    assert_eq!(hull.surface().mesh, full(&after), "curve {curve}: {last:?}");
                }
            }
        }
        assert!(in_place > 0, "no small move rewritten in place");
    }

    #[test]
    fn stages_of_other_faces_are_assembled_afresh() {
        let net = frigate();
        let options = HullOptions::try_new(1e-4, 8).expect("options");
        let hull = LiveHull::new(&net, &options).expect("builds");
        // Another resolution: every face's mesh has another shape.
        let finer =
            Stages::full(&net, &HullOptions::try_new(1e-4, 9).expect("options")).expect("stages");
        let mut weld = hull.weld.clone();
        assert!(
            reassemble(&finer, &hull.stages, &hull.surface, &mut weld).is_none(),
            "other mesh shapes"
        );
    }
}
