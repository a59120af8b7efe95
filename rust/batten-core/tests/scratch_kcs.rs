//! scratch
use batten_core::*;
#[test]
fn kcs() {
    let net = Network::from_json(&std::fs::read_to_string("/tmp/kcs_net.json").unwrap()).unwrap();
    let hull = build_hull(&net, &HullOptions::default()).unwrap();
    let m = hull.hydro_model(CellDensity::DEFAULT);
    let plane = Waterplane::level(2.9);
    for c in m.open_chains() {
        let zmin = c.points.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
        let ymax = c.points.iter().map(|p| p.y.abs()).fold(0.0, f64::max);
        println!(
            "chain {} pts closed {} zmin {zmin:.3} ymax {ymax:.4} first {:?} last {:?}",
            c.points.len(),
            c.closed,
            c.points[0],
            c.points[c.points.len() - 1]
        );
    }
    let _ = plane;
}
