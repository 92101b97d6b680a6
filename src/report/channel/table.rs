//! `depo channel`'s text table: a line per `tau+` beside Wood and Papavergos & Hedley, and its
//! notes; with both near-wall models, Code_Saturne's own results after them.

use depo_tracker::studies::CHANNEL_SWEEPS;

use super::peer::{peer_points, PeerPoint, PEER_MODELS};
use super::ChannelRun;
use crate::report::{outln, ERROR_NOTE};
use crate::text::shown;

/// The table of `run`, each line ended, as `depo channel` prints it.
pub fn table(run: &ChannelRun) -> String {
    let mut text = String::new();
    let o = &mut text;
    let seconds = run.seconds;
    let study = &run.study;
    let rows = &run.rows;
    let (u_star, re_tau) = (run.friction_velocity, run.re_tau);
    let steps: u64 = rows.iter().map(|r| r.particle_steps).sum();
    let more = match study.target_error {
        Some(target) => format!(
            ", up to {} times as many where V+ needs them for a {:.0} % error",
            shown(study.max_factor),
            100.0 * target
        ),
        None => String::new(),
    };
    match study.scene.wall_function {
        Some(wf) => outln!(
            o,
            "Turbulent channel, u* = {} m/s, Re_tau = {re_tau:.0}, {} particles per tau+{more}; V+ = v_d / u*; wall function: within {} wall units of a wall, deposition at the rate of {} (V+ = the correlation's times C_w/C, the layer's concentration over the mean)",
            shown(u_star),
            study.count,
            shown(wf.layer_plus),
            wf.correlation.name()
        ),
        None => outln!(
            o,
            "Turbulent channel, u* = {} m/s, Re_tau = {re_tau:.0}, {} particles per tau+ ({} below tau+ {} with excursions){more}; V+ = v_d / u*",
            shown(u_star),
            study.count,
            study.excursion_count,
            shown(study.excursions_below)
        ),
    }
    outln!(
        o,
        "{:>8} {:>9} {:>9}  {:>28}  {:>9} {:>9} {:>7} {:>8} {:>9}  method",
        "tau+",
        "d (um)",
        "Sc",
        "V+ (depo) [deposits]",
        "Wood",
        "P&H",
        "ratio",
        "band",
        "particles"
    );
    for r in rows {
        let method = match (r.excursions_truncated, &r.layer_concentration) {
            (Some(t), _) if t > 1e-3 => format!("{} ({:.1} %)", r.method, 100.0 * t),
            (_, Some(c)) => format!("{} (C_w/C {:.2} +- {:.2})", r.method, c.value, c.error),
            _ => r.method.to_string(),
        };
        let ratio = if r.v_plus.upper_bound.is_some() { "-".to_string() } else { format!("{:.2}", r.ratio_to_wood) };
        let flag = if r.unresolved { "*" } else { " " };
        outln!(
            o,
            "{:>8} {:>9.3} {:>9.2e}  {:>28}{flag} {:>9.2e} {:>9.2e} {:>7} {:>8} {:>9}  {method}",
            tau_plus_cell(r.tau_plus),
            r.diameter_um,
            r.schmidt,
            r.v_plus.cell(),
            r.wood,
            r.papavergos_hedley,
            ratio,
            band_cell(r.band_factor),
            r.particles
        );
    }
    outln!(o, "ratio = depo / Wood. band: within the band between Wood and P&H, or the factor to its nearer edge. {ERROR_NOTE}");
    let below: Vec<f64> =
        rows.iter().filter(|r| r.band_factor.is_some_and(|f| f < 1.0 / BAND_FACTOR)).map(|r| r.tau_plus).collect();
    if below.iter().any(|t| (0.2..=5.0).contains(t)) {
        outln!(
            o,
            "! below the band by more than a factor 2: in the diffusion-impaction regime (tau+ about 0.3-3) the near-wall model deposits too little, as continuous random walks are known to (docs/validation.md); --near-wall wall-function takes the layer's transfer from Wood's correlation instead."
        );
    } else if !below.is_empty() {
        outln!(o, "! below the band by more than a factor 2.");
    }
    if rows.iter().any(|r| r.band_factor.is_some_and(|f| f > BAND_FACTOR)) {
        outln!(o, "! above the band by more than a factor 2.");
    }
    if rows.iter().any(|r| r.method == "excursions+sweeps") {
        outln!(
            o,
            "\"+sweeps\": strong sweeps (the fluid's wall-ward velocity above {} standard deviations) anywhere in the channel start excursions too, where inertia lets them carry particles to the wall.",
            CHANNEL_SWEEPS.enter
        );
    }
    if let Some(target) = study.target_error.filter(|_| rows.iter().any(|r| r.unresolved)) {
        outln!(
            o,
            "* unresolved: no deposit event, or a relative standard error above the {:.0} % target that {} times the first particles would not reach.",
            100.0 * target,
            shown(study.max_factor)
        );
    }
    outln!(
        o,
        "Averages over the last {:.0} % of the run; {steps} particle-steps tracked (excursions not counted) in {seconds:.1} s.",
        100.0 * (1.0 - study.transient)
    );
    text
}

