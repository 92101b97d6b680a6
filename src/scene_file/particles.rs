//! `[particles]`: a room's diameters or its size distribution (lognormal `modes`, or
//! measured size classes in a CSV file), their counts and target error; a channel's `tau+`.

use std::path::Path;

use depo_tracker::distribution::{Amount, Distribution, Median, Mode, Quantity, SizeClass, DEFAULT_BINS};
use depo_tracker::Air;
use serde::Deserialize;
use toml::Spanned;

use super::{Error, SceneSource};
use crate::csv_input::{at_line, CsvInput};

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RoomParticles {
    pub(super) diameters: Option<Vec<f64>>,
    pub(super) count: Option<usize>,
    /// 0 turns the target off.
    pub(super) target_error: Option<f64>,
    pub(super) max_count: Option<usize>,
    pub(super) density: Option<f64>,
    /// A size distribution instead of `diameters`: lognormal modes...
    pub(super) modes: Option<Spanned<Vec<Spanned<ModeFile>>>>,
    /// ... cut into this many bins in ln d ...
    pub(super) bins: Option<Spanned<usize>>,
    /// ... over this range (m).
    pub(super) bin_range: Option<Spanned<[f64; 2]>>,
    /// Or measured size classes: a CSV file, relative to the scene file.
    pub(super) size_bins: Option<Spanned<String>>,
}

/// One lognormal mode of `particles.modes`.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct ModeFile {
    pub(super) count_median: Option<f64>,
    pub(super) mass_median: Option<f64>,
    pub(super) geometric_sd: Option<f64>,
    pub(super) density: Option<f64>,
    pub(super) number_share: Option<f64>,
    pub(super) mass_share: Option<f64>,
    pub(super) number_concentration: Option<f64>,
    pub(super) mass_concentration: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct ChannelParticles {
    pub(super) tau_plus: Option<Vec<f64>>,
    pub(super) count: Option<usize>,
    pub(super) excursion_count: Option<usize>,
    /// 0 turns the target off.
    pub(super) target_error: Option<f64>,
    pub(super) max_factor: Option<f64>,
    pub(super) density: Option<f64>,
}

/// Bins holding less of the modes' mass than this are an error: the answers would be of a
/// sliver of the distribution.
pub(super) const MIN_BINNED_SHARE: f64 = 0.5;

/// Bins holding less of the modes' mass than this are warned of.
pub(super) const WARN_BINNED_SHARE: f64 = 0.99;

