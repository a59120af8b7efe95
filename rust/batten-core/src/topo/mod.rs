//! Topology of a curve network (H-rep paper §3.1): nodes where the designer's curves meet,
//! edges as parameter intervals of those curves, a half-edge B-rep, and faces found
//! automatically (§5.2) with their true corners, plus diagnostics that name curves and places.

mod adjacency;
mod brep;
mod checks;
mod faces;
mod node_kind;
mod rotation;

use std::collections::{BTreeMap, HashMap};

use glam::DVec3;

pub use brep::{
    Brep, Edge, EdgeId, Face, FaceId, HalfEdge, HalfEdgeId, Loop, LoopId, Shell, ShellId, Vertex,
    VertexId,
};
pub use checks::{EdgeFacesError, EulerPoincareError, NextPrevError, TwinError, ValidationError};
pub use faces::{FaceSide, CORNER_ANGLE_DEGREES};
pub use node_kind::NodeKind;

use adjacency::Adjacency;

use crate::curve::BezierDecomposition;
use crate::diagnostic::Diagnostic;
use crate::error::Error;
use crate::network::Network;
use crate::tolerance::Tolerance;

/// Faces with more corners than this are reported ([`Diagnostic::UnusualFace`]): the N-sided
/// patch of §3.2.1 degrades with many sides.
pub const MAX_NORMAL_CORNERS: usize = 8;
/// A node whose unit edge tangents have a tip farther than this from the best plane through
/// the tips is a branching of the surface ([`Diagnostic::NonManifoldNode`], H-rep §3.1: faces
/// form a manifold shell). In one smooth surface the tips lie in the tangent plane (0); at a
/// cone-like corner they lie in a plane across the cone (0); where three sheets branch off one
/// curve the farthest tip is 0.75 from the best plane.
pub const BRANCHING_TIP_DISTANCE: f64 = 0.6;
/// Faces with fewer corners than this are reported: no patch method of §3.2.1 takes them.
pub const MIN_CORNERS: usize = 3;

/// A face as the patch builder needs it: its edges in loop order, its sides between true
/// corners and the designer curves along them (H-rep paper §5.2).
#[derive(Clone, Debug, PartialEq)]
pub struct TopoFace {
    /// Its edges, counter-clockwise about the surface normal.
    pub edges: Vec<EdgeId>,
    /// For each edge, true when the loop runs along the curve (from `t0` to `t1`).
    pub forward: Vec<bool>,
    /// The number of true corners (3 for a triangle, 4 for a quad …).
    pub corners: usize,
    /// The sides between corners.
    pub sides: Vec<FaceSide>,
    /// The designer curves of its boundary (indices into the network and into
    /// [`Topology::curve_names`]), sorted, without repeats.
    pub curves: Vec<usize>,
}

/// A boundary loop of the network (the open edge of a half hull: keel, stem, deck, transom …).
#[derive(Clone, Debug, PartialEq)]
pub struct BoundaryLoop {
    /// Its edges in order.
    pub edges: Vec<EdgeId>,
    /// The designer curves along it (indices into [`Topology::curve_names`]), sorted, without
    /// repeats.
    pub curves: Vec<usize>,
}

/// The topology of a curve network: the B-rep, its faces and boundary loops as plain data, and
/// everything the designer should know about the network.
#[derive(Clone, Debug, PartialEq)]
pub struct Topology {
    /// The names of the network's curves, by index: every `curves` list of the topology holds
    /// indices into this.
    pub curve_names: Vec<String>,
    /// The half-edge B-rep (vertices are the nodes, edges the curve stretches between them).
    pub brep: Brep,
    /// The faces, indexed like `brep.faces`.
    pub faces: Vec<TopoFace>,
    /// The boundary loops.
    pub boundary_loops: Vec<BoundaryLoop>,
    /// Findings about the network: dangling ends, near misses, unusual faces …
    pub diagnostics: Vec<Diagnostic>,
}

