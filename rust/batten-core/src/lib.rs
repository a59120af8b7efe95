//! batten-core: the geometry of batten, a hull-design tool that turns a network of designer curves
//! into a smooth multi-patch surface.
//!
//! This crate knows nothing of Python or Blender. It holds the curve kernel (B-spline and NURBS
//! curves with derivatives, knot insertion, splitting, arc length, closest points, bounding boxes),
//! the model tolerance, typed errors and the versioned JSON format for curve networks.
//!
//! The public API is flat: every type is re-exported here and the modules stay private.

mod adjacency;
mod curve;
mod defaults;
mod diagnostic;
mod error;
mod export;
mod fair;
mod form;
mod hull;
mod hydro;
mod hydro_transform;
mod network;
mod patch;
mod sections;
mod surface_fair;
mod tolerance;
mod topo;
mod union_find;
mod wireframe;

pub use curve::{
    Aabb, BezierDecomposition, CurveDerivs, CurveError, KnotLayout, Nearest, NurbsCurve, MAX_DEGREE,
};
pub use defaults::{
    DEFAULT_CORNER_ANGLE_DEGREES, DEFAULT_FAIR_DEGREE, DEFAULT_FAIR_TOLERANCE,
    DEFAULT_PARAMETER_ITERATIONS, DEFAULT_RESOLUTION, DEFAULT_SECTION_MODEL_TOLERANCE,
    DEFAULT_SECTION_TOLERANCE, DEFAULT_TOLERANCE, MAX_RESOLUTION, SECTION_CAPTURE_FACTOR,
};
pub use diagnostic::Diagnostic;
pub use error::Error;
pub use export::{
    cad_surface, cad_surface_with, iges_text, step_text, BsplineSurface, CadFace, CadHeader,
    CadSurface, ExportError, ExportOptions, Timestamp, UnfittedFace, UnfittedFaces, BOUNDARY_SHARE,
    DEFAULT_EXPORT_TOLERANCE, EXPORT_DEGREE, FACE_SHARE, KNOT_MERGE, MAX_CURVE_SPANS,
    MAX_SURFACE_CELLS, MAX_SURFACE_SPANS,
};
pub use fair::{
    corner_indices, curvature_variation, fair_points, fairness_metrics, FairError, FairOptions,
    FairReport, FairedCurve, FairnessMetrics, FlatEnd, FlatPlane, PieceReport, Smoothing,
    EXTREMUM_THRESHOLD, INFLECTION_THRESHOLD, MAX_FAIR_DEGREE, MIN_FLAT_RUN,
};
pub use form::{
    form_topology, Bilge, EdgeKind, FaceBulge, FormEdge, FormError, FormFace, FormOptions,
    FormParameters, FormPlane, FormTopology, FormVertex, ParallelMiddleBody, Plan, PlaneKind,
    Target, Transformed, VertexMove, BLEND_TANGENT_DEGREES,
};
pub use form::{parametric_moves, transform, transform_bulged, transform_to};
pub use hull::{
    build_hull, FaceError, HullOptions, HullReport, HullSurface, KnuckleEdge, KnuckleSource,
    LiveHull, Rebuild, VertexCurvature, Warning, WarningKind, BOX_SLACK, FOLD_ANGLE_DEGREES,
    KNUCKLE_EDGE_SAMPLES, KNUCKLE_POINT_ANGLE_DEGREES,
};
pub use hydro::{
    default_datums, float_to, hydrostatics, immersed_section_area, is_port_half, level_draft,
    sectional_areas, CellDensity, Datums, Flotation, HullGeometry, HydroError, Hydrostatics,
    OpenChain, PatchHydroModel, SectionArc, SectionSegment, TriangleHull, Waterplane, WetIntegrals,
    CAP_FLATNESS_RELATIVE, CENTREPLANE_RELATIVE, CENTREPLANE_TOLERANCE_RELATIVE,
    ENTRANCE_FIT_FRACTION, HALF_HULL_SLACK, SEA_WATER_DENSITY, SECTION_TOLERANCE_RELATIVE,
};
pub use hydro_transform::{
    transform_hydrostatic, Explored, HydroTargets, HydroTransformOptions, HydroTransformed,
    PmbHold, Stop, VolumeTarget, LCB_TOLERANCE, MAX_BULGE_FRACTION, MAX_EVALUATIONS,
    MIN_LENGTH_FRACTION, VOLUME_TOLERANCE,
};
pub use network::{
    Incidence, Junction, Junctions, Network, NetworkCurve, Role, TangentPlane, NETWORK_FORMAT,
    NETWORK_VERSION,
};
pub use patch::{
    gram_schmidt_cross_tangent, tessellate_patches, Domain, EdgeNormal, FaceBoundary, Patch,
    PatchError, PatchKind, PatchOptions, PatchWarning, RibbonNode, Side, SideParam, SideRibbon,
    SideSegment, SurfaceCurvature, SurfaceMesh, MAX_SIDES, MIN_CORNER_ANGLE_DEGREES,
    MIN_CROSSING_ANGLE_DEGREES,
};
pub use sections::{
    knuckle_lines, KnuckleLine, SectionModel, SectionPlane, SectionPolyline, DEFAULT_CUT_TOLERANCE,
};
pub use surface_fair::{
    fair_sections, fair_sections_with, section_noise, HullFairness, SectionFairness, SectionFamily,
    SectionFilter, SectionReport, SurfaceFairOptions, SurfaceFairReport, SurfaceFairing,
    DEFAULT_BIAS_SHARE, DEFAULT_FIXED_ROLES, DEFAULT_SMOOTHING_PER_TOLERANCE,
    DEFAULT_SURFACE_FAIR_ROUNDS, DEFAULT_SURFACE_FAIR_TOLERANCE,
};
pub use tolerance::{InvalidTolerance, Tolerance};
pub use topo::{
    BoundaryLoop, Brep, Edge, EdgeFacesError, EdgeId, EulerPoincareError, Face, FaceId, FaceSide,
    HalfEdge, HalfEdgeId, Loop, LoopId, NextPrevError, NodeKind, Shell, ShellId, TopoFace,
    Topology, TwinError, ValidationError, Vertex, VertexId, BRANCHING_TIP_DISTANCE,
    CORNER_ANGLE_DEGREES, MAX_NORMAL_CORNERS, MIN_CORNERS,
};
pub use wireframe::{
    chines_from_knuckles, nodes_from_data, snap_to_nodes, CurveSnap, DataNode, NodedPoints,
    SmoothNodeReport, SnapData, SnappedNetwork, MAX_TANGENT_TURN_DEGREES,
};
