//! IGES 5.3 (US PRO/IPO-100, 1996) text of the exported faces: one rational B-spline surface
//! entity (type 128, form 0, polynomial flag set, all weights 1) per face, each with its
//! parameter range `U(0), U(1), V(0), V(1)` — the fields a reader needs to know which part of
//! the surface is meant (FREE!ship's files once lost a face for want of them).
//!
//! Layout (IGES 5.3 §2.1–2.2): 80-column fixed records, columns 1–72 data, 73 the section
//! letter (S, G, D, P, T), 74–80 the sequence number within the section; a parameter record
//! holds data in columns 1–64 and its entity's directory pointer in 66–72.

use super::bspline::BsplineSurface;
use super::surface::CadSurface;
use super::text::{ascii, real, system, CadHeader};

/// Data columns of a record.
const DATA_COLUMNS: usize = 72;
/// Data columns of a parameter-section record (the directory pointer follows).
const PARAMETER_COLUMNS: usize = 64;
/// Width of a directory-entry field and of a sequence number.
const FIELD: usize = 8;
/// Model units flag of the global section: 6 = metres (IGES 5.3 Table 3).
const UNITS_METRES: u32 = 6;
/// Version flag of the global section: 11 = IGES 5.3.
const VERSION_5_3: u32 = 11;
/// The rational B-spline surface entity.
const SURFACE_ENTITY: u32 = 128;

/// One fixed-width record: `data` padded to 72 columns, the section letter, the sequence.
fn record(data: &str, section: char, seq: usize) -> String {
    format!("{data:<DATA_COLUMNS$}{section}{seq:>7}\n")
}

/// A Hollerith string constant, `nH…`.
fn hollerith(s: &str) -> String {
    let s = ascii(s);
    format!("{}H{s}", s.len())
}

/// Free-format parameters packed into lines of at most `width` columns, none split, joined by
/// `,` and closed by `;`.
fn pack(params: &[String], width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for (k, p) in params.iter().enumerate() {
        let item = format!("{p}{}", if k + 1 == params.len() { ';' } else { ',' });
        if !line.is_empty() && line.len() + item.len() > width {
            lines.push(std::mem::take(&mut line));
        }
        line.push_str(&item);
    }
    lines.push(line);
    lines
}

/// The parameters of entity 128 for `s` on its whole range `[0, 1]²` (IGES 5.3 §4.24).
fn surface_parameters(s: &BsplineSurface) -> Vec<String> {
    let (nu, nv) = (s.count_u, s.count_v);
    let p = s.degree();
    let mut out: Vec<String> = [SURFACE_ENTITY as usize, nu - 1, nv - 1, p, p]
        .iter()
        .map(ToString::to_string)
        .collect();
    // Not closed in u or v, polynomial, not periodic in u or v.
    out.extend(["0", "0", "1", "0", "0"].map(String::from));
    out.extend(s.knots_u.iter().map(|&k| real(k)));
    out.extend(s.knots_v.iter().map(|&k| real(k)));
    out.extend(std::iter::repeat_n(real(1.0), nu * nv));
    // Control points with the first index (along u) varying fastest.
    for j in 0..nv {
        for i in 0..nu {
            out.extend(s.point_at(i, j).to_array().map(real));
        }
    }
    out.extend([0.0, 1.0, 0.0, 1.0].map(real));
    out
}

/// The global section's parameters (IGES 5.3 §2.2.4, fields 1–25).
fn global_parameters(cad: &CadSurface, header: &CadHeader) -> Vec<String> {
    let t = header.timestamp;
    let date = hollerith(&format!(
        "{:04}{:02}{:02}.{:02}{:02}{:02}",
        t.year, t.month, t.day, t.hour, t.minute, t.second
    ));
    let size = cad
        .faces
        .iter()
        .flat_map(|f| &f.surface.control)
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max);
    vec![
        hollerith(","),
        hollerith(";"),
        hollerith(&header.name),
        hollerith(&header.file_name),
        hollerith("batten"),
        hollerith(&system()),
        "32".into(),
        "38".into(),
        "6".into(),
        "308".into(),
        "15".into(),
        hollerith(&header.name),
        real(1.0),
        UNITS_METRES.to_string(),
        hollerith("M"),
        "1".into(),
        real(1.0),
        date.clone(),
        real(cad.tolerance),
        real(size),
        hollerith(&header.author),
        hollerith(""),
        VERSION_5_3.to_string(),
        "0".into(),
        date,
    ]
}

