//! `depo room --format csv`: a row per size (with a size distribution, its mass balance, a
//! row per class: the per-size figures are in the JSON).

use super::{DistributionReport, Measured, RoomResult};
use crate::report::csv_text;
use crate::Error;

/// The CSV of `r`, without the last line's end.
pub fn to_csv(r: &RoomResult) -> Result<String, Error> {
    if let Some(d) = &r.distribution {
        return d.csv();
    }
    let study = &r.study;
    let rows = &r.rows;
    let ventilated = study.scene.exchange_rate() > 0.0;
    let furnished = !study.scene.furnishings.is_empty();
    let mut header = vec![
        "diameter_um",
        "floor",
        "floor_error",
        "floor_deposits",
        "floor_lai_nazaroff",
        "ceiling",
        "ceiling_error",
        "ceiling_deposits",
        "ceiling_lai_nazaroff",
        "walls",
        "walls_error",
        "walls_deposits",
        "walls_lai_nazaroff",
        "x0",
        "x0_error",
        "x0_deposits",
        "x1",
        "x1_error",
        "x1_deposits",
        "y0",
        "y0_error",
        "y0_deposits",
        "y1",
        "y1_error",
        "y1_deposits",
        "beta_per_hour",
        "beta_error",
        "beta_lai_nazaroff",
    ];
    // Without ventilation the indoor/outdoor columns are left out.
    if ventilated {
        header.extend(["indoor_outdoor", "indoor_outdoor_error"]);
    }
    let supply_filtered = rows.iter().any(|r| r.supply_filter_efficiency.is_some());
    if supply_filtered {
        header.push("supply_filter_efficiency");
    }
    let recirculated = rows.iter().any(|r| r.recirculation_filter_efficiency.is_some());
    if recirculated {
        header.push("recirculation_filter_efficiency");
    }
    header.extend([
        "beta_fitted_per_hour",
        "beta_fitted_error",
        "floor_share",
        "ceiling_share",
        "walls_share",
        "exhausted_share",
        "airborne_share",
        "floor_kg",
        "ceiling_kg",
        "walls_kg",
        "exhausted_kg",
        "airborne_kg",
    ]);
    // A furnished room adds, per furnishing, its deposition velocity onto all its faces,
    // onto its top, and its share of the release; and the surface-to-volume ratio.
    let names: Vec<String> = study.scene.furnishings.iter().enumerate().map(|(k, f)| f.label(k)).collect();
    let furnishing_columns: Vec<String> = names
        .iter()
        .flat_map(|n| {
            ["vd", "vd_error", "deposits", "top_vd", "top_vd_error", "share", "kg"].map(|c| format!("{n}_{c}"))
        })
        .collect();
    header.extend(furnishing_columns.iter().map(String::as_str));
    if furnished {
        header.extend(["furnishings_share", "surface_to_volume_per_m"]);
    }
    // Whether the room is well mixed for the size, and the steady state under the source.
    header.extend([
        "near_floor_over_mean",
        "near_floor_error",
        "well_mixed",
        "steady_residence_h",
        "steady_residence_error",
        "steady_near_floor_over_mean",
        "steady_near_floor_error",
        "steady_indoor_outdoor",
        "steady_indoor_outdoor_error",
    ]);
    let surface_to_volume = study.scene.surface_to_volume();
    csv_text(
        &header,
        rows.iter().map(|r| {
            let n = |m: &Measured| m.events.to_string();
            let x = |v: f64| v.to_string();
            // An absent figure (no decay fit, no steady state, no indoor/outdoor ratio) is a
            // pair of empty cells, not NaN.
            let pair = |m: Option<(f64, f64)>| m.map_or([String::new(), String::new()], |(v, e)| [x(v), x(e)]);
            let mut row = vec![
                x(r.diameter_um),
                x(r.floor.value),
                x(r.floor.error),
                n(&r.floor),
                x(r.lai_nazaroff.floor),
                x(r.ceiling.value),
                x(r.ceiling.error),
                n(&r.ceiling),
                x(r.lai_nazaroff.ceiling),
                x(r.walls.value),
                x(r.walls.error),
                n(&r.walls),
                x(r.lai_nazaroff.walls),
            ];
            for w in &r.each_wall {
                row.extend([x(w.velocity.value), x(w.velocity.error), n(&w.velocity)]);
            }
            row.extend([x(r.beta_per_hour.value), x(r.beta_per_hour.error), x(r.lai_nazaroff.beta_per_hour)]);
            if ventilated {
                row.extend(pair(r.indoor_outdoor.as_ref().map(|m| (m.value, m.error))));
            }
            if supply_filtered {
                row.push(x(r.supply_filter_efficiency.unwrap_or(0.0)));
            }
            if recirculated {
                row.push(x(r.recirculation_filter_efficiency.unwrap_or(0.0)));
            }
            // No decay fit (fewer than 3 sample times: every particle gone early): empty cells.
            row.extend(pair(r.decay_fit.as_ref().map(|f| (f.beta_per_hour.value, f.beta_per_hour.error))));
            let release = &r.release;
            row.extend(
                [&release.floor, &release.ceiling, &release.walls, &release.exhausted, &release.airborne]
                    .map(|s| x(s.share)),
            );
            row.extend(
                [&release.floor, &release.ceiling, &release.walls, &release.exhausted, &release.airborne]
                    .map(|s| x(s.kg)),
            );
            for f in &r.furnishings {
                row.extend([
                    x(f.all.value),
                    x(f.all.error),
                    n(&f.all),
                    x(f.top.value),
                    x(f.top.error),
                    x(f.deposited.share),
                    x(f.deposited.kg),
                ]);
            }
            if let Some(share) = &release.furnishings {
                row.extend([x(share.share), x(surface_to_volume)]);
            }
            let steady = r.steady.as_ref();
            row.extend(pair(r.near_floor_over_mean.map(|m| (m.value, m.error))));
            row.push(r.well_mixed.map_or(String::new(), |w| w.to_string()));
            row.extend(pair(steady.map(|st| (st.residence_h.value, st.residence_h.error))));
            row.extend(pair(steady.map(|st| (st.near_floor_over_mean.value, st.near_floor_over_mean.error))));
            row.extend(pair(steady.and_then(|st| st.indoor_outdoor.as_ref()).map(|m| (m.value, m.error))));
            row
        }),
    )
}

