//! The pieces of a section joined into polylines: each piece's ends to the nearest end of
//! another within the join distance (a spatial hash of the ends; closest pairs first), then
//! chains walked from the pieces with a free end (open) and round what is left (closed), each
//! oriented the way most of its length runs along `m × n` (`n` outward).
//! Where a chain passes from one patch to another at a crease of the surface (the section's
//! tangents `m × n` on the two sides more than the knuckle angle apart), the point is a corner.

use std::collections::HashMap;

use glam::DVec3;

use super::trace::Piece;
use crate::patch::Patch;

/// One polyline of a section: points in order, whether it closes on itself, and the indices
/// of its corners (where it crosses a knuckle of the surface).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SectionPolyline {
    /// The points (m, hull axes) on the surface and the plane; a closed polyline does not
    /// repeat its first point.
    pub points: Vec<DVec3>,
    /// Whether the last point joins the first.
    pub closed: bool,
    /// Indices into `points` of the corners, ascending (a closed polyline with corners starts
    /// at one, which is then index 0).
    pub corners: Vec<usize>,
}

/// The grid cell of a point in the spatial hash of cell size `h`.
fn key(p: DVec3, h: f64) -> (i64, i64, i64) {
    let q = (p / h).floor();
    // The hull's size over the join distance is far below i64's range.
    (q.x as i64, q.y as i64, q.z as i64)
}

/// The other end of a piece's end `(piece, 0 = start | 1 = end)`.
type End = (usize, usize);

/// The point of a piece's end.
fn end_point(pieces: &[Piece], (i, e): End) -> DVec3 {
    let pts = &pieces[i].points;
    if e == 0 {
        pts[0]
    } else {
        *pts.last().expect("a piece has points")
    }
}

/// For each end of each piece, the end of another piece it joins (within `join`), pairs taken
/// nearest first, each end used once. Ends are matched whichever way the pieces run, so a
/// piece whose orientation came out wrong (a normal at a degenerate patch corner) still joins.
fn partners(pieces: &[Piece], join: f64) -> Vec<[Option<End>; 2]> {
    let mut grid: HashMap<(i64, i64, i64), Vec<End>> = HashMap::new();
    for i in 0..pieces.len() {
        for e in 0..2 {
            grid.entry(key(end_point(pieces, (i, e)), join))
                .or_default()
                .push((i, e));
        }
    }
    let mut pairs: Vec<(f64, End, End)> = Vec::new();
    for i in 0..pieces.len() {
        for e in 0..2 {
            let p = end_point(pieces, (i, e));
            let (a, b, c) = key(p, join);
            for da in -1..=1 {
                for db in -1..=1 {
                    for dc in -1..=1 {
                        let Some(ends) = grid.get(&(a + da, b + db, c + dc)) else {
                            continue;
                        };
                        for &(j, f) in ends {
                            let d = (end_point(pieces, (j, f)) - p).length();
                            if (i, e) < (j, f) && j != i && d <= join {
                                pairs.push((d, (i, e), (j, f)));
                            }
                        }
                    }
                }
            }
        }
    }
    pairs.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
    let mut partner = vec![[None; 2]; pieces.len()];
    for (_, a, b) in pairs {
        if partner[a.0][a.1].is_none() && partner[b.0][b.1].is_none() {
            partner[a.0][a.1] = Some(b);
            partner[b.0][b.1] = Some(a);
        }
    }
    partner
}

/// A piece as a chain runs through it: its index and whether it is run backwards.
#[derive(Clone, Copy)]
struct Run {
    piece: usize,
    reversed: bool,
}

impl Run {
    /// The domain point where the chain leaves the piece, and where it enters it.
    fn exit(self, pieces: &[Piece]) -> glam::DVec2 {
        let p = &pieces[self.piece];
        if self.reversed {
            p.start
        } else {
            p.end
        }
    }

    fn entry(self, pieces: &[Piece]) -> glam::DVec2 {
        let p = &pieces[self.piece];
        if self.reversed {
            p.end
        } else {
            p.start
        }
    }
}

/// Whether the section turns by more than `corner_angle` (radians) where run `a` ends and run
/// `b` starts on another patch: the angle between `m × n` on either side (the runs' own
/// direction does not matter: the angle between the lines is taken).
fn is_corner(
    a: Run,
    b: Run,
    pieces: &[Piece],
    patches: &[Patch],
    m: DVec3,
    corner_angle: f64,
) -> bool {
    let (pa, pb) = (pieces[a.piece].patch, pieces[b.piece].patch);
    if pa == pb {
        return false;
    }
    let ta = m.cross(patches[pa].normal(a.exit(pieces).to_array()));
    let tb = m.cross(patches[pb].normal(b.entry(pieces).to_array()));
    if ta.length_squared() == 0.0 || tb.length_squared() == 0.0 {
        return false;
    }
    let angle = ta.angle_between(tb);
    angle.min(std::f64::consts::PI - angle) > corner_angle
}

