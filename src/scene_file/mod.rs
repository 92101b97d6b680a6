//! Scene files for the room and channel studies: TOML, every key optional (the built-in
//! study's value stands in), unknown keys rejected with their line. The commented examples
//! `examples/room.toml` and `examples/channel.toml` list every key.
//!
//! A scene comes from a file, a TOML string or a parsed [`toml::Table`] ([`SceneInput`]);
//! [`room_scene`] and [`channel_scene`] read it into the tracker's study. Every error is one
//! line naming the file (or what stands in for it), the line and the key at fault, as the
//! `depo` command prints it. The reader is split by the file's sections: `run` (`[run]`),
//! `air`, `walls`, `furnishings`, `openings`, `ventilation`, `source` (where the steady
//! state's source enters), `particles` (the diameters or a size distribution), and the two
//! kinds of scene, `room` and `channel`, which put them together.

mod air;
mod channel;
mod furnishings;
mod openings;
mod particles;
mod room;
mod run;
mod source;
#[cfg(test)]
mod tests;
mod ventilation;
mod walls;

use std::path::{Path, PathBuf};

use depo_tracker::SceneError;
use serde::Deserialize;

pub use channel::ChannelScene;
pub use room::RoomScene;
pub use walls::{check_fit, law_entry};

use crate::text::shown;

/// A reader's error: one line, naming the file, the line and the key.
type Error = String;

/// Where a scene is read from.
#[derive(Clone, Debug)]
pub enum SceneInput {
    /// The built-in room or channel.
    BuiltIn,
    /// A scene file; a `size_bins` file it names is read beside it.
    Path(PathBuf),
    /// A scene file's text: `name` stands in for its path in errors, and a `size_bins` file is
    /// read from `dir`.
    Text { text: String, name: String, dir: PathBuf },
    /// A parsed TOML table (a binding's dictionary), read as [`SceneInput::Text`] reads the
    /// table written as TOML; a table has no lines, so its errors name `name` and the key
    /// (`scene: `run.dt` = ...`), without a line.
    Table { table: toml::Table, name: String, dir: PathBuf },
}

impl SceneInput {
    /// A file's scene, or the built-in one without a path.
    pub fn from_path(path: Option<&Path>) -> Self {
        path.map_or(Self::BuiltIn, |p| Self::Path(p.to_path_buf()))
    }
}

/// The room scene of `input` (its study and its size distribution), or the built-in one.
pub fn room_scene(input: &SceneInput) -> Result<RoomScene, crate::Error> {
    Ok(room::room_scene(input)?)
}

/// The channel study of `input`, or the built-in one, and where it came from.
pub fn channel_scene(input: &SceneInput) -> Result<ChannelScene, crate::Error> {
    Ok(channel::channel(input)?)
}

/// A scene file's text, what its errors call it, the directory its own files are read from,
/// and whether its errors give lines (not a table's); `None` for the built-in scene.
fn text_of(input: &SceneInput) -> Result<Option<(String, String, PathBuf, bool)>, Error> {
    let parent = |p: &Path| p.parent().unwrap_or(Path::new(".")).to_path_buf();
    Ok(match input {
        SceneInput::BuiltIn => None,
        SceneInput::Path(path) => {
            let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
            Some((text, path.display().to_string(), parent(path), true))
        }
        SceneInput::Text { text, name, dir } => Some((text.clone(), name.clone(), dir.clone(), true)),
        SceneInput::Table { table, name, dir } => {
            let text = toml::to_string(table).map_err(|e| format!("{name}: {e}"))?;
            Some((text, name.clone(), dir.clone(), false))
        }
    })
}

/// Where a scene came from, for its errors: a file's path and text (to give the line of a
/// key), or what stands in for a file, `the built-in room`, which has no lines.
pub struct SceneSource {
    /// The file's path as errors show it, or `the built-in ...`.
    name: String,
    /// The file's text; empty for a built-in scene.
    text: String,
    /// A channel's `Re_tau`; `None` for a room.
    re_tau: Option<f64>,
    /// Whether errors give the line of a key: not for a table, which has none.
    lines: bool,
}

impl SceneSource {
    /// A built-in scene's: `name` stands in for the file, and no key has a line.
    fn built_in(name: &str) -> Self {
        Self { name: name.to_string(), text: String::new(), re_tau: None, lines: false }
    }

