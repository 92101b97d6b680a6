//! `depo channel --format csv`: a row per `tau+`.

use super::ChannelRun;
use crate::report::csv_text;
use crate::Error;

/// The CSV of `run`, without the last line's end.
pub fn to_csv(run: &ChannelRun) -> Result<String, Error> {
    let rows = &run.rows;
    let header = [
        "tau_plus",
        "diameter_um",
        "schmidt",
        "v_plus",
        "v_plus_error",
        "deposits",
        "wood",
        "papavergos_hedley",
        "ratio_to_wood",
        "band_factor",
    ];
    csv_text(
        &header,
        rows.iter().map(|r| {
            [
                r.tau_plus.to_string(),
                r.diameter_um.to_string(),
                r.schmidt.to_string(),
                r.v_plus.value.to_string(),
                r.v_plus.error.to_string(),
                r.v_plus.events.to_string(),
                r.wood.to_string(),
                r.papavergos_hedley.to_string(),
                r.ratio_to_wood.to_string(),
                r.band_factor.map_or(String::new(), |f| f.to_string()),
            ]
        }),
    )
}
