//! STEP AP214 (ISO 10303-214, automotive design; ISO 10303-21 clear text) of the exported
//! faces: a product with one `MANIFOLD_SURFACE_SHAPE_REPRESENTATION` holding a
//! `SHELL_BASED_SURFACE_MODEL` of one `OPEN_SHELL`, one `ADVANCED_FACE` per face on its
//! `B_SPLINE_SURFACE_WITH_KNOTS`, bounded by an `EDGE_LOOP` of its four boundary curves
//! (`B_SPLINE_CURVE_WITH_KNOTS`, the rows and columns of its control net), lengths in metres.
//!
//! Every face has its own edges and vertices: the faces of neighbouring patches meet along
//! the same curve but are split at different points (a T-joint, an N-sided patch's quads), so
//! a reader sews them (as it sews any surface model) rather than the file naming shared edges.

use std::fmt::Write;

use super::bspline::BsplineSurface;
use super::surface::CadSurface;
use super::text::{ascii, knot_multiplicities, real, system, CadHeader};

/// Writes numbered entities `#n=…;`.
struct Entities {
    text: String,
    next: usize,
}

impl Entities {
    /// Add an entity and return its number.
    fn add(&mut self, body: impl AsRef<str>) -> usize {
        let id = self.next;
        self.next += 1;
        // Writing into a String cannot fail.
        let _ = writeln!(self.text, "#{id}={};", body.as_ref());
        id
    }
}

/// A STEP string: printable ASCII, apostrophes doubled.
fn string(s: &str) -> String {
    format!("'{}'", ascii(s).replace('\'', "''"))
}

/// `(#a,#b,…)`.
fn refs(ids: &[usize]) -> String {
    let inner: Vec<String> = ids.iter().map(|i| format!("#{i}")).collect();
    format!("({})", inner.join(","))
}

/// `(a,b,…)` of displayed items.
fn list<T: ToString>(items: &[T]) -> String {
    let inner: Vec<String> = items.iter().map(ToString::to_string).collect();
    format!("({})", inner.join(","))
}

/// The multiplicities and knot values of a knot vector, as STEP lists.
fn knot_lists(knots: &[f64]) -> (String, String) {
    let (values, mults) = knot_multiplicities(knots);
    let values: Vec<String> = values.into_iter().map(real).collect();
    (list(&mults), list(&values))
}

/// Write one face: its control points, surface, boundary curves, vertices, edges, loop and
/// the face itself; returns the face's number.
fn write_face(e: &mut Entities, s: &BsplineSurface) -> usize {
    let (nu, nv) = (s.count_u, s.count_v);
    let p = s.degree();
    let points: Vec<usize> = s
        .control
        .iter()
        .map(|c| {
            let xyz: Vec<String> = c.to_array().map(real).to_vec();
            e.add(format!("CARTESIAN_POINT('',{})", list(&xyz)))
        })
        .collect();
    let rows: Vec<String> = (0..nu)
        .map(|i| refs(&points[i * nv..(i + 1) * nv]))
        .collect();
    let (mu, ku) = knot_lists(&s.knots_u);
    let (mv, kv) = knot_lists(&s.knots_v);
    let surface = e.add(format!(
        "B_SPLINE_SURFACE_WITH_KNOTS('',{p},{p},({}),.UNSPECIFIED.,.F.,.F.,.F.,{mu},{mv},{ku},{kv},.UNSPECIFIED.)",
        rows.join(",")
    ));
    let at = |i: usize, j: usize| points[i * nv + j];
    let corners = [at(0, 0), at(nu - 1, 0), at(nu - 1, nv - 1), at(0, nv - 1)];
    let vertices: Vec<usize> = corners
        .iter()
        .map(|&c| e.add(format!("VERTEX_POINT('',#{c})")))
        .collect();
    // Bottom and top run along u, left and right along v, all from parameter 0 to 1.
    let bottom: Vec<usize> = (0..nu).map(|i| at(i, 0)).collect();
    let top: Vec<usize> = (0..nu).map(|i| at(i, nv - 1)).collect();
    let left: Vec<usize> = (0..nv).map(|j| at(0, j)).collect();
    let right: Vec<usize> = (0..nv).map(|j| at(nu - 1, j)).collect();
    // (control points, knots, start vertex, end vertex, runs with the loop)
    let sides = [
        (bottom, (&mu, &ku), vertices[0], vertices[1], true),
        (right, (&mv, &kv), vertices[1], vertices[2], true),
        (top, (&mu, &ku), vertices[3], vertices[2], false),
        (left, (&mv, &kv), vertices[0], vertices[3], false),
    ];
    let edges: Vec<usize> = sides
        .iter()
        .map(|(pts, (m, k), a, b, sense)| {
            let c = e.add(format!(
                "B_SPLINE_CURVE_WITH_KNOTS('',{p},{},.UNSPECIFIED.,.F.,.F.,{m},{k},.UNSPECIFIED.)",
                refs(pts)
            ));
            let edge = e.add(format!("EDGE_CURVE('',#{a},#{b},#{c},.T.)"));
            let flag = if *sense { ".T." } else { ".F." };
            e.add(format!("ORIENTED_EDGE('',*,*,#{edge},{flag})"))
        })
        .collect();
    let edge_loop = e.add(format!("EDGE_LOOP('',{})", refs(&edges)));
    let bound = e.add(format!("FACE_OUTER_BOUND('',#{edge_loop},.T.)"));
    e.add(format!("ADVANCED_FACE('',(#{bound}),#{surface},.T.)"))
}