/// The size distribution of a room scene's `[particles]`: its `modes` or its `size_bins`
/// file, or none. A mode's density defaults to `particles.density`, and its amount to a share
/// of 1 (of number for a count median, of mass for a mass median). Errors name the file, the
/// line and the key.
/// A size-classes file is read from `dir`; `(density, air)` are the study's; a warning goes
/// into `warnings`.
pub(super) fn distribution(
    dir: &Path,
    src: &SceneSource,
    particles: &RoomParticles,
    (density, air): (f64, &Air),
    warnings: &mut Vec<String>,
) -> Result<Option<Distribution>, Error> {
    let at = |offset: usize, message: String| src.at_offset(offset, message);
    if let (Some(modes), Some(bins)) = (&particles.modes, &particles.size_bins) {
        let later = modes.span().start.max(bins.span().start);
        return Err(at(later, "give `particles.modes` or `particles.size_bins`, not both".into()));
    }
    let given =
        particles.modes.as_ref().map(|m| m.span().start).or(particles.size_bins.as_ref().map(|b| b.span().start));
    let Some(offset) = given else {
        for (key, span) in [
            ("particles.bins", particles.bins.as_ref().map(|b| b.span().start)),
            ("particles.bin_range", particles.bin_range.as_ref().map(|b| b.span().start)),
        ] {
            if let Some(s) = span {
                return Err(at(s, format!("`{key}` needs a size distribution, `particles.modes`")));
            }
        }
        return Ok(None);
    };
    if particles.diameters.is_some() {
        return Err(at(offset, "give `particles.diameters` or a size distribution, not both".into()));
    }
    let distribution = if let Some(modes) = &particles.modes {
        let mut parsed = Vec::new();
        for (i, mode) in modes.get_ref().iter().enumerate() {
            let key = |k: &str| format!("`particles.modes[{i}].{k}`");
            let m = mode.get_ref();
            let line_at = |message: String| at(mode.span().start, message);
            let median = match (m.count_median, m.mass_median) {
                (Some(d), None) => Median::Count(d),
                (None, Some(d)) => Median::Mass(d),
                (Some(_), Some(_)) => {
                    return Err(line_at(format!("{} or {}, not both", key("count_median"), key("mass_median"))))
                }
                (None, None) => {
                    return Err(line_at(format!("{} or {} is needed", key("count_median"), key("mass_median"))))
                }
            };
            let amounts = [
                m.number_share.map(Amount::NumberShare),
                m.mass_share.map(Amount::MassShare),
                m.number_concentration.map(Amount::NumberConcentration),
                m.mass_concentration.map(Amount::MassConcentration),
            ];
            let mut given = amounts.into_iter().flatten();
            let amount = match (given.next(), given.next()) {
                (Some(a), None) => a,
                (None, _) => match median {
                    Median::Count(_) => Amount::NumberShare(1.0),
                    Median::Mass(_) => Amount::MassShare(1.0),
                },
                (Some(_), Some(_)) => {
                    return Err(line_at(format!(
                        "{}: give one of `number_share`, `mass_share`, `number_concentration`, `mass_concentration`",
                        key("*")
                    )))
                }
            };
            let geometric_sd = m.geometric_sd.ok_or_else(|| line_at(format!("{} is needed", key("geometric_sd"))))?;
            parsed.push(Mode { median, geometric_sd, density: m.density.unwrap_or(density), amount });
        }
        let bins = particles.bins.as_ref().map_or(DEFAULT_BINS, |b| *b.get_ref());
        let range = particles.bin_range.as_ref().map(|r| *r.get_ref());
        let distribution = Distribution::Modes { modes: parsed, bins, range };
        distribution.validate().map_err(|e| {
            // The line of the mode the error names, or of the key.
            let index: Option<usize> =
                e.field.strip_prefix("modes[").and_then(|rest| rest.split(']').next()).and_then(|i| i.parse().ok());
            let offset = match (index, e.field.as_str()) {
                (Some(i), _) => modes.get_ref()[i].span().start,
                (None, "bins") => particles.bins.as_ref().map_or(offset, |b| b.span().start),
                (None, "bin_range") => particles.bin_range.as_ref().map_or(offset, |b| b.span().start),
                _ => offset,
            };
            if e.field == "modes" {
                // The modes together: their count is no value of theirs.
                at(offset, format!("`particles.modes`: {}", e.requirement))
            } else {
                at(offset, format!("`particles.{}` = {} {}", e.field, e.value, e.requirement))
            }
        })?;
        distribution
    } else {
        let name = particles.size_bins.as_ref().expect("given");
        if let Some(b) =
            particles.bins.as_ref().map(|b| b.span().start).or(particles.bin_range.as_ref().map(|b| b.span().start))
        {
            return Err(at(
                b,
                "`particles.bins` and `particles.bin_range` are for `particles.modes`; a size_bins file has its own"
                    .into(),
            ));
        }
        let file = dir.join(name.get_ref());
        Distribution::Classes(
            size_classes(&file, density).map_err(|e| at(name.span().start, format!("`particles.size_bins`: {e}")))?,
        )
    };
    let (bins, outside) = distribution
        .bins(air)
        .map_err(|e| at(offset, format!("`particles.{}` = {} {}", e.field, e.value, e.requirement)))?;
    // Modes the bins miss: their mass is left out of every answer.
    let inside: f64 = bins.iter().map(|b| b.mass).sum();
    let binned = inside / (inside + outside);
    let range = particles.bin_range.as_ref().map_or(offset, |r| r.span().start);
    if binned < MIN_BINNED_SHARE {
        return Err(at(
            range,
            format!(
                "the bins hold {:.3} % of the modes' mass, less than the {} % needed: widen `particles.bin_range`",
                100.0 * binned,
                100.0 * MIN_BINNED_SHARE
            ),
        ));
    }
    if binned < WARN_BINNED_SHARE {
        warnings.push(format!(
            "warning: {}: the bins hold {:.1} % of the modes' mass; the rest is left out of the mass balance",
            src.name,
            100.0 * binned
        ));
    }
    Ok(Some(distribution))
}

/// How far (relative to the first step) the steps in `ln d` between a CSV's midpoints may
/// differ: instruments' midpoints are rounded to a few digits.
pub(super) const MIDPOINT_SPACING: f64 = 0.02;