impl Topology {
    /// Build the topology of `network` at `tolerance` (H-rep paper §3.1 and §5.2).
    ///
    /// 1. Nodes: [`Network::junctions`] (end to end, T-joints, crossings within tolerance).
    /// 2. Edges: each curve is cut at its nodes into parameter intervals `[t0, t1]`; the
    ///    designer's curve stays the fundamental entity.
    /// 3. Branches that cannot bound a region (dangling ends and the edges leading to them) are
    ///    pruned and reported; the rest gets half-edges.
    /// 4. At each node the edges are sorted counter-clockwise about a surface normal estimated
    ///    from the edge tangents and oriented consistently by propagation over the network.
    /// 5. Loops are traced with "next = the edge immediately clockwise from the twin"; a loop
    ///    that is counter-clockwise about the normals is a face, the others are boundary loops.
    /// 6. Each face's corners are counted: the boundary turning by 15° or more (§3.2.2).
    /// 7. The B-rep is validated; a failure becomes [`Diagnostic::InvalidTopology`].
    ///
    /// Bad input (near misses, dangling ends, duplicates, overlaps, self-intersections,
    /// zero-length curves, faces with too few or too many corners) is reported in
    /// [`Topology::diagnostics`], never a panic; the error case is reserved for the curve kernel.
    ///
    /// Implementation note: corners are counted at nodes only, so a kink inside a curve between
    /// two nodes does not make a corner; a self-intersection makes no node; edges on dangling
    /// branches stay in `brep.edges` without half-edges.
    pub fn build(network: &Network, tolerance: Tolerance) -> Result<Topology, Error> {
        let junctions = network.junctions(tolerance)?;
        let tol = tolerance.get();
        let curves = network.curves();
        let mut diagnostics = junctions.diagnostics.clone();
        let mut brep = Brep::default();

        for j in &junctions.nodes {
            let mut names: Vec<usize> = j.incidences.iter().map(|i| i.curve).collect();
            names.sort();
            names.dedup();
            brep.vertices.push(Vertex {
                position: j.position,
                curves: names,
                outgoing: None,
                normal: DVec3::ZERO,
            });
        }

        // Edges: curve stretches between consecutive nodes.
        brep.edges.reserve_exact(
            junctions
                .splits
                .iter()
                .map(|s| s.len().saturating_sub(1))
                .sum(),
        );
        for (ci, splits) in junctions.splits.iter().enumerate() {
            if junctions.excluded[ci] {
                continue;
            }
            let curve = &curves[ci].curve;
            for w in splits.windows(2) {
                let ((t0, n0), (t1, n1)) = (w[0], w[1]);
                if t1 <= t0 {
                    continue;
                }
                let tm = 0.5 * (t0 + t1);
                if junctions
                    .suppressed
                    .iter()
                    .any(|&(c, lo, hi)| c == ci && tm > lo && tm < hi)
                {
                    continue; // another curve carries this shared stretch
                }
                if n0 == n1 {
                    let mid = curve.point(tm);
                    if (mid - brep.vertices[n0].position).length() <= tol {
                        continue; // a sub-tolerance wiggle, not a loop
                    }
                }
                brep.edges.push(Edge {
                    curve: ci,
                    t0,
                    t1,
                    start: VertexId::from_index(n0),
                    end: VertexId::from_index(n1),
                    half_edges: None,
                });
            }
        }

        let core = prune_branches(&brep);
        let evals: Vec<BezierDecomposition> = curves
            .iter()
            .map(|c| c.curve.bezier_decomposition())
            .collect();
        report_ends(network, &junctions, &brep, &core, &mut diagnostics);

        // Half-edges: 2k runs along edge k's curve, 2k + 1 against it.
        let core_edges = core.iter().filter(|&&c| c).count();
        brep.half_edges.reserve_exact(2 * core_edges);
        let mut dirs: Vec<DVec3> = Vec::with_capacity(2 * core_edges);
        let mut cache = rotation::EvalCache::default();
        for (k, e) in brep.edges.iter_mut().enumerate() {
            if !core[k] {
                continue;
            }
            let curve = &evals[e.curve];
            cache.on_curve(e.curve);
            let a = HalfEdgeId::from_index(brep.half_edges.len());
            let b = HalfEdgeId::from_index(brep.half_edges.len() + 1);
            for (h, origin, twin, from, to) in
                [(a, e.start, b, e.t0, e.t1), (b, e.end, a, e.t1, e.t0)]
            {
                brep.half_edges.push(HalfEdge {
                    origin,
                    twin,
                    next: h,
                    prev: h,
                    edge: EdgeId::from_index(k),
                    loop_id: LoopId(0),
                });
                dirs.push(rotation::leaving_direction(curve, from, to, &mut cache));
            }
            e.half_edges = Some([a, b]);
        }

        // The half-edges leaving each vertex, in the order they were made.
        let mut outgoing = Adjacency::from_pairs(
            brep.vertices.len(),
            brep.half_edges
                .iter()
                .enumerate()
                .map(|(i, he)| (he.origin.index(), HalfEdgeId::from_index(i))),
        );

        // Normals and the rotation system.
        let mut ts: Vec<DVec3> = Vec::new();
        let mut branching: Vec<HalfEdgeId> = Vec::new();
        let raw: Vec<Option<(DVec3, f64)>> = (0..outgoing.rows())
            .map(|v| {
                let hs = outgoing.row(v);
                ts.clear();
                ts.extend(hs.iter().map(|h| dirs[h.index()]));
                if rotation::off_plane(&ts) > BRANCHING_TIP_DISTANCE {
                    branching.push(hs[0]);
                }
                rotation::raw_normal(&ts).map(|n| (n, confidence(&ts)))
            })
            .collect();
        let neighbours = outgoing.map(|h| brep.destination(h).index());
        let mut normals = rotation::orient_normals(&raw, &neighbours);
        let mut position_in_rotation = vec![0usize; brep.half_edges.len()];
        let (mut keys, mut order, mut hs) = (Vec::new(), Vec::new(), Vec::new());
        for (v, &normal) in normals.iter().enumerate() {
            if outgoing.row(v).is_empty() {
                continue;
            }
            hs.clear();
            hs.extend_from_slice(outgoing.row(v));
            ts.clear();
            ts.extend(hs.iter().map(|h| dirs[h.index()]));
            let d = &ts;
            // Edges leaving with the same tangent are told apart a quarter along the edge.
            let further = |i: usize| {
                let h = hs[i];
                let e = &brep.edges[brep.half_edges[h.index()].edge.index()];
                let (from, to) = if brep.half_edges[h.index()].origin == e.start {
                    (e.t0, e.t1)
                } else {
                    (e.t1, e.t0)
                };
                let c = &evals[e.curve];
                (c.point(from + 0.25 * (to - from)) - c.point(from)).normalize_or_zero()
            };
            rotation::ccw_order(normal, d, &further, &mut keys, &mut order);
            let row = outgoing.row_mut(v);
            for (i, &k) in order.iter().enumerate() {
                row[i] = hs[k];
                position_in_rotation[hs[k].index()] = i;
            }
            brep.vertices[v].outgoing = Some(row[0]);
            brep.vertices[v].normal = normal;
        }
        for i in 0..brep.half_edges.len() {
            let twin = brep.half_edges[i].twin;
            let v = brep.half_edges[twin.index()].origin.index();
            let rot = outgoing.row(v);
            let next = rot[(position_in_rotation[twin.index()] + rot.len() - 1) % rot.len()];
            brep.half_edges[i].next = next;
            brep.half_edges[next.index()].prev = HalfEdgeId::from_index(i);
        }

        for h in branching {
            let v = brep.half_edges[h.index()].origin.index();
            diagnostics.push(Diagnostic::NonManifoldNode {
                curves: brep.vertices[v]
                    .curves
                    .iter()
                    .map(|&c| curves[c].name.clone())
                    .collect(),
                location: brep.vertices[v].position,
            });
        }

        // Shells: connected parts.
        let shell_of = components(&neighbours);

        // Loops.
        let mut visited = vec![false; brep.half_edges.len()];
        for i in 0..brep.half_edges.len() {
            if visited[i] {
                continue;
            }
            let l = LoopId::from_index(brep.loops.len());
            let first = HalfEdgeId::from_index(i);
            let mut h = first;
            loop {
                visited[h.index()] = true;
                brep.half_edges[h.index()].loop_id = l;
                h = brep.half_edges[h.index()].next;
                if h == first {
                    break;
                }
            }
            let shell = shell_of[brep.half_edges[i].origin.index()];
            brep.loops.push(Loop {
                first,
                face: None,
                shell: ShellId::from_index(shell),
            });
        }
        let shell_count = shell_of
            .iter()
            .copied()
            .filter(|&s| s != usize::MAX)
            .max()
            .map_or(0, |m| m + 1);
        brep.shells = vec![
            Shell {
                faces: Vec::new(),
                boundaries: Vec::new(),
                genus: 0,
            };
            shell_count
        ];

        // A part whose nodes all have parallel tangents (a lone closed curve) has no normal
        // from its tangents: take the direction of its first loop's vector area.
        let mut has_normal = vec![false; shell_count];
        for (v, r) in raw.iter().enumerate() {
            if r.is_some() && shell_of[v] != usize::MAX {
                has_normal[shell_of[v]] = true;
            }
        }
        for (si, _) in has_normal.iter().enumerate().filter(|(_, &h)| !h) {
            let Some(li) = brep.loops.iter().position(|l| l.shell.index() == si) else {
                continue;
            };
            let (area, _) = faces::orientation(&brep, &evals, &normals, LoopId::from_index(li));
            let n = area.normalize_or_zero();
            for v in 0..normals.len() {
                if shell_of[v] == si {
                    normals[v] = n;
                    brep.vertices[v].normal = n;
                }
            }
        }

        // Faces and boundary loops.
        let edge_areas = faces::edge_areas(&brep, &evals);
        let mut faces = Vec::with_capacity(brep.loops.len());
        let mut boundary_loops = Vec::new();
        let mut edge_stamp = vec![0u32; brep.edges.len()];
        let (mut corner_flags, mut names_buf) = (Vec::new(), Vec::new());
        for li in 0..brep.loops.len() {
            let l = LoopId::from_index(li);
            brep.loop_half_edges_into(l, &mut hs);
            let (area, normal) =
                faces::loop_orientation(&brep, &evals, &edge_areas, &normals, l, &hs);
            let is_face_side = area.dot(normal) > 0.0;
            let bridge = faces::has_bridge(&brep, &hs, &mut edge_stamp, li as u32 + 1);
            let shell = brep.loops[li].shell;
            let names = sorted_curves(&brep, &hs, &mut names_buf);
            if is_face_side && !bridge {
                let f = FaceId::from_index(brep.faces.len());
                brep.faces.push(Face { outer: l, shell });
                brep.loops[li].face = Some(f);
                brep.shells[shell.index()].faces.push(f);
                let (corners, sides) =
                    faces::corners_and_sides(&brep, &dirs, &hs, &mut corner_flags);
                faces.push(TopoFace {
                    edges: hs.iter().map(|&h| brep.half_edge(h).edge).collect(),
                    forward: hs.iter().map(|&h| brep.is_forward(h)).collect(),
                    corners,
                    sides,
                    curves: names,
                });
            } else {
                if is_face_side {
                    diagnostics.push(Diagnostic::UnclosedRegion {
                        curves: names.iter().map(|&c| curves[c].name.clone()).collect(),
                        location: brep.vertices[brep.half_edge(hs[0]).origin.index()].position,
                    });
                }
                brep.shells[shell.index()].boundaries.push(l);
                boundary_loops.push(BoundaryLoop {
                    edges: hs.iter().map(|&h| brep.half_edge(h).edge).collect(),
                    curves: names,
                });
            }
        }

        // Genus of every shell from its counts.
        for (si, shell) in brep.shells.iter_mut().enumerate() {
            let v = shell_of.iter().filter(|&&s| s == si).count() as i64;
            let e = brep
                .edges
                .iter()
                .filter(|e| e.half_edges.is_some() && shell_of[e.start.index()] == si)
                .count() as i64;
            let chi = v - e + shell.faces.len() as i64 + shell.boundaries.len() as i64;
            shell.genus = (2 - chi) / 2;
            if shell.genus != 0 || chi % 2 != 0 {
                let location = shell_of
                    .iter()
                    .position(|&s| s == si)
                    .map_or(DVec3::ZERO, |v| brep.vertices[v].position);
                diagnostics.push(Diagnostic::Genus {
                    genus: shell.genus,
                    location,
                });
            }
        }

        for (i, f) in faces.iter().enumerate() {
            if f.corners < MIN_CORNERS || f.corners > MAX_NORMAL_CORNERS {
                let e = &brep.edges[f.edges[0].index()];
                diagnostics.push(Diagnostic::UnusualFace {
                    face: i,
                    corners: f.corners,
                    curves: f.curves.iter().map(|&c| curves[c].name.clone()).collect(),
                    location: brep.vertices[e.start.index()].position,
                });
            }
        }
        for err in brep.validate() {
            if let ValidationError::EdgeFaces(ref e) = err {
                let edge = &brep.edges[e.edge.index()];
                let mid = curves[edge.curve].curve.point(0.5 * (edge.t0 + edge.t1));
                diagnostics.push(Diagnostic::NonManifoldEdge {
                    curve: curves[edge.curve].name.clone(),
                    location: mid,
                });
            }
            diagnostics.push(Diagnostic::InvalidTopology {
                message: err.to_string(),
            });
        }

        Ok(Topology {
            curve_names: curves.iter().map(|c| c.name.clone()).collect(),
            brep,
            faces,
            boundary_loops,
            diagnostics,
        })
    }