/// The pieces joined into polylines (see the module).
pub(crate) fn join_pieces(
    pieces: &[Piece],
    patches: &[Patch],
    m: DVec3,
    join: f64,
    corner_angle: f64,
) -> Vec<SectionPolyline> {
    let partner = partners(pieces, join);
    let mut used = vec![false; pieces.len()];
    let mut out = Vec::new();
    // Open chains first (from a piece with a free end), then the loops left.
    let heads: Vec<Run> = (0..pieces.len())
        .filter_map(|i| match partner[i] {
            [None, _] => Some(Run {
                piece: i,
                reversed: false,
            }),
            [_, None] => Some(Run {
                piece: i,
                reversed: true,
            }),
            _ => None,
        })
        .chain((0..pieces.len()).map(|i| Run {
            piece: i,
            reversed: false,
        }))
        .collect();
    for head in heads {
        if used[head.piece] {
            continue;
        }
        let mut runs = vec![head];
        used[head.piece] = true;
        let mut closed = false;
        loop {
            let last = *runs.last().expect("a run");
            let leaving = if last.reversed { 0 } else { 1 };
            match partner[last.piece][leaving] {
                Some((j, _)) if j == head.piece => {
                    closed = true;
                    break;
                }
                Some((j, f)) if !used[j] => {
                    used[j] = true;
                    runs.push(Run {
                        piece: j,
                        reversed: f == 1,
                    });
                }
                _ => break,
            }
        }
        out.push(polyline(&runs, closed, pieces, patches, m, corner_angle));
    }
    out
}

/// The polyline of a chain of runs, oriented the way most of its length runs along `m × n`.
fn polyline(
    runs: &[Run],
    closed: bool,
    pieces: &[Piece],
    patches: &[Patch],
    m: DVec3,
    corner_angle: f64,
) -> SectionPolyline {
    let length = |p: &Piece| -> f64 { p.points.windows(2).map(|w| (w[1] - w[0]).length()).sum() };
    let forward: f64 = runs
        .iter()
        .map(|r| if r.reversed { -1.0 } else { 1.0 } * length(&pieces[r.piece]))
        .sum();
    let runs: Vec<Run> = if forward >= 0.0 {
        runs.to_vec()
    } else {
        runs.iter()
            .rev()
            .map(|r| Run {
                piece: r.piece,
                reversed: !r.reversed,
            })
            .collect()
    };
    let mut line = SectionPolyline::default();
    for (k, run) in runs.iter().enumerate() {
        let pts = &pieces[run.piece].points;
        let skip = usize::from(k > 0);
        let kept = line.corners.last().map_or(0, |&c| c + 1);
        let ordered: Box<dyn Iterator<Item = &DVec3>> = if run.reversed {
            Box::new(pts.iter().rev().skip(skip))
        } else {
            Box::new(pts.iter().skip(skip))
        };
        for &p in ordered {
            push_in_order(&mut line.points, p, kept);
        }
        if let Some(next) = runs.get(k + 1) {
            if is_corner(*run, *next, pieces, patches, m, corner_angle) {
                line.corners.push(line.points.len() - 1);
            }
        }
    }
    if closed {
        if is_corner(
            runs[runs.len() - 1],
            runs[0],
            pieces,
            patches,
            m,
            corner_angle,
        ) {
            line.corners.push(0);
        }
        line.points.pop();
        line.closed = true;
        start_at_corner(&mut line);
    }
    line
}

/// A section's polyline turns back on itself by more than this (cosine of the turn between
/// consecutive chords, 120°) only where its points are out of order along the curve: within a
/// piece every chord is within the cut tolerance of the curve, and corners are kept apart.
const REVERSAL_COS: f64 = -0.5;

/// Push `p` after the points of `line`, first dropping the last points (not before index
/// `kept`, the one after the last corner) that `p` shows out of order: where the polyline would
/// turn back on itself (every point is on the curve, so dropping one keeps the polyline on it).
fn push_in_order(line: &mut Vec<DVec3>, p: DVec3, kept: usize) {
    while line.len() >= 2 && line.len() > kept {
        let (a, b) = (line[line.len() - 2], line[line.len() - 1]);
        let (u, v) = (b - a, p - b);
        if u.dot(v) < REVERSAL_COS * u.length() * v.length() {
            line.pop();
        } else {
            break;
        }
    }
    line.push(p);
}

/// Rotate a closed polyline with corners so it starts at its first corner.
fn start_at_corner(line: &mut SectionPolyline) {
    line.corners.sort_unstable();
    let Some(&first) = line.corners.first() else {
        return;
    };
    let n = line.points.len();
    line.points.rotate_left(first);
    line.corners = line.corners.iter().map(|&c| (c + n - first) % n).collect();
    line.corners.sort_unstable();
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pushed(points: &[[f64; 3]], kept: usize) -> Vec<[f64; 3]> {
        let mut line = Vec::new();
        for &p in points {
            push_in_order(&mut line, DVec3::from(p), kept);
        }
        line.iter().map(|p| p.to_array()).collect()
    }

    #[test]
    fn points_out_of_order_are_dropped_so_the_section_never_doubles_back() {
        // Up a station: a polish overshot to z 4.40, then the points come back down to 4.39
        // and on: the overshoot and the points it passed go, the order along the curve stays.
        let z = [4.30, 4.35, 4.40, 4.39, 4.385, 4.45, 4.50];
        let line = pushed(&z.map(|z| [0.0, z * 0.1, z]), 0);
        let zs: Vec<f64> = line.iter().map(|p| p[2]).collect();
        assert_eq!(zs, vec![4.30, 4.35, 4.385, 4.45, 4.50]);
        assert!(zs.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn a_corner_and_an_ordinary_turn_are_kept() {
        // A turn back by 148° off a point that is no corner: taken for points out of order.
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [1.2, 0.5, 0.0],
        ];
        assert_eq!(
            pushed(&pts, 0).len(),
            3,
            "a turn back by more than 120° drops the point"
        );
        // At a corner the line keeps (points before `kept`), the same turn stays.
        assert_eq!(pushed(&pts, 3).len(), 4);
        // A turn of 58° is an ordinary bend.
        let gentle = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.5, 0.8, 0.0]];
        assert_eq!(pushed(&gentle, 0).len(), 3);
    }
}
