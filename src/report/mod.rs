//! The studies' results and their reports: [`room`] and [`channel`] each run their study once
//! into a result ([`room::study`], [`channel::study`]), and render that one result as a text
//! table, JSON, CSV and SVG figures, each renderer in a module of its own that reads the result
//! and nothing else. The `depo` command prints what they render; a binding can do the same, or
//! read the result's fields.
//!
//! Imports go down only: a renderer uses its study's result and this module's shared pieces;
//! the results use the tracker and the scene reader ([`crate::scene_file`]).

pub mod channel;
pub mod room;

use depo_tracker::{Cancel, Estimate, WallTally};
use serde::Serialize;

/// Writes a line into a `String` report (writing to a `String` cannot fail).
macro_rules! outln {
    ($o:expr, $($arg:tt)*) => {{
        use std::fmt::Write as _;
        let _ = writeln!($o, $($arg)*);
    }};
}
pub(crate) use outln;

/// What a study tells its caller as it runs: a progress bar or a binding's callback; and the
/// token through which the caller may stop it.
pub trait Progress {
    /// A token the caller may cancel from another thread to stop the study: every run of the
    /// study watches it ([`Cancel::watch`]), and the study then ends with
    /// [`Error::Cancelled`](crate::Error::Cancelled) within a chunk of particles' time. `None`
    /// (the default): the study runs to its end.
    fn cancel(&self) -> Option<Cancel> {
        None
    }

    /// A study of `total` runs starts; `what` names them (`sizes`, `tau+`).
    fn start(&mut self, total: usize, what: &str) {
        let _ = (total, what);
    }
    /// `done` of the runs are complete.
    fn done(&mut self, done: usize) {
        let _ = done;
    }
    /// The study has ended.
    fn finish(&mut self) {}
}

/// No progress shown.
pub struct Silent;

impl Progress for Silent {}

/// CSV text: the header, then one record per row, each field quoted only where it needs it
/// (the `csv` crate's rules), without the last line's end. The caller formats its own
/// numbers.
pub fn csv_text<R>(header: &[&str], rows: impl IntoIterator<Item = R>) -> Result<String, crate::Error>
where
    R: IntoIterator,
    R::Item: AsRef<[u8]>,
{
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(header).map_err(|e| e.to_string())?;
    for row in rows {
        writer.write_record(row).map_err(|e| e.to_string())?;
    }
    let bytes = writer.into_inner().map_err(|e| e.to_string())?;
    let text = String::from_utf8(bytes).map_err(|e| e.to_string())?;
    Ok(text.trim_end_matches('\n').to_string())
}

/// A measured value with its standard error, the deposit events it rests on, and with no
/// event a 95 % upper bound.
#[derive(Serialize)]
pub struct Measured {
    pub value: f64,
    pub error: f64,
    pub events: usize,
    pub upper_bound: Option<f64>,
}

impl From<Estimate> for Measured {
    fn from(e: Estimate) -> Self {
        let upper_bound = (e.events == 0).then_some(e.upper_bound);
        Self { value: e.value, error: e.error, events: e.events, upper_bound }
    }
}

impl Measured {
    /// Back to the study's estimate (the upper bound, unused by the studies' rules, NaN where
    /// events were seen).
    pub fn estimate(&self) -> Estimate {
        let upper_bound = self.upper_bound.unwrap_or(f64::NAN);
        Estimate { value: self.value, error: self.error, events: self.events, upper_bound }
    }

    /// `value +- error [events]`, or `< bound [0]` when nothing deposited.
    pub fn cell(&self) -> String {
        match self.upper_bound {
            Some(bound) => format!("< {bound:.1e} [0]"),
            None => format!("{:.2e} +- {:.1e} [{}]", self.value, self.error, self.events),
        }
    }

    /// The same scaled by `k` (a change of unit).
    pub fn scaled(&self, k: f64) -> Self {
        Self {
            value: self.value * k,
            error: self.error * k,
            events: self.events,
            upper_bound: self.upper_bound.map(|b| b * k),
        }
    }
}

/// The note under a study's table: what its numbers mean.
pub const ERROR_NOTE: &str = "+- one standard error; [n] deposit events; with none, < the 95 % upper \
bound; \"excursions (x % at T s)\": deposits counted by near-wall excursions, x the weight given up at \
their longest duration T (--help says more).";

/// A run's wall-law tallies, summed over the surfaces; energy in J.
#[derive(Serialize)]
pub struct Tally {
    pub contacts: u64,
    pub rebounds: u64,
    pub captures: u64,
    pub resting: u64,
    pub energy_lost_material: f64,
    pub energy_lost_adhesion: f64,
    pub energy_lost_friction: f64,
    pub energy_deposited: f64,
}

impl From<WallTally> for Tally {
    fn from(t: WallTally) -> Self {
        Self {
            contacts: t.contacts,
            rebounds: t.rebounds,
            captures: t.captures,
            resting: t.resting,
            energy_lost_material: t.energy.material,
            energy_lost_adhesion: t.energy.adhesion,
            energy_lost_friction: t.energy.friction,
            energy_deposited: t.energy.deposition,
        }
    }
}

/// `n` log-spaced points from `from` to `to`; around `from` when the two are equal.
pub fn log_grid(from: f64, to: f64, n: usize) -> Vec<f64> {
    let (from, to) = if from < to { (from, to) } else { (from / 2.0, to * 2.0) };
    (0..n).map(|i| from * (to / from).powf(i as f64 / (n - 1) as f64)).collect()
}