/// The STEP AP214 file of `cad` (see the module documentation).
pub fn step_text(cad: &CadSurface, header: &CadHeader) -> String {
    let t = header.timestamp;
    let when = format!(
        "{:04}-{:02}-{:02}T{:02}:{:02}:{:02}",
        t.year, t.month, t.day, t.hour, t.minute, t.second
    );
    let name = string(&header.name);
    let mut e = Entities {
        text: String::new(),
        next: 1,
    };
    let app = e.add("APPLICATION_CONTEXT('automotive design')");
    e.add(format!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
    ));
    let pc = e.add(format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
    let product = e.add(format!("PRODUCT({name},{name},'hull surface',(#{pc}))"));
    e.add(format!(
        "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"
    ));
    let pdf = e.add(format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
    let pdc = e.add(format!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"
    ));
    let pd = e.add(format!("PRODUCT_DEFINITION('design','',#{pdf},#{pdc})"));
    let pds = e.add(format!("PRODUCT_DEFINITION_SHAPE('','',#{pd})"));
    let length = e.add("(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.))");
    let angle = e.add("(NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.))");
    let solid = e.add("(NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT())");
    let uncertainty = e.add(format!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE({}),#{length},'distance_accuracy_value','maximum deviation from batten''s surface')",
        real(cad.tolerance)
    ));
    let context = e.add(format!(
        "(GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{uncertainty})) GLOBAL_UNIT_ASSIGNED_CONTEXT((#{length},#{angle},#{solid})) REPRESENTATION_CONTEXT('hull','3D'))"
    ));
    let origin = e.add("CARTESIAN_POINT('',(0.0E0,0.0E0,0.0E0))");
    let z = e.add("DIRECTION('',(0.0E0,0.0E0,1.0E0))");
    let x = e.add("DIRECTION('',(1.0E0,0.0E0,0.0E0))");
    let placement = e.add(format!("AXIS2_PLACEMENT_3D('',#{origin},#{z},#{x})"));
    let faces: Vec<usize> = cad
        .faces
        .iter()
        .map(|f| write_face(&mut e, &f.surface))
        .collect();
    let shell = e.add(format!("OPEN_SHELL('',{})", refs(&faces)));
    let model = e.add(format!("SHELL_BASED_SURFACE_MODEL('',(#{shell}))"));
    let rep = e.add(format!(
        "MANIFOLD_SURFACE_SHAPE_REPRESENTATION({name},(#{placement},#{model}),#{context})"
    ));
    e.add(format!("SHAPE_DEFINITION_REPRESENTATION(#{pds},#{rep})"));
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('hull surface of {}: {} B-spline faces from {} patches'),'2;1');\n\
         FILE_NAME({},'{when}',({}),(''),{},'batten','');\n\
         FILE_SCHEMA(('AUTOMOTIVE_DESIGN {{ 1 0 10303 214 1 1 1 1 }}'));\nENDSEC;\nDATA;\n{}ENDSEC;\nEND-ISO-10303-21;\n",
        ascii(&header.name).replace('\'', "''"),
        cad.faces.len(),
        cad.patches,
        string(&header.file_name),
        string(&header.author),
        string(&system()),
        e.text
    )
}