    /// The names of curves given by index (as in a face's or side's `curves`; the designer's
    /// curves of H-rep §3.1).
    pub fn names(&self, curves: &[usize]) -> Vec<&str> {
        curves
            .iter()
            .map(|&c| self.curve_names[c].as_str())
            .collect()
    }

    /// Number of nodes (vertices, H-rep §3.1).
    pub fn node_count(&self) -> usize {
        self.brep.vertices.len()
    }

    /// Number of edges (curve stretches between nodes, H-rep §3.1), including those bounding no
    /// face.
    pub fn edge_count(&self) -> usize {
        self.brep.edges.len()
    }

    /// Number of faces with each corner count: `{3: …, 4: …, 5: …}` (three-, four- and N-sided
    /// patches, H-rep §3.2.1).
    pub fn faces_by_corners(&self) -> BTreeMap<usize, usize> {
        let mut out = BTreeMap::new();
        for f in &self.faces {
            *out.entry(f.corners).or_insert(0) += 1;
        }
        out
    }

    /// The diagnostics of one kind (see [`Diagnostic::kind`]; H-rep §5.2).
    pub fn diagnostics_of(&self, kind: &str) -> Vec<&Diagnostic> {
        self.diagnostics
            .iter()
            .filter(|d| d.kind() == kind)
            .collect()
    }
}