    /// `message` as the TOML errors put it, `FILE line N: message`, with the line of the
    /// first of `keys` (dotted, as [`line_of_key`] takes them) the file gives; `FILE: message`
    /// where it gives none of them (their values are the defaults).
    fn at(&self, keys: &[&str], message: impl std::fmt::Display) -> Error {
        match keys.iter().find_map(|key| self.line(key)).filter(|_| self.lines) {
            Some(line) => format!("{} line {line}: {message}", self.name),
            None => format!("{}: {message}", self.name),
        }
    }

    /// `keys` ordered by the line the file gives each on, the keys it leaves out last.
    fn in_file_order<'k>(&self, keys: &[&'k str]) -> Vec<&'k str> {
        let mut keys = keys.to_vec();
        keys.sort_by_key(|k| self.line(k).unwrap_or(usize::MAX));
        keys
    }

    /// The line of the dotted `key` in the file ([`line_of_key`]); `None` where the file
    /// leaves it out, or for a built-in scene. The text is parsed anew: errors only ask.
    fn line(&self, key: &str) -> Option<usize> {
        let root = toml::de::DeTable::parse(&self.text).ok()?;
        line_of_key(&self.text, root.get_ref(), key)
    }

    /// `message` at the line of the byte `offset` into the file (a span of its values).
    fn at_offset(&self, offset: usize, message: impl std::fmt::Display) -> Error {
        if self.lines {
            format!("{} line {}: {message}", self.name, line_of(&self.text, offset))
        } else {
            format!("{}: {message}", self.name)
        }
    }

    /// The error of a run of this scene, with the line of the key its field names where the
    /// file gives that key. [`Scene::validate`](depo_tracker::Scene::validate) and the studies name a field as a scene holds
    /// it (`dt`, `size.x`, `air_exchange`): these are the keys a file sets it with, a room's or
    /// a channel's (a file can only hold its own kind's keys).
    pub fn scene_error(&self, e: &SceneError) -> Error {
        match e.field.as_str() {
            // The boxes together: the value counts them, a number the file does not give.
            "furnishings" => return self.at(&["furnishings"], format!("`[[furnishings]]` {}", e.requirement)),
            // A room releases its particles over the whole room, which the boxes fill.
            "particles.region" => {
                return self.at(
                    &["furnishings"],
                    format!(
                        "`[[furnishings]]` take up {} % of the room (each grown by a particle's radius): at least 1 % \
                         must be free air, where the particles are released",
                        shown(100.0 * e.value)
                    ),
                )
            }
            // A channel's particles are given by their tau+, and its height by Re_tau.
            "particles.diameter" => {
                if let Some(re_tau) = self.re_tau {
                    let size = shown(e.value * 1e6);
                    return if e.requirement.contains("half the domain") {
                        self.at(
                            &["channel.re_tau", "particles.tau_plus"],
                            format!(
                                "`channel.re_tau` = {}: the channel, 2 Re_tau wall units high, must be more than twice \
                                 as high as its largest particle, {size} um across (`particles.tau_plus`)",
                                shown(re_tau)
                            ),
                        )
                    } else {
                        let message = format!("`particles.tau_plus`: a particle of {size} um {}", e.requirement);
                        self.at(&["particles.tau_plus"], message)
                    };
                }
            }
            _ => {}
        }
        let keys: &[&str] = match e.field.as_str() {
            "size.x" | "size.y" | "size.z" => &["room.size"],
            "dt" => &["run.dt", "run.dt_plus"],
            "duration" => &["run.duration", "run.duration_plus"],
            "average_from" => &["run.transient"],
            "gravity" => &["run.gravity"],
            "lift" => &["run.lift"],
            "near_wall" | "wall_function" => &["run.near_wall"],
            "wall_function.layer_plus" => &["run.layer_plus"],
            "air_exchange" => &["ventilation.air_changes_per_hour"],
            "penetration" => &["ventilation.penetration"],
            "supply_share" => &["ventilation.supply_share"],
            "recirculation" => &["ventilation.recirculation_per_hour"],
            "flow.friction_velocity" => &["flow.friction_velocity", "channel.friction_velocity"],
            "flow.core_rms" => &["flow.core_rms", "flow.core_tke"],
            "particles.diameter" => &["particles.diameters", "particles.tau_plus"],
            field => &[field],
        };
        self.at(keys, e)
    }
}

