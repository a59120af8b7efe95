//! The versioned JSON format of a curve network.
//!
//! ```json
//! {"format": "batten-network", "version": 1, "name": "frigate",
//!  "curves": [{"name": "keel", "role": "keel", "degree": 3,
//!              "knots": [...], "points": [[x, y, z], ...], "weights": null}]}
//! ```
//! Version 2 adds the network's tangent planes (see [`TangentPlane`]), as
//! `"tangent_planes": [[nx, ny, nz, offset], ...]`; a network without any is written as
//! version 1, so that older readers still read it. Floats are written in shortest round-trip
//! form and read with correct rounding, so writing and reading a network gives back bitwise
//! the same curves and planes.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::{Network, NetworkCurve, Role, TangentPlane};
use crate::curve::NurbsCurve;
use crate::error::Error;

/// The `format` tag of a network file.
pub const NETWORK_FORMAT: &str = "batten-network";
/// The newest network file version; files of a newer version are refused with a clear error.
pub const NETWORK_VERSION: u32 = 2;

/// The first version that holds tangent planes.
const PLANES_VERSION: u32 = 2;

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileOut {
    format: String,
    version: u32,
    #[serde(default)]
    name: String,
    curves: Vec<CurveRecord>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    tangent_planes: Vec<[f64; 4]>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct CurveRecord {
    name: String,
    #[serde(default)]
    role: Role,
    degree: usize,
    knots: Vec<f64>,
    points: Vec<[f64; 3]>,
    #[serde(default)]
    weights: Option<Vec<f64>>,
}

/// A network file as read: the curves kept as JSON values first, so that an error in one
/// names the curve (by index and name) rather than a line and column.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileIn {
    /// Checked by [`Header`] first; declared so that it is not an unknown field.
    #[serde(rename = "format")]
    _format: String,
    /// Checked by [`Header`] first.
    #[serde(rename = "version")]
    _version: u32,
    #[serde(default)]
    name: String,
    curves: Vec<serde_json::Value>,
    /// Version 2 on.
    #[serde(default)]
    tangent_planes: Option<Vec<serde_json::Value>>,
}

#[derive(Deserialize)]
struct Header {
    format: Option<String>,
    version: Option<u32>,
}

impl Network {
    /// The network as JSON text: format version 1, or 2 (the first to hold them) when it has
    /// tangent planes.
    pub fn to_json(&self) -> String {
        let planes = self.tangent_planes();
        let file = FileOut {
            format: NETWORK_FORMAT.to_owned(),
            version: if planes.is_empty() { 1 } else { PLANES_VERSION },
            name: self.name.clone(),
            tangent_planes: planes.iter().map(TangentPlane::to_array).collect(),
            curves: self
                .curves()
                .iter()
                .map(|c| CurveRecord {
                    name: c.name.clone(),
                    role: c.role,
                    degree: c.curve.degree(),
                    knots: c.curve.knots().to_vec(),
                    points: c
                        .curve
                        .control_points()
                        .iter()
                        .map(|p| p.to_array())
                        .collect(),
                    weights: c.curve.weights(),
                })
                .collect(),
        };
        serde_json::to_string_pretty(&file).expect("a network always serialises")
    }

    /// Read a network from JSON text, validating every curve and tangent plane; an error names
    /// the curve or the plane.
    pub fn from_json(text: &str) -> Result<Network, Error> {
        // A byte-order mark is not JSON, but editors write one.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let header: Header = serde_json::from_str(text)
            .map_err(|e| Error::Format(format!("not valid JSON ({e})")))?;
        if header.format.as_deref() != Some(NETWORK_FORMAT) {
            return Err(Error::Format(format!(
                "not a batten network (expected \"format\": \"{NETWORK_FORMAT}\")"
            )));
        }
        let version = match header.version {
            Some(v) if (1..=NETWORK_VERSION).contains(&v) => v,
            Some(v) if v > NETWORK_VERSION => {
                return Err(Error::Format(format!(
                    "version {v} is newer than this batten reads ({NETWORK_VERSION})"
                )))
            }
            Some(v) => {
                return Err(Error::Format(format!(
                    "version {v} is not a batten network version (versions start at 1)"
                )))
            }
            None => return Err(Error::Format("missing \"version\"".to_owned())),
        };
        let file: FileIn = serde_json::from_str(text).map_err(|e| Error::Format(e.to_string()))?;
        let curves = file
            .curves
            .into_iter()
            .enumerate()
            .map(|(i, v)| {
                let named = match v.get("name").and_then(|n| n.as_str()) {
                    Some(n) => format!("curve {i} ('{n}')"),
                    None => format!("curve {i}"),
                };
                let r: CurveRecord = serde_json::from_value(v)
                    .map_err(|e| Error::Format(format!("{named}: {e}")))?;
                let points = r.points.iter().map(|p| DVec3::from_array(*p)).collect();
                NurbsCurve::try_new(r.degree, r.knots, points, r.weights)
                    .map(|curve| NetworkCurve {
                        name: r.name.clone(),
                        role: r.role,
                        curve,
                    })
                    .map_err(|e| e.named(r.name))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let planes = match file.tangent_planes {
            Some(_) if version < PLANES_VERSION => {
                return Err(Error::Format(format!(
                    "\"tangent_planes\" needs version {PLANES_VERSION} or newer, the file says \
                     {version}"
                )))
            }
            Some(planes) => planes
                .into_iter()
                .enumerate()
                .map(|(i, v)| {
                    let [nx, ny, nz, offset]: [f64; 4] =
                        serde_json::from_value(v).map_err(|e| {
                            Error::Format(format!(
                                "tangent plane {i}: {e} (a plane is [nx, ny, nz, offset])"
                            ))
                        })?;
                    TangentPlane::try_new(DVec3::new(nx, ny, nz), offset)
                        .map_err(|e| Error::Format(format!("tangent plane {i}: {e}")))
                })
                .collect::<Result<Vec<_>, _>>()?,
            None => Vec::new(),
        };
        Ok(Network::try_new(file.name, curves)?.with_tangent_planes(planes))
    }
}