/// How well a set of tangents defines a plane: the largest sine between two of them.
fn confidence(tangents: &[DVec3]) -> f64 {
    let mut best: f64 = 0.0;
    for (i, a) in tangents.iter().enumerate() {
        for b in &tangents[i + 1..] {
            best = best.max(a.cross(*b).length());
        }
    }
    best
}

/// The designer curves along a loop, sorted, without repeats (`scratch` is a work buffer).
fn sorted_curves(brep: &Brep, hs: &[HalfEdgeId], scratch: &mut Vec<usize>) -> Vec<usize> {
    scratch.clear();
    scratch.extend(
        hs.iter()
            .map(|&h| brep.edges[brep.half_edge(h).edge.index()].curve),
    );
    scratch.sort_unstable();
    scratch.dedup();
    scratch.clone()
}

/// Edges that can bound a region: repeatedly drop edges with an end no other edge touches.
fn prune_branches(brep: &Brep) -> Vec<bool> {
    let at = Adjacency::from_pairs(
        brep.vertices.len(),
        brep.edges
            .iter()
            .enumerate()
            .flat_map(|(k, e)| [(e.start.index(), k), (e.end.index(), k)]),
    );
    let mut degree: Vec<usize> = (0..at.rows()).map(|v| at.row(v).len()).collect();
    let mut core = vec![true; brep.edges.len()];
    let mut stack: Vec<usize> = (0..degree.len()).filter(|&v| degree[v] == 1).collect();
    while let Some(v) = stack.pop() {
        if degree[v] != 1 {
            continue;
        }
        let Some(&k) = at.row(v).iter().find(|&&k| core[k]) else {
            continue;
        };
        core[k] = false;
        let e = &brep.edges[k];
        for w in [e.start.index(), e.end.index()] {
            degree[w] -= 1;
            if degree[w] == 1 {
                stack.push(w);
            }
        }
    }
    core
}