/// Code_Saturne's `V+` beside Wood, as measured in its channel case, each line ended.
pub fn peer_table() -> String {
    let mut text = String::new();
    let o = &mut text;
    outln!(
        o,
        "Code_Saturne 6.0.2 in a channel meshed with wall functions (k-epsilon, first cell at y+ 40, Re_tau 479, u* = 0.30 m/s; integrations/code_saturne), V+:"
    );
    outln!(
        o,
        "{:>8}  {:>26}  {:>26}  {:>26}  {:>9}",
        "tau+",
        "its deposition model",
        "no model",
        "depo's wall function",
        "Wood"
    );
    let columns: Vec<Vec<PeerPoint>> = PEER_MODELS.iter().map(|(m, _)| peer_points(m)).collect();
    for &(tau_plus, _, _, wood) in &columns[0] {
        let cell = |c: &[PeerPoint]| {
            c.iter().find(|p| p.0 == tau_plus).map_or("-".to_string(), |&(_, v, e, _)| format!("{v:.2e} +- {e:.1e}"))
        };
        outln!(
            o,
            "{:>8}  {:>26}  {:>26}  {:>26}  {:>9.2e}",
            tau_plus_cell(tau_plus),
            cell(&columns[0]),
            cell(&columns[1]),
            cell(&columns[2]),
            wood
        );
    }
    outln!(o, "The wall function's V+ there is Wood's times Code_Saturne's own wall-cell concentration over the mean, 1.3-1.9 (integrations/code_saturne/README.md).");
    text
}

/// How far outside the band between Wood and Papavergos & Hedley a `V+` may lie and still
/// agree with them: the factor 2 deposition models are judged by.
const BAND_FACTOR: f64 = 2.0;

/// The band column: `within`, or the factor to the band's nearer edge, marked `!` beyond
/// [`BAND_FACTOR`]; `-` with no deposit.
fn band_cell(factor: Option<f64>) -> String {
    match factor {
        None => "-".to_string(),
        Some(1.0) => "within".to_string(),
        Some(f) => format!("{}{f:.2}", if (1.0 / BAND_FACTOR..=BAND_FACTOR).contains(&f) { "" } else { "!" }),
    }
}

/// `tau+` for the table: three decimals from 0.01 up, two significant digits in exponent form
/// below (the diffusion regime's 1e-5 would otherwise read 0.000).
fn tau_plus_cell(tau_plus: f64) -> String {
    if tau_plus >= 0.01 {
        format!("{tau_plus:.3}")
    } else {
        format!("{tau_plus:.1e}")
    }
}

#[cfg(test)]
mod tests {
    use super::tau_plus_cell;

    #[test]
    fn small_tau_plus_reads_in_exponent_form() {
        assert_eq!(tau_plus_cell(1e-5), "1.0e-5");
        assert_eq!(tau_plus_cell(3e-3), "3.0e-3");
        assert_eq!(tau_plus_cell(0.01), "0.010");
        assert_eq!(tau_plus_cell(100.0), "100.000");
    }
}
