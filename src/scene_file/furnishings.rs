//! `[[furnishings]]`: boxes in a room, each with its faces' behaviour.

use depo_tracker::furnishing::FACE_NAMES;
use depo_tracker::Furnishing;
use serde::Deserialize;
use toml::Spanned;

use super::walls::{wall_behaviour, WallFile};
use super::{Error, SceneSource};

/// One `[[furnishings]]` entry: a box and its faces' behaviour (the keys of a `[walls.*]`
/// table, for all faces or per face).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FurnishingFile {
    pub(super) name: Option<String>,
    pub(super) low: Spanned<[f64; 3]>,
    pub(super) high: Spanned<[f64; 3]>,
    pub(super) all: Option<WallFile>,
    pub(super) bottom: Option<WallFile>,
    pub(super) top: Option<WallFile>,
    pub(super) x0: Option<WallFile>,
    pub(super) x1: Option<WallFile>,
    pub(super) y0: Option<WallFile>,
    pub(super) y1: Option<WallFile>,
}

/// The `[[furnishings]]` of a room of `size` (m), checked: each box strictly inside the room
/// and above its `low` corner, none overlapping another; errors name the file, the line and
/// the key.
pub(super) fn furnishings(
    src: &SceneSource,
    entries: &[Spanned<FurnishingFile>],
    size: [f64; 3],
) -> Result<Vec<Furnishing>, Error> {
    let at = |offset: usize, message: String| src.at_offset(offset, message);
    let mut boxes: Vec<Furnishing> = Vec::new();
    for (k, entry) in entries.iter().enumerate() {
        let f = entry.get_ref();
        let (low, high) = (*f.low.get_ref(), *f.high.get_ref());
        for a in 0..3 {
            let axis = ["x", "y", "z"][a];
            if !(low[a].is_finite() && low[a] > 0.0 && low[a] < size[a]) {
                return Err(at(
                    f.low.span().start,
                    format!(
                        "`furnishings[{k}].low` {axis} = {} must lie strictly inside the room (0 to {} m)",
                        low[a], size[a]
                    ),
                ));
            }
            if !(high[a].is_finite() && high[a] > low[a] && high[a] < size[a]) {
                return Err(at(
                    f.high.span().start,
                    format!(
                        "`furnishings[{k}].high` {axis} = {} must lie above `low` and strictly inside the room (below {} m)",
                        high[a], size[a]
                    ),
                ));
            }
        }
        let mut furnishing = Furnishing::new(low, high);
        furnishing.name = f.name.clone();
        if let Some(other) = boxes.iter().position(|b| b.overlaps(&furnishing)) {
            return Err(at(entry.span().start, format!("`furnishings[{k}]` overlaps `furnishings[{other}]`")));
        }
        if let Some(all) = &f.all {
            furnishing.faces = [wall_behaviour(src, &format!("furnishings[{k}].all"), all)?; 6];
        }
        for (face, file) in [&f.bottom, &f.top, &f.x0, &f.x1, &f.y0, &f.y1].into_iter().enumerate() {
            if let Some(file) = file {
                let prefix = format!("furnishings[{k}].{}", FACE_NAMES[face]);
                furnishing.faces[face] = wall_behaviour(src, &prefix, file)?;
            }
        }
        boxes.push(furnishing);
    }
    Ok(boxes)
}