/// Dangling ends, isolated curves and edges bounding no face.
fn report_ends(
    network: &Network,
    junctions: &crate::network::Junctions,
    brep: &Brep,
    core: &[bool],
    diagnostics: &mut Vec<Diagnostic>,
) {
    let curves = network.curves();
    let mut degree = vec![0usize; brep.vertices.len()];
    for e in &brep.edges {
        degree[e.start.index()] += 1;
        degree[e.end.index()] += 1;
    }
    let mut isolated = vec![false; curves.len()];
    for (ci, splits) in junctions.splits.iter().enumerate() {
        if junctions.excluded[ci] || splits.is_empty() {
            continue;
        }
        let alone = splits
            .iter()
            .all(|&(_, n)| junctions.nodes[n].incidences.iter().all(|i| i.curve == ci));
        if alone {
            isolated[ci] = true;
            diagnostics.push(Diagnostic::IsolatedCurve {
                curve: curves[ci].name.clone(),
                location: brep.vertices[splits[0].1].position,
            });
        }
    }
    for e in &brep.edges {
        if isolated[e.curve] {
            continue;
        }
        for v in [e.start, e.end] {
            if degree[v.index()] == 1 {
                diagnostics.push(Diagnostic::DanglingEnd {
                    curve: curves[e.curve].name.clone(),
                    location: brep.vertices[v.index()].position,
                });
            }
        }
    }
    let mut unused: HashMap<usize, (usize, DVec3)> = HashMap::new();
    for (k, e) in brep.edges.iter().enumerate() {
        if !core[k] && !isolated[e.curve] {
            let entry = unused
                .entry(e.curve)
                .or_insert((0, brep.vertices[e.start.index()].position));
            entry.0 += 1;
        }
    }
    let mut unused: Vec<(usize, (usize, DVec3))> = unused.into_iter().collect();
    unused.sort_by_key(|(c, _)| *c);
    for (c, (edges, location)) in unused {
        diagnostics.push(Diagnostic::UnusedEdges {
            curve: curves[c].name.clone(),
            edges,
            location,
        });
    }
}

/// Connected parts of the graph: a part index per vertex (`usize::MAX` for lone vertices).
fn components(neighbours: &Adjacency<usize>) -> Vec<usize> {
    let mut part = vec![usize::MAX; neighbours.rows()];
    let mut count = 0;
    let mut stack = Vec::new();
    for s in 0..neighbours.rows() {
        if part[s] != usize::MAX || neighbours.row(s).is_empty() {
            continue;
        }
        part[s] = count;
        stack.push(s);
        while let Some(u) = stack.pop() {
            for &v in neighbours.row(u) {
                if part[v] == usize::MAX {
                    part[v] = count;
                    stack.push(v);
                }
            }
        }
        count += 1;
    }
    part
}