/// The IGES 5.3 file of `cad`: start, global, directory-entry, parameter-data and terminate
/// sections, one entity 128 per face, lengths in metres.
pub fn iges_text(cad: &CadSurface, header: &CadHeader) -> String {
    let mut out = String::new();
    let start = format!(
        "{}: hull surface of '{}', {} bicubic B-spline surfaces (entity 128) from {} patches, \
         metres, within {} m of batten's surface.",
        system(),
        ascii(&header.name),
        cad.faces.len(),
        cad.patches,
        real(cad.tolerance)
    );
    let start_lines: Vec<String> = start
        .as_bytes()
        .chunks(DATA_COLUMNS)
        .map(|c| String::from_utf8_lossy(c).into_owned())
        .collect();
    for (k, l) in start_lines.iter().enumerate() {
        out.push_str(&record(l, 'S', k + 1));
    }
    let global = pack(&global_parameters(cad, header), DATA_COLUMNS);
    for (k, l) in global.iter().enumerate() {
        out.push_str(&record(l, 'G', k + 1));
    }
    let mut directory = String::new();
    let mut parameters = String::new();
    let mut p_seq = 1;
    for (k, face) in cad.faces.iter().enumerate() {
        let de = 2 * k + 1;
        let lines = pack(&surface_parameters(&face.surface), PARAMETER_COLUMNS);
        let field = |v: &dyn ToString| format!("{:>FIELD$}", v.to_string());
        let first = [
            field(&SURFACE_ENTITY),
            field(&p_seq),
            field(&0),
            field(&0),
            field(&0),
            field(&0),
            field(&0),
            field(&0),
            "00000000".to_string(),
        ]
        .concat();
        let second = [
            field(&SURFACE_ENTITY),
            field(&0),
            field(&0),
            field(&lines.len()),
            field(&0),
            field(&""),
            field(&""),
            field(&"PATCH"),
            field(&(face.face)),
        ]
        .concat();
        directory.push_str(&record(&first, 'D', de));
        directory.push_str(&record(&second, 'D', de + 1));
        for l in &lines {
            let data = format!("{l:<PARAMETER_COLUMNS$} {de:>7}");
            parameters.push_str(&record(&data, 'P', p_seq));
            p_seq += 1;
        }
    }
    out.push_str(&directory);
    out.push_str(&parameters);
    let counts = format!(
        "S{:>7}G{:>7}D{:>7}P{:>7}",
        start_lines.len(),
        global.len(),
        2 * cad.faces.len(),
        p_seq - 1
    );
    out.push_str(&record(&counts, 'T', 1));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::bspline::clamped;
    use crate::export::surface::CadFace;
    use glam::DVec3;

    fn flat() -> CadSurface {
        let control = (0..4)
            .flat_map(|i| (0..5).map(move |j| DVec3::new(i as f64 / 3.0, j as f64 / 4.0, 0.0)))
            .collect();
        let surface = BsplineSurface {
            knots_u: clamped(&[]),
            knots_v: clamped(&[0.5]),
            count_u: 4,
            count_v: 5,
            control,
        };
        CadSurface {
            faces: vec![CadFace {
                patch: 0,
                face: 7,
                quad: 0,
                surface,
                deviation: 0.0,
            }],
            tolerance: 1e-4,
            max_deviation: 0.0,
            patches: 1,
        }
    }

    #[test]
    fn every_record_is_80_columns_with_its_section_and_sequence() {
        let text = iges_text(&flat(), &CadHeader::default());
        let mut last = (' ', 0);
        for line in text.lines() {
            assert_eq!(line.len(), 80, "record length: {line:?}");
            let section = line.as_bytes()[72] as char;
            let seq: usize = line[73..].trim().parse().expect("a sequence number");
            if section == last.0 {
                assert_eq!(seq, last.1 + 1, "sequence runs on in {section}");
            } else {
                assert_eq!(seq, 1, "sequence starts at 1 in {section}");
            }
            last = (section, seq);
        }
        assert_eq!(last.0, 'T', "ends with the terminate section");
        let p: Vec<&str> = text.lines().filter(|l| l.as_bytes()[72] == b'P').collect();
        assert!(
            p.iter().all(|l| l[65..72].trim() == "1"),
            "parameter lines point at DE 1"
        );
        let data: String = p.iter().map(|l| l[..64].trim_end()).collect();
        assert!(
            data.starts_with("128,3,4,3,3,0,0,1,0,0,"),
            "entity header: {data}"
        );
        assert!(
            data.ends_with("0.0E0,1.0E0,0.0E0,1.0E0;"),
            "parameter ranges: {data}"
        );
        let g: String = text
            .lines()
            .filter(|l| l.as_bytes()[72] == b'G')
            .map(|l| l[..72].trim_end())
            .collect();
        assert!(
            g.contains(",1.0E0,6,1HM,"),
            "metres in the global section: {g}"
        );
    }
}