/// The size classes of a CSV file: a header naming the edges (`lower` and `upper`, m, or
/// `lower_um` and `upper_um`) or the midpoints (`diameter` or `diameter_um`, at least two, in
/// increasing order and evenly spaced in `ln d`: edges at the geometric means between them), and `number` (1/m^3) or
/// `mass` (kg/m^3) per class; a `density` column (kg/m^3) is optional, `density` standing in.
/// `#` starts a comment.
pub(super) fn size_classes(path: &Path, density: f64) -> Result<Vec<SizeClass>, Error> {
    let mut file = CsvInput::open(path)?;
    let name = file.name().to_string();
    // A column in m or in um.
    let sized = |key: &str| {
        file.column(key)
            .map(|c| (c, 1.0, key.to_string()))
            .or_else(|| file.column(&format!("{key}_um")).map(|c| (c, 1e-6, format!("{key}_um"))))
    };
    let edges = match (sized("lower"), sized("upper"), sized("diameter")) {
        (Some(lo), Some(hi), None) => Ok((lo, hi)),
        (None, None, Some(mid)) => Err(mid),
        _ => {
            return Err(
                file.header_error("the header must name `lower` and `upper` or `diameter` (in m, or with `_um`)")
            )
        }
    };
    let (amount, quantity) = match (file.column("number"), file.column("mass")) {
        (Some(c), None) => (c, Quantity::Number),
        (None, Some(c)) => (c, Quantity::Mass),
        _ => return Err(file.header_error("the header must name `number` or `mass`, one of them")),
    };
    let density_column = file.column("density");
    let mut rows = Vec::new();
    for row in file.rows()? {
        let (a, b) = match &edges {
            Ok(((lo, kl, nl), (hi, kh, nh))) => (row.number(*lo, nl)? * kl, row.number(*hi, nh)? * kh),
            Err((mid, k, n)) => {
                let d = row.number(*mid, n)? * k;
                (d, d)
            }
        };
        let rho = match density_column {
            Some(c) => row.number(c, "density")?,
            None => density,
        };
        let what = if quantity == Quantity::Number { "number" } else { "mass" };
        let class = SizeClass { lower: a, upper: b, amount: row.number(amount, what)?, quantity, density: rho };
        rows.push((row.line, class));
    }
    if let Err((_, _, key)) = &edges {
        // Midpoints: edges halfway in ln d, the outer ones as far out as the inner ones.
        if rows.len() < 2 {
            return Err(format!("{name}: `{key}` gives midpoints: at least two classes are needed"));
        }
        for w in rows.windows(2) {
            if w[1].1.lower <= w[0].1.lower {
                return Err(at_line(&name, w[1].0, &format!("`{key}` must increase from row to row")));
            }
        }
        let mids: Vec<f64> = rows.iter().map(|r| r.1.lower).collect();
        // Each class runs at the geometric mean of its edges: that is its given midpoint only
        // where the midpoints are evenly spaced in ln d (to rounding).
        let step = (mids[1] / mids[0]).ln();
        for (i, w) in mids.windows(2).enumerate().skip(1) {
            if ((w[1] / w[0]).ln() / step - 1.0).abs() > MIDPOINT_SPACING {
                return Err(at_line(
                    &name,
                    rows[i + 1].0,
                    &format!(
                        "`{key}` must be evenly spaced in ln d (ratio {} here, {} at first); \
                         give uneven classes by their edges, `lower` and `upper`",
                        w[1] / w[0],
                        mids[1] / mids[0]
                    ),
                ));
            }
        }
        let n = mids.len();
        let inner: Vec<f64> = mids.windows(2).map(|w| (w[0] * w[1]).sqrt()).collect();
        for (i, (_, class)) in rows.iter_mut().enumerate() {
            class.lower = if i == 0 { mids[0] * mids[0] / inner[0] } else { inner[i - 1] };
            class.upper = if i == n - 1 { mids[n - 1] * mids[n - 1] / inner[n - 2] } else { inner[i] };
        }
    }
    let classes: Vec<SizeClass> = rows.iter().map(|r| r.1).collect();
    Distribution::Classes(classes.clone()).validate().map_err(|e| {
        let row: Option<usize> =
            e.field.strip_prefix("size_bins[").and_then(|rest| rest.split(']').next()).and_then(|i| i.parse().ok());
        match row {
            Some(i) => at_line(
                &name,
                rows[i].0,
                &format!("{} = {} {}", e.field.split('.').next_back().unwrap_or(""), e.value, e.requirement),
            ),
            None => format!("{name}: the size classes {}", e.requirement),
        }
    })?;
    Ok(classes)
}