impl DistributionReport {
    /// The CSV: one row per class (all, PM10, PM2.5).
    pub(super) fn csv(&self) -> Result<String, Error> {
        // A furnished room's CSV has the furnishings' columns after the walls'.
        let mut parts = vec!["floor", "ceiling", "walls"];
        if self.furnished {
            parts.push("furnishings");
        }
        parts.extend(["airborne", "exhausted"]);
        let mut header = vec!["class".to_string(), "injected".to_string()];
        for p in parts {
            header.extend([
                p.to_string(),
                format!("{p}_error"),
                format!("{p}_quadrature"),
                format!("{p}_unseen_bound"),
            ]);
        }
        header.extend(["beta_per_hour".to_string(), "beta_error".to_string(), "beta_mass_share".to_string()]);
        let header: Vec<&str> = header.iter().map(String::as_str).collect();
        csv_text(
            &header,
            self.classes().into_iter().map(|(name, s)| {
                let mut row = vec![name.to_string(), s.injected.to_string()];
                let mut parts = vec![&s.floor, &s.ceiling, &s.walls];
                if self.furnished {
                    parts.push(&s.furnishings);
                }
                parts.extend([&s.airborne, &s.exhausted]);
                for p in parts {
                    row.extend([
                        p.value.to_string(),
                        p.error.to_string(),
                        p.quadrature.map_or(String::new(), |q| q.to_string()),
                        p.unseen_bound.to_string(),
                    ]);
                }
                let beta = s
                    .beta_per_hour
                    .as_ref()
                    .map_or([String::new(), String::new()], |b| [b.value.to_string(), b.error.to_string()]);
                row.extend(beta);
                row.push(s.beta_mass_share.to_string());
                row
            }),
        )
    }
}
