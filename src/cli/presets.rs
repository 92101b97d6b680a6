//! `depo presets`: the paper's Table 1 as depo ships it.

use clap::Args;
use depo::wall_model::{WallLaw, PRESETS};
use serde::Serialize;

use super::{print_csv_rows, Error, Format};

#[derive(Args, Debug)]
pub struct PresetsArgs {
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    format: Format,
}

/// One preset as printed; the JSON keys are stable.
#[derive(Serialize)]
struct Row {
    id: &'static str,
    source: &'static str,
    particle: &'static str,
    surface: &'static str,
    k: f64,
    kappa: f64,
    vc: f64,
    p: f64,
    q: f64,
    mu: f64,
    /// R(vc) for vc > 0.
    restitution_at_vc: Option<f64>,
    /// The table's last column as printed (R(vc), or R(vc)^2 for sim-35um).
    table_last_column: Option<f64>,
    reconstructed: bool,
}

pub fn run(args: &PresetsArgs) -> Result<(), Error> {
    let rows: Vec<Row> = PRESETS
        .iter()
        .map(|p| {
            let lp = p.params;
            let law = WallLaw::new(lp).expect("presets are valid");
            Row {
                id: p.id,
                source: p.source,
                particle: p.particle,
                surface: p.surface,
                k: lp.k1,
                kappa: lp.kappa1,
                vc: lp.vc,
                p: lp.p,
                q: lp.q,
                mu: lp.mu,
                restitution_at_vc: (lp.vc > 0.0).then(|| law.restitution(lp.vc)),
                table_last_column: p.last_column,
                reconstructed: p.reconstructed,
            }
        })
        .collect();
    match args.format {
        Format::Json => out!("{}", serde_json::to_string_pretty(&rows).map_err(|e| e.to_string())?),
        Format::Csv => print_csv_rows(&rows)?,
        Format::Table => {
            out!(
                "{:<21} {:>7} {:>11} {:>8} {:>4} {:>6} {:>6}  {:<34} {:<30} source",
                "id",
                "k (m/s)",
                "kappa (m/s)",
                "vc (m/s)",
                "q",
                "R(vc)",
                "table",
                "particle",
                "surface"
            );
            for r in &rows {
                let opt = |x: Option<f64>| x.map(|v| format!("{v:.3}")).unwrap_or_else(|| "-".into());
                out!(
                    "{:<21} {:>7.1} {:>11.3} {:>8.3} {:>4} {:>6} {:>6}  {:<34} {:<30} {}",
                    r.id,
                    r.k,
                    r.kappa,
                    r.vc,
                    r.q,
                    opt(r.restitution_at_vc),
                    opt(r.table_last_column),
                    r.particle,
                    r.surface,
                    r.source,
                );
            }
            out!(
                "q, R(vc) and table (Table 1's last column) are pure numbers; p = 1 and mu = 0 for every preset (the paper gives no friction coefficient)."
            );
        }
    }
    Ok(())
}
