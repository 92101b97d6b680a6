//! Code_Saturne 6.0.2's own Lagrangian deposition in a channel meshed with wall functions
//! (integrations/code_saturne/channel_case: its results as run there), for the table and the
//! figure.

/// Code_Saturne 6.0.2's own Lagrangian deposition in a channel meshed with wall functions
/// (integrations/code_saturne/channel_case: its results as run there).
const CODE_SATURNE_PEER: &str = include_str!("../../../integrations/code_saturne/channel_peer.csv");

/// One `tau+` of the peer's channel case: `tau+`, `V+`, its standard error and Wood's `V+`.
pub type PeerPoint = (f64, f64, f64, f64);

/// The peer's points for one `model` of its CSV (`guingo-minier`, `no-model`,
/// `depo-wall-function`).
pub fn peer_points(model: &str) -> Vec<PeerPoint> {
    let mut lines = CODE_SATURNE_PEER.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name);
    let (Some(t), Some(m), Some(v), Some(e), Some(w)) =
        (column("tau_plus"), column("model"), column("v_plus"), column("v_plus_error"), column("wood"))
    else {
        return Vec::new();
    };
    let number = |f: &[&str], i: usize| f.get(i)?.parse::<f64>().ok();
    lines
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|f| f.get(m) == Some(&model))
        .filter_map(|f| Some((number(&f, t)?, number(&f, v)?, number(&f, e)?, number(&f, w)?)))
        .collect()
}

/// The models of the peer's CSV with their names, in the table's and the figure's order.
pub const PEER_MODELS: [(&str, &str); 3] = [
    ("guingo-minier", "Code_Saturne 6.0.2, its deposition model (wall-function mesh)"),
    ("no-model", "Code_Saturne 6.0.2, deposition walls, no model"),
    ("depo-wall-function", "Code_Saturne 6.0.2 with depo's wall function (Wood)"),
];

#[cfg(test)]
mod tests {
    use super::{peer_points, PEER_MODELS};

    #[test]
    fn the_peer_s_stored_points_are_read_whole() {
        for (model, _) in PEER_MODELS {
            let points = peer_points(model);
            let tau_plus: Vec<f64> = points.iter().map(|p| p.0).collect();
            assert_eq!(tau_plus, [0.1, 0.3, 1.0, 3.0, 10.0, 30.0], "{model}");
            assert!(points.iter().all(|&(_, v, e, w)| v > 0.0 && e > 0.0 && w > 0.0), "{model}: {points:?}");
        }
        // Code_Saturne's own model: 2150 times Wood at tau+ 0.1, as its README says.
        let (_, v, _, wood) = peer_points("guingo-minier")[0];
        assert!((v / wood / 2150.0 - 1.0).abs() < 0.01, "{}", v / wood);
    }
}