/// The line (from 1) of the dotted `key` in a TOML document `root` parsed from `text`
/// (`run.dt`, `walls.floor.preset`, `furnishings[1].top`; `[i]` is an array's entry): the
/// line of the key itself (of an `[[array]]` entry, its header's), `None` where the document
/// does not give the key.
fn line_of_key(text: &str, root: &toml::de::DeTable<'_>, key: &str) -> Option<usize> {
    let mut table = root;
    let mut found: Option<(usize, &toml::de::DeValue<'_>)> = None;
    for part in key.split('.') {
        if let Some((_, value)) = found {
            table = value.as_table()?;
        }
        let (name, indices) = part.split_once('[').map_or((part, ""), |(name, rest)| (name, rest));
        let (k, v) = table.get_key_value(name)?;
        let (mut offset, mut value) = (k.span().start, v.get_ref());
        for index in indices.split('[').filter(|i| !i.is_empty()) {
            let entry = value.as_array()?.get(index.trim_end_matches(']').parse::<usize>().ok()?)?;
            (offset, value) = (entry.span().start, entry.get_ref());
        }
        found = Some((offset, value));
    }
    found.map(|(offset, _)| line_of(text, offset))
}

/// Parses a scene file's `text`, keeping it for the lines of later errors; a TOML error
/// names the file (`name`), the line and the key. Without `lines` (a table's text), an error
/// names the key its span falls on instead of the line.
fn parse<T: for<'de> Deserialize<'de>>(text: String, name: &str, lines: bool) -> Result<(T, SceneSource), Error> {
    let file = toml::from_str(&text).map_err(|e| {
        let message = e.message().trim().replace('\n', " ");
        let start = e.span().map(|s| s.start);
        match start {
            Some(offset) if lines => format!("{name} line {}: {message}", line_of(&text, offset)),
            Some(offset) => match key_at(&text, offset) {
                Some(key) => format!("{name}: `{key}`: {message}"),
                None => format!("{name}: {message}"),
            },
            None => format!("{name}: {message}"),
        }
    })?;
    Ok((file, SceneSource { name: name.to_string(), text, re_tau: None, lines }))
}

/// The dotted key (`walls.floor.k`, `furnishings[1].low`) of the TOML document `text` whose
/// name starts last at or before the byte `offset`: the key an error at `offset` is about
/// (its value follows it on its line, or the offset is on the key itself).
fn key_at(text: &str, offset: usize) -> Option<String> {
    use toml::de::{DeTable, DeValue};
    fn walk(table: &DeTable<'_>, prefix: &str, offset: usize, best: &mut Option<(usize, String)>) {
        for (k, v) in table {
            let start = k.span().start;
            let path = if prefix.is_empty() { k.get_ref().to_string() } else { format!("{prefix}.{}", k.get_ref()) };
            if start <= offset && best.as_ref().is_none_or(|(s, _)| start >= *s) {
                *best = Some((start, path.clone()));
            }
            within(v.get_ref(), &path, offset, best);
        }
    }
    fn within(value: &DeValue<'_>, path: &str, offset: usize, best: &mut Option<(usize, String)>) {
        match value {
            DeValue::Table(t) => walk(t, path, offset, best),
            DeValue::Array(a) => {
                for (i, entry) in a.iter().enumerate() {
                    let here = format!("{path}[{i}]");
                    let start = entry.span().start;
                    if start <= offset && best.as_ref().is_none_or(|(s, _)| start > *s) {
                        *best = Some((start, here.clone()));
                    }
                    within(entry.get_ref(), &here, offset, best);
                }
            }
            _ => {}
        }
    }
    let root = DeTable::parse(text).ok()?;
    let mut best = None;
    walk(root.get_ref(), "", offset, &mut best);
    best.map(|(_, key)| key)
}

/// The line (from 1) of a byte offset into `text`.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// The value a `run` key names among `options`, `None` where the file leaves the key out; any
/// other name is an error listing the options.
fn named<T: Copy>(src: &SceneSource, key: &str, name: Option<&str>, options: &[(&str, T)]) -> Result<Option<T>, Error> {
    let Some(name) = name else { return Ok(None) };
    match options.iter().find(|(n, _)| *n == name) {
        Some(&(_, value)) => Ok(Some(value)),
        None => {
            let names: Vec<String> = options.iter().map(|(n, _)| format!("\"{n}\"")).collect();
            Err(src.at(&[key], format!("`{key}` = \"{name}\": expected {}", names.join(" or "))))
        }
    }
}

fn set<T>(slot: &mut T, value: Option<T>) {
    if let Some(v) = value {
        *slot = v;
    }
}
