//! `[source]`: where the continuous source of the steady state enters the room: indoors
//! (over the room or a region of it), by infiltration, or through a supply opening.

use depo_tracker::steady::Source;
use depo_tracker::studies::RoomStudy;
use depo_tracker::OpeningKind;
use serde::Deserialize;

use super::{named, Error, SceneSource};
use crate::text::shown;

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct SourceFile {
    /// "indoor", "infiltration" or "supply".
    pub(super) enters: Option<String>,
    /// An indoor source's box: `[[x, y, z], [x, y, z]]`, its low and high corners (m).
    pub(super) region: Option<[[f64; 3]; 2]>,
    /// A supply source's opening: its index in `[[openings]]`.
    pub(super) opening: Option<usize>,
}

/// What `[source]` can name.
#[derive(Clone, Copy)]
enum Enters {
    Indoor,
    Infiltration,
    Supply,
}

/// The source `file` gives `study` (read after its openings and ventilation), checked against
/// the room; an error names the key the file wrote, and its line.
pub(super) fn apply_source(src: &SceneSource, study: &mut RoomStudy, file: &SourceFile) -> Result<(), Error> {
    let options = [("indoor", Enters::Indoor), ("infiltration", Enters::Infiltration), ("supply", Enters::Supply)];
    let Some(enters) = named(src, "source.enters", file.enters.as_deref(), &options)? else {
        if file.region.is_some() || file.opening.is_some() {
            let (key, enters) =
                if file.region.is_some() { ("source.region", "indoor") } else { ("source.opening", "supply") };
            return Err(src.at(&[key], format!("`{key}` needs `source.enters` = \"{enters}\"")));
        }
        return Ok(());
    };
    let scene = &study.scene;
    let size = scene.geometry.size();
    let written = file.enters.as_deref().unwrap_or_default();
    if file.region.is_some() && !matches!(enters, Enters::Indoor) {
        return Err(src.at(
            &["source.region"],
            format!("`source.region` places an indoor source: not with `source.enters` = \"{written}\""),
        ));
    }
    if file.opening.is_some() && !matches!(enters, Enters::Supply) {
        return Err(src.at(
            &["source.opening"],
            format!("`source.opening` names a supply opening: not with `source.enters` = \"{written}\""),
        ));
    }
    let supplies: Vec<usize> =
        scene.openings.iter().enumerate().filter(|(_, o)| o.kind == OpeningKind::Supply).map(|(k, _)| k).collect();
    let source = match enters {
        Enters::Indoor => match file.region {
            None => Source::Indoor(None),
            Some([low, high]) => {
                for a in 0..3 {
                    if !(0.0 <= low[a] && low[a] < high[a] && high[a] <= size[a]) {
                        return Err(src.at(
                            &["source.region"],
                            format!(
                                "`source.region` = [[{}], [{}]] must be a box inside the room ({} x {} x {} m), its \
                                 first corner below its second on every axis",
                                low.map(shown).join(", "),
                                high.map(shown).join(", "),
                                shown(size[0]),
                                shown(size[1]),
                                shown(size[2])
                            ),
                        ));
                    }
                }
                Source::Indoor(Some((low, high)))
            }
        },
        Enters::Infiltration => {
            if scene.exchange_rate() <= 0.0 {
                return Err(src.at(
                    &["source.enters"],
                    "`source.enters` = \"infiltration\" needs ventilation: `ventilation.air_changes_per_hour` or \
                     `[[openings]]`",
                ));
            }
            Source::Infiltration
        }
        Enters::Supply => match (file.opening, supplies.as_slice()) {
            (None, []) => {
                return Err(
                    src.at(&["source.enters"], "`source.enters` = \"supply\" needs a supply opening in `[[openings]]`")
                )
            }
            (None, [k]) => Source::Supply(*k),
            (None, _) => {
                return Err(src.at(
                    &["source.enters"],
                    format!(
                        "`source.enters` = \"supply\": say which supply opening with `source.opening` (one of {})",
                        supplies.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ")
                    ),
                ))
            }
            (Some(k), _) if supplies.contains(&k) => Source::Supply(k),
            (Some(k), _) => {
                let what = if k < scene.openings.len() {
                    format!("`openings[{k}]` is an exhaust")
                } else {
                    format!("the file has {} `[[openings]]`, numbered from 0", scene.openings.len())
                };
                return Err(
                    src.at(&["source.opening"], format!("`source.opening` = {k} is not a supply opening: {what}"))
                );
            }
        },
    };
    study.source = Some(source);
    Ok(())
}
