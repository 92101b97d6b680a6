//! `[[openings]]`: supply and exhaust openings on a room's walls.

use depo_tracker::openings;
use depo_tracker::{Geometry, Opening, OpeningKind};
use serde::Deserialize;
use toml::Spanned;

use super::{Error, SceneSource};

/// One `[[openings]]` entry: a supply or exhaust opening on a room wall.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct OpeningFile {
    /// "supply" or "exhaust".
    pub(super) kind: Spanned<String>,
    /// A wall's name: floor, ceiling, x0, x1, y0, y1.
    pub(super) wall: Spanned<String>,
    /// Centre in the wall's two in-plane coordinates, in the order x, y, z (m).
    pub(super) center: Spanned<[f64; 2]>,
    /// Extent along the same coordinates (m).
    pub(super) size: Spanned<[f64; 2]>,
    /// Volume flow through it, m^3/h.
    pub(super) flow_m3_per_hour: Spanned<f64>,
}

/// The `[[openings]]` of a room `geometry`, checked (each within its wall, none overlapping
/// another, supply and exhaust flows balanced); errors name the file, the line and the key.
pub(super) fn openings(
    src: &SceneSource,
    entries: &[Spanned<OpeningFile>],
    geometry: &Geometry,
) -> Result<Vec<Opening>, Error> {
    let at = |offset: usize, message: String| src.at_offset(offset, message);
    let walls = geometry.walls();
    let mut parsed = Vec::new();
    for (k, entry) in entries.iter().enumerate() {
        let o = entry.get_ref();
        let kind = match o.kind.get_ref().as_str() {
            "supply" => OpeningKind::Supply,
            "exhaust" => OpeningKind::Exhaust,
            other => {
                return Err(at(
                    o.kind.span().start,
                    format!("`openings[{k}].kind` = \"{other}\": expected \"supply\" or \"exhaust\""),
                ))
            }
        };
        let name = o.wall.get_ref();
        let Some(wall) = walls.iter().find(|w| w.name(geometry) == name) else {
            return Err(at(
                o.wall.span().start,
                format!("`openings[{k}].wall` = \"{name}\": expected floor, ceiling, x0, x1, y0 or y1"),
            ));
        };
        let flow = *o.flow_m3_per_hour.get_ref() / 3600.0;
        parsed.push(Opening { kind, wall: wall.id, center: *o.center.get_ref(), size: *o.size.get_ref(), flow });
    }
    openings::validate(&parsed, geometry).map_err(|e| {
        // The entry and the key the error names, in the file's terms.
        let index: Option<usize> =
            e.field.strip_prefix("openings[").and_then(|rest| rest.split(']').next()).and_then(|i| i.parse().ok());
        match index {
            // The entry as a whole: it overlaps the one the value numbers.
            Some(k) if !e.field.contains('.') => at(
                entries[k].span().start,
                format!("`openings[{k}]` overlaps `openings[{}]` on the same wall", e.value),
            ),
            Some(k) => {
                let o = entries[k].get_ref();
                let key = e.field.rsplit('.').next().unwrap_or("");
                let (offset, key, value) = match key {
                    "flow" => (o.flow_m3_per_hour.span().start, "flow_m3_per_hour", e.value * 3600.0),
                    "size" => (o.size.span().start, "size", e.value),
                    "center" => (o.center.span().start, "center", e.value),
                    _ => (entries[k].span().start, key, e.value),
                };
                at(offset, format!("`openings[{k}].{key}` = {value} {}", e.requirement))
            }
            None => {
                let offset = entries.first().map_or(0, |e| e.span().start);
                if e.requirement.starts_with("must balance") {
                    let (supply, exhaust) = (openings::supply_flow(&parsed), openings::exhaust_flow(&parsed));
                    at(
                        offset,
                        format!(
                            "`openings`: the supply flows ({} m^3/h) must sum to the exhaust flows ({} m^3/h)",
                            supply * 3600.0,
                            exhaust * 3600.0
                        ),
                    )
                } else {
                    at(offset, format!("`openings` {}", e.requirement))
                }
            }
        }
    })?;
    Ok(parsed)
}
