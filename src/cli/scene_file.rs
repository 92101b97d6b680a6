//! Scene files for `depo room` and `depo channel`: TOML, every key optional (the built-in
//! study's value stands in), unknown keys rejected with their line. The commented examples
//! `examples/room.toml` and `examples/channel.toml` list every key.

use std::path::Path;

use depo::tracker::air::STANDARD_GRAVITY;
use depo::tracker::distribution::{Amount, Distribution, Median, Mode, Quantity, SizeClass, DEFAULT_BINS};
use depo::tracker::filtration::FilterEfficiency;
use depo::tracker::furnishing::FACE_NAMES;
use depo::tracker::openings;
use depo::tracker::studies::{ChannelStudy, RoomStudy};
use depo::tracker::{
    Air, Correlation, Drag, Flow, Furnishing, Geometry, NearWall, Opening, OpeningKind, Scene, SceneError, Scheme,
    WallBehaviour, WallFunction,
};
use depo::wall_model::{LawParams, SizeDependence, WallLaw};
use serde::Deserialize;
use toml::Spanned;

use super::csv_input::{at_line, CsvInput};
use super::{check_memory, shown, Error};

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct AirFile {
    temperature: Option<f64>,
    pressure: Option<f64>,
    density: Option<f64>,
    viscosity: Option<f64>,
}

#[derive(Deserialize, Default, Clone)]
#[serde(deny_unknown_fields)]
struct WallFile {
    /// "sink", "reflect" or "law".
    behaviour: Option<String>,
    preset: Option<String>,
    /// A law's own constants instead of a preset, as `depo fit` prints them (m/s; `p` and `q`
    /// default to 1).
    k: Option<f64>,
    kappa: Option<f64>,
    vc: Option<f64>,
    p: Option<f64>,
    q: Option<f64>,
    mu: Option<f64>,
    size_exponent: Option<f64>,
    reference_diameter: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct WallsFile {
    all: Option<WallFile>,
    floor: Option<WallFile>,
    ceiling: Option<WallFile>,
    x0: Option<WallFile>,
    x1: Option<WallFile>,
    y0: Option<WallFile>,
    y1: Option<WallFile>,
    lower: Option<WallFile>,
    upper: Option<WallFile>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RunFile {
    dt: Option<f64>,
    duration: Option<f64>,
    dt_plus: Option<f64>,
    duration_plus: Option<f64>,
    seed: Option<u64>,
    brownian: Option<bool>,
    gravity: Option<f64>,
    lift: Option<bool>,
    transient: Option<f64>,
    /// "stokes" or "schiller-naumann".
    drag: Option<String>,
    /// "gaussian", "intermittent" (channels) or "wall-function".
    near_wall: Option<String>,
    /// The wall function's correlation: "wood", "papavergos-hedley" or "lai-nazaroff".
    correlation: Option<String>,
    /// The wall function's layer in wall units.
    layer_plus: Option<f64>,
    /// "exponential" or "midpoint".
    scheme: Option<String>,
    excursions: Option<bool>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RoomSection {
    size: Option<[f64; 3]>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RoomFlowFile {
    friction_velocity: Option<f64>,
    core_rms: Option<f64>,
    core_tke: Option<f64>,
    core_time: Option<f64>,
    blend_length: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RoomParticles {
    diameters: Option<Vec<f64>>,
    count: Option<usize>,
    /// 0 turns the target off.
    target_error: Option<f64>,
    max_count: Option<usize>,
    density: Option<f64>,
    /// A size distribution instead of `diameters`: lognormal modes...
    modes: Option<Spanned<Vec<Spanned<ModeFile>>>>,
    /// ... cut into this many bins in ln d ...
    bins: Option<Spanned<usize>>,
    /// ... over this range (m).
    bin_range: Option<Spanned<[f64; 2]>>,
    /// Or measured size classes: a CSV file, relative to the scene file.
    size_bins: Option<Spanned<String>>,
}

/// One lognormal mode of `particles.modes`.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct ModeFile {
    count_median: Option<f64>,
    mass_median: Option<f64>,
    geometric_sd: Option<f64>,
    density: Option<f64>,
    number_share: Option<f64>,
    mass_share: Option<f64>,
    number_concentration: Option<f64>,
    mass_concentration: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct VentilationFile {
    air_changes_per_hour: Option<f64>,
    penetration: Option<f64>,
    supply_share: Option<f64>,
    supply_filter: Option<EfficiencyFile>,
    recirculation_per_hour: Option<f64>,
    recirculation_filter: Option<EfficiencyFile>,
}

/// A filter's efficiency in a scene: one number for every size, or `[diameter m, efficiency]`
/// pairs.
#[derive(Deserialize)]
#[serde(untagged)]
enum EfficiencyFile {
    One(f64),
    Curve(Vec<[f64; 2]>),
}

/// The filter of `ventilation.{key}` as [`FilterEfficiency`], or an error naming the file, the
/// key and its line.
fn filter_efficiency(src: &SceneSource, key: &str, file: &EfficiencyFile) -> Result<FilterEfficiency, Error> {
    let curve = match file {
        EfficiencyFile::One(eta) => FilterEfficiency::constant(*eta),
        EfficiencyFile::Curve(points) => FilterEfficiency::new(points.iter().map(|&[d, eta]| (d, eta)).collect()),
    };
    let key = format!("ventilation.{key}");
    curve.map_err(|e| src.at(&[&key], format!("`{key}`: {} = {} {}", e.field, e.value, e.requirement)))
}

/// One `[[furnishings]]` entry: a box and its faces' behaviour (the keys of a `[walls.*]`
/// table, for all faces or per face).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FurnishingFile {
    name: Option<String>,
    low: Spanned<[f64; 3]>,
    high: Spanned<[f64; 3]>,
    all: Option<WallFile>,
    bottom: Option<WallFile>,
    top: Option<WallFile>,
    x0: Option<WallFile>,
    x1: Option<WallFile>,
    y0: Option<WallFile>,
    y1: Option<WallFile>,
}

/// One `[[openings]]` entry: a supply or exhaust opening on a room wall.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OpeningFile {
    /// "supply" or "exhaust".
    kind: Spanned<String>,
    /// A wall's name: floor, ceiling, x0, x1, y0, y1.
    wall: Spanned<String>,
    /// Centre in the wall's two in-plane coordinates, in the order x, y, z (m).
    center: Spanned<[f64; 2]>,
    /// Extent along the same coordinates (m).
    size: Spanned<[f64; 2]>,
    /// Volume flow through it, m^3/h.
    flow_m3_per_hour: Spanned<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RoomFile {
    #[serde(default)]
    furnishings: Vec<Spanned<FurnishingFile>>,
    #[serde(default)]
    openings: Vec<Spanned<OpeningFile>>,
    #[serde(default)]
    room: RoomSection,
    #[serde(default)]
    air: AirFile,
    #[serde(default)]
    flow: RoomFlowFile,
    #[serde(default)]
    particles: RoomParticles,
    #[serde(default)]
    walls: WallsFile,
    #[serde(default)]
    ventilation: VentilationFile,
    #[serde(default)]
    run: RunFile,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct ChannelSection {
    friction_velocity: Option<f64>,
    re_tau: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct ChannelParticles {
    tau_plus: Option<Vec<f64>>,
    count: Option<usize>,
    excursion_count: Option<usize>,
    /// 0 turns the target off.
    target_error: Option<f64>,
    max_factor: Option<f64>,
    density: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct ChannelFile {
    #[serde(default)]
    channel: ChannelSection,
    #[serde(default)]
    air: AirFile,
    #[serde(default)]
    particles: ChannelParticles,
    #[serde(default)]
    walls: WallsFile,
    #[serde(default)]
    run: RunFile,
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
}

impl SceneSource {
    /// A built-in scene's: `name` stands in for the file, and no key has a line.
    fn built_in(name: &str) -> Self {
        Self { name: name.to_string(), text: String::new(), re_tau: None }
    }

    /// `message` as the TOML errors put it, `FILE line N: message`, with the line of the
    /// first of `keys` (dotted, as [`line_of_key`] takes them) the file gives; `FILE: message`
    /// where it gives none of them (their values are the defaults).
    fn at(&self, keys: &[&str], message: impl std::fmt::Display) -> Error {
        match keys.iter().find_map(|key| self.line(key)) {
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
        format!("{} line {}: {message}", self.name, line_of(&self.text, offset))
    }

    /// The error of a run of this scene, with the line of the key its field names where the
    /// file gives that key. [`Scene::validate`] and the studies name a field as a scene holds
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

/// Reads and parses `path`, keeping its text for the lines of later errors; a TOML error
/// names the file, the line and the key.
fn read<T: for<'de> Deserialize<'de>>(path: &Path) -> Result<(T, SceneSource), Error> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let file = toml::from_str(&text).map_err(|e| {
        let line = e.span().map(|s| line_of(&text, s.start));
        let message = e.message().trim().replace('\n', " ");
        match line {
            Some(line) => format!("{} line {line}: {message}", path.display()),
            None => format!("{}: {message}", path.display()),
        }
    })?;
    Ok((file, SceneSource { name: path.display().to_string(), text, re_tau: None }))
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

/// The run's named choices where the file makes them: the drag law, the step (the studies offer
/// the exponential scheme and its midpoint form; Euler is for the integrator benchmark), the
/// near-wall model and what it steps.
fn apply_run_choices(src: &SceneSource, scene: &mut Scene, run: &RunFile) -> Result<(), Error> {
    let drag = [("stokes", Drag::Stokes), ("schiller-naumann", Drag::SchillerNaumann)];
    set(&mut scene.drag, named(src, "run.drag", run.drag.as_deref(), &drag)?);
    let schemes = [("exponential", Scheme::Exponential), ("midpoint", Scheme::Midpoint)];
    set(&mut scene.scheme, named(src, "run.scheme", run.scheme.as_deref(), &schemes)?);
    let models = [
        ("gaussian", Some(NearWall::Gaussian)),
        ("intermittent", Some(NearWall::Intermittent)),
        ("wall-function", None),
    ];
    match named(src, "run.near_wall", run.near_wall.as_deref(), &models)? {
        Some(Some(model)) => scene.near_wall = model,
        // The wall function's transport is the Gaussian model's.
        Some(None) => {
            scene.near_wall = NearWall::Gaussian;
            let correlation = if matches!(scene.geometry, Geometry::Channel { .. }) {
                Correlation::Wood
            } else {
                Correlation::LaiNazaroff
            };
            scene.wall_function = Some(WallFunction::new(correlation));
        }
        None => {}
    }
    let correlation = named(src, "run.correlation", run.correlation.as_deref(), &Correlation::NAMED)?;
    if let Some(wf) = &mut scene.wall_function {
        set(&mut wf.correlation, correlation);
        set(&mut wf.layer_plus, run.layer_plus);
    } else if let Some(key) = [(correlation.is_some(), "run.correlation"), (run.layer_plus.is_some(), "run.layer_plus")]
        .into_iter()
        .find_map(|(given, key)| given.then_some(key))
    {
        return Err(src.at(&[key], format!("`{key}` is for a wall function: set `run.near_wall = \"wall-function\"`")));
    }
    Ok(())
}

fn set<T>(slot: &mut T, value: Option<T>) {
    if let Some(v) = value {
        *slot = v;
    }
}

fn apply_air(scene: &mut Scene, air: &AirFile) {
    set(&mut scene.air.temperature, air.temperature);
    set(&mut scene.air.pressure, air.pressure);
    set(&mut scene.air.density, air.density);
    set(&mut scene.air.viscosity, air.viscosity);
}

/// The behaviour `file` gives a surface whose keys start `prefix` (`walls.floor`,
/// `furnishings[0].top`); an error names the file and the line of the key at fault, or of the
/// surface where a key is missing.
fn wall_behaviour(src: &SceneSource, prefix: &str, file: &WallFile) -> Result<WallBehaviour, Error> {
    let key = |k: &str| format!("{prefix}.{k}");
    // The line of the surface's key `k`, or of the surface.
    let at = |k: &str, message: String| src.at(&[&key(k), prefix], message);
    let at_surface = |message: String| src.at(&[prefix], message);
    let constants = [file.k, file.kappa, file.vc, file.p, file.q];
    let has_constants = constants.iter().any(Option::is_some);
    let default = if file.preset.is_some() || has_constants { "law" } else { "sink" };
    match file.behaviour.as_deref().unwrap_or(default) {
        "sink" => Ok(WallBehaviour::Sink),
        "reflect" => Ok(WallBehaviour::Reflect),
        "law" => {
            let mut law = match (file.preset.as_deref(), has_constants) {
                (Some(_), true) => {
                    return Err(at_surface(format!(
                        "`{prefix}`: give a `preset` or the constants `k`, `kappa`, `vc`, not both"
                    )))
                }
                (Some(id), false) => {
                    WallLaw::preset(id).map_err(|e| at("preset", format!("`{}`: {e}", key("preset"))))?
                }
                (None, true) => {
                    let need = |v: Option<f64>, k: &str| {
                        v.ok_or_else(|| at_surface(format!("`{}` is needed with the law's constants", key(k))))
                    };
                    let (k, kappa, vc) = (need(file.k, "k")?, need(file.kappa, "kappa")?, need(file.vc, "vc")?);
                    let params = LawParams::symmetric(k, kappa, vc, file.p.unwrap_or(1.0), file.q.unwrap_or(1.0));
                    // The law's field as the file's key: `k1`/`k2` are the file's `k`, and so on.
                    WallLaw::new(params).map_err(|e| {
                        let file_key = e.field.trim_end_matches(['1', '2']);
                        at(file_key, format!("`{prefix}`: {e}"))
                    })?
                }
                (None, false) => {
                    return Err(at_surface(format!(
                        "`{}` (or the constants `k`, `kappa`, `vc`) is needed for a wall law",
                        key("preset")
                    )))
                }
            };
            if let Some(mu) = file.mu {
                law = WallLaw::new(law.params().with_friction(mu))
                    .map_err(|e| at("mu", format!("`{}`: {e}", key("mu"))))?;
            }
            let size = match file.size_exponent {
                None => None,
                Some(alpha) => {
                    let d_ref = file.reference_diameter.ok_or_else(|| {
                        at("size_exponent", format!("`{}` is needed with a size exponent", key("reference_diameter")))
                    })?;
                    let size = SizeDependence::new(d_ref, alpha).map_err(|e| {
                        let file_key = if e.field == "reference_diameter" { e.field } else { "size_exponent" };
                        at(file_key, format!("`{prefix}`: {e}"))
                    })?;
                    Some(size)
                }
            };
            Ok(WallBehaviour::Law { law, size })
        }
        other => Err(at(
            "behaviour",
            format!("`{}` = \"{other}\": expected \"sink\", \"reflect\" or \"law\"", key("behaviour")),
        )),
    }
}

/// The `[walls]` of a scene onto its walls: `all` first, then each wall's own table.
fn apply_walls(src: &SceneSource, scene: &mut Scene, walls: &WallsFile) -> Result<(), Error> {
    if let Some(all) = &walls.all {
        let behaviour = wall_behaviour(src, "walls.all", all)?;
        scene.walls.iter_mut().for_each(|w| *w = behaviour);
    }
    let geometry = scene.geometry;
    for wall in geometry.walls() {
        let name = wall.name(&geometry);
        let file = match name {
            "floor" => &walls.floor,
            "ceiling" => &walls.ceiling,
            "x0" => &walls.x0,
            "x1" => &walls.x1,
            "y0" => &walls.y0,
            "y1" => &walls.y1,
            "lower" => &walls.lower,
            _ => &walls.upper,
        };
        if let Some(file) = file {
            scene.walls[wall.id] = wall_behaviour(src, &format!("walls.{name}"), file)?;
        }
    }
    let room_only = [&walls.floor, &walls.ceiling, &walls.x0, &walls.x1, &walls.y0, &walls.y1];
    let channel_only = [&walls.lower, &walls.upper];
    // The other kind's walls, by key.
    let (foreign, keys) = match geometry {
        Geometry::Room { .. } => (channel_only.iter().any(|w| w.is_some()), &["walls.lower", "walls.upper"][..]),
        Geometry::Channel { .. } => (
            room_only.iter().any(|w| w.is_some()),
            &["walls.floor", "walls.ceiling", "walls.x0", "walls.x1", "walls.y0", "walls.y1"][..],
        ),
    };
    if foreign {
        // At the first of the foreign keys in the file.
        let keys = src.in_file_order(keys);
        return Err(src.at(&keys, "`walls`: a room has floor, ceiling, x0, x1, y0, y1; a channel has lower and upper"));
    }
    Ok(())
}

/// The `[[furnishings]]` of a room of `size` (m), checked: each box strictly inside the room
/// and above its `low` corner, none overlapping another; errors name the file, the line and
/// the key.
fn furnishings(
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

/// The `[[openings]]` of a room `geometry`, checked (each within its wall, none overlapping
/// another, supply and exhaust flows balanced); errors name the file, the line and the key.
fn openings(src: &SceneSource, entries: &[Spanned<OpeningFile>], geometry: &Geometry) -> Result<Vec<Opening>, Error> {
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

fn gravity(g: f64) -> [f64; 3] {
    [0.0, 0.0, -g]
}

/// A room scene: its study, the size distribution it runs instead of the study's diameters,
/// if it gives one, and where it came from (for the lines of the run's errors).
pub struct RoomScene {
    pub study: RoomStudy,
    pub distribution: Option<Distribution>,
    pub source: SceneSource,
}

/// The room scene of `path` (its study and its size distribution), or the built-in one.
pub fn room_scene(path: Option<&Path>) -> Result<RoomScene, Error> {
    let mut study = RoomStudy::default();
    let Some(path) = path else {
        return Ok(RoomScene { study, distribution: None, source: SceneSource::built_in("the built-in room") });
    };
    let (file, src): (RoomFile, SceneSource) = read(path)?;
    let scene = &mut study.scene;
    if let Some(size) = file.room.size {
        scene.geometry = Geometry::Room { size };
    }
    apply_air(scene, &file.air);
    if let Flow::TurbulentRoom { mut friction_velocity, mut core_rms, mut core_time, mut blend_length } = scene.flow {
        set(&mut friction_velocity, file.flow.friction_velocity);
        set(&mut core_rms, file.flow.core_rms);
        if let Some(k) = file.flow.core_tke {
            if file.flow.core_rms.is_some() {
                return Err(src.at(&["flow.core_tke"], "give `flow.core_rms` or `flow.core_tke`, not both"));
            }
            core_rms = (2.0 * k / 3.0).sqrt();
        }
        set(&mut core_time, file.flow.core_time);
        set(&mut blend_length, file.flow.blend_length);
        scene.flow = Flow::TurbulentRoom { friction_velocity, core_rms, core_time, blend_length };
    }
    set(&mut scene.dt, file.run.dt);
    set(&mut scene.duration, file.run.duration);
    set(&mut scene.seed, file.run.seed);
    set(&mut scene.brownian, file.run.brownian);
    set(&mut scene.lift, file.run.lift);
    apply_run_choices(&src, scene, &file.run)?;
    set(&mut study.excursions, file.run.excursions);
    scene.gravity = gravity(file.run.gravity.unwrap_or(STANDARD_GRAVITY));
    if file.run.dt_plus.is_some() || file.run.duration_plus.is_some() {
        return Err(
            src.at(&["run.dt_plus", "run.duration_plus"], "a room takes `run.dt` and `run.duration` in seconds")
        );
    }
    check_duration(&src, "run.duration", file.run.duration)?;
    if scene.dt > scene.duration {
        return Err(src.at(
            &["run.dt", "run.duration"],
            format!("`run.dt` = {} s is longer than the run, `run.duration` = {} s", scene.dt, scene.duration),
        ));
    }
    apply_walls(&src, scene, &file.walls)?;
    scene.furnishings = furnishings(&src, &file.furnishings, scene.geometry.size())?;
    scene.openings = openings(&src, &file.openings, &scene.geometry)?;
    openings::validate_clearance(&scene.openings, &scene.furnishings, scene.geometry.size()).map_err(|e| {
        // `furnishings[k]`: the line of that entry.
        let k: usize = e.field.trim_start_matches("furnishings[").trim_end_matches(']').parse().unwrap_or(0);
        let offset = file.furnishings.get(k).map_or(0, |f| f.span().start);
        src.at_offset(
            offset,
            format!(
                "`furnishings[{k}]` is {} m off an opening's wall and {}",
                shown(e.value),
                e.requirement.trim_end_matches(" (this is the gap, m)")
            ),
        )
    })?;
    set(&mut study.transient, file.run.transient);
    check_transient(&src, study.transient)?;
    set(&mut study.diameters, file.particles.diameters.clone());
    set(&mut study.count, file.particles.count);
    set(&mut study.max_count, file.particles.max_count);
    set_target_error(&src, &mut study.target_error, file.particles.target_error)?;
    set(&mut study.density, file.particles.density);
    let ventilation = &file.ventilation;
    // An error at the line of `ventilation.{key}`.
    let at = |key: &str, message: String| src.at(&[&format!("ventilation.{key}")], message);
    if let Some(ach) = ventilation.air_changes_per_hour {
        if !(ach.is_finite() && ach >= 0.0) {
            return Err(at(
                "air_changes_per_hour",
                format!("`ventilation.air_changes_per_hour` = {ach} must be finite and not negative"),
            ));
        }
        if ach > 0.0 && !scene.openings.is_empty() {
            return Err(at(
                "air_changes_per_hour",
                format!(
                    "`ventilation.air_changes_per_hour` = {ach} must be 0 with `[[openings]]`: their exhaust flow sets it"
                ),
            ));
        }
        scene.air_exchange = ach / 3600.0;
    }
    if let Some(p) = ventilation.penetration {
        if !(0.0..=1.0).contains(&p) {
            return Err(at("penetration", format!("`ventilation.penetration` = {p} must be in [0, 1]")));
        }
        study.penetration = p;
    }
    if let Some(share) = ventilation.supply_share {
        if !(0.0..=1.0).contains(&share) {
            return Err(at("supply_share", format!("`ventilation.supply_share` = {share} must be in [0, 1]")));
        }
        study.filtration.supply_share = share;
    }
    if let Some(filter) = &ventilation.supply_filter {
        study.filtration.supply_filter = filter_efficiency(&src, "supply_filter", filter)?;
    }
    if let Some(rate) = ventilation.recirculation_per_hour {
        if !(rate.is_finite() && rate >= 0.0) {
            return Err(at(
                "recirculation_per_hour",
                format!("`ventilation.recirculation_per_hour` = {rate} must be finite and not negative"),
            ));
        }
        if rate > 0.0 && !scene.openings.is_empty() {
            return Err(at(
                "recirculation_per_hour",
                format!(
                    "`ventilation.recirculation_per_hour` = {rate} must be 0 with `[[openings]]` (not modelled beside them)"
                ),
            ));
        }
        study.filtration.recirculation = rate / 3600.0;
    }
    if let Some(filter) = &ventilation.recirculation_filter {
        study.filtration.recirculation_filter = filter_efficiency(&src, "recirculation_filter", filter)?;
    }
    check_count(&src, "particles.count", &["particles.count"], study.count)?;
    if study.target_error.is_some() {
        check_count(&src, "particles.max_count", &["particles.max_count"], study.max_count)?;
    }
    if study.diameters.is_empty() {
        return Err(src.at(&["particles.diameters"], "`particles.diameters` is empty"));
    }
    let distribution = distribution(path, &src, &file.particles, study.density, &study.scene.air)?;
    Ok(RoomScene { study, distribution, source: src })
}

/// The channel study of `path`, or the built-in one, and where it came from (for the lines
/// of the run's errors).
pub fn channel(path: Option<&Path>) -> Result<(ChannelStudy, SceneSource), Error> {
    let mut study = ChannelStudy::default();
    let Some(path) = path else {
        // Half the height in wall units.
        let unit = study.scene.air.kinematic_viscosity() / study.scene.flow.friction_velocity().unwrap_or(1.0);
        let re_tau = study.scene.geometry.size()[2] / 2.0 / unit;
        return Ok((study, SceneSource { re_tau: Some(re_tau), ..SceneSource::built_in("the built-in channel") }));
    };
    let (file, mut src): (ChannelFile, SceneSource) = read(path)?;
    let scene = &mut study.scene;
    apply_air(scene, &file.air);
    let u_star = file.channel.friction_velocity.unwrap_or(scene.flow.friction_velocity().unwrap_or(0.3));
    let re_tau = file.channel.re_tau.unwrap_or(150.0);
    for (key, v) in [("channel.friction_velocity", u_star), ("channel.re_tau", re_tau)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(src.at(&[key], format!("`{key}` = {v} must be finite and positive")));
        }
    }
    src.re_tau = Some(re_tau);
    let unit = scene.air.kinematic_viscosity() / u_star;
    let time = unit / u_star;
    scene.geometry = Geometry::Channel { length: 1000.0 * unit, width: 300.0 * unit, height: 2.0 * re_tau * unit };
    scene.flow = Flow::TurbulentChannel { friction_velocity: u_star };
    let (dt_plus, duration_plus) = (file.run.dt_plus.unwrap_or(0.2), file.run.duration_plus.unwrap_or(3000.0));
    scene.dt = dt_plus * time;
    scene.duration = duration_plus * time;
    if file.run.dt.is_some() || file.run.duration.is_some() {
        return Err(
            src.at(&["run.dt", "run.duration"], "a channel takes `run.dt_plus` and `run.duration_plus` in wall units")
        );
    }
    check_duration(&src, "run.duration_plus", file.run.duration_plus)?;
    if dt_plus > duration_plus {
        return Err(src.at(
            &["run.dt_plus", "run.duration_plus"],
            format!("`run.dt_plus` = {dt_plus} is longer than the run, `run.duration_plus` = {duration_plus}"),
        ));
    }
    set(&mut scene.seed, file.run.seed);
    set(&mut scene.brownian, file.run.brownian);
    set(&mut scene.lift, file.run.lift);
    apply_run_choices(&src, scene, &file.run)?;
    if file.run.excursions == Some(false) {
        study.excursions_below = 0.0;
    }
    scene.gravity = gravity(file.run.gravity.unwrap_or(0.0));
    apply_walls(&src, scene, &file.walls)?;
    set(&mut study.transient, file.run.transient);
    check_transient(&src, study.transient)?;
    set(&mut study.tau_plus, file.particles.tau_plus);
    if study.tau_plus.is_empty() {
        return Err(src.at(&["particles.tau_plus"], "`particles.tau_plus` is empty"));
    }
    set(&mut study.count, file.particles.count);
    set(&mut study.excursion_count, file.particles.excursion_count);
    check_count(&src, "particles.count", &["particles.count"], study.count)?;
    check_count(&src, "particles.excursion_count", &["particles.excursion_count"], study.excursion_count)?;
    set_target_error(&src, &mut study.target_error, file.particles.target_error)?;
    if let Some(factor) = file.particles.max_factor {
        if !(factor.is_finite() && factor >= 1.0) {
            let key = "particles.max_factor";
            return Err(src.at(&[key], format!("`{key}` = {factor} must be finite and at least 1")));
        }
        study.max_factor = factor;
    }
    let most = |count: usize| (count as f64 * study.max_factor).min(usize::MAX as f64) as usize;
    // The counts alone fit (above): the factor makes too many.
    for (count, n) in [("particles.count", study.count), ("particles.excursion_count", study.excursion_count)] {
        check_count(&src, &format!("{count} times particles.max_factor"), &["particles.max_factor", count], most(n))?;
    }
    set(&mut study.density, file.particles.density);
    Ok((study, src))
}

/// A run's length `key`, if the file sets it: a run of no time measures nothing (its rates
/// would be bounds of `inf`).
fn check_duration(src: &SceneSource, key: &str, value: Option<f64>) -> Result<(), Error> {
    match value {
        Some(d) if !(d.is_finite() && d > 0.0) => {
            Err(src.at(&[key], format!("`{key}` = {d} must be finite and positive")))
        }
        _ => Ok(()),
    }
}

/// `particles.target_error`, if the file sets it: 0 turns the target off.
fn set_target_error(src: &SceneSource, target_error: &mut Option<f64>, value: Option<f64>) -> Result<(), Error> {
    if let Some(target) = value {
        if !(target.is_finite() && target >= 0.0) {
            let key = "particles.target_error";
            return Err(src.at(&[key], format!("`{key}` = {target} must be finite and not negative")));
        }
        *target_error = (target > 0.0).then_some(target);
    }
    Ok(())
}

/// A particle count whose particles would not fit in memory is one line, not an abort: the
/// count's `key`, at the line of the first of `lines` the file gives.
fn check_count(src: &SceneSource, key: &str, lines: &[&str], count: usize) -> Result<(), Error> {
    check_memory(&src.at(lines, format!("`{key}` = {count}")), count as u64, PARTICLE_BYTES)
}

/// What a particle of a run keeps in memory, generously: its record and tally (about 900
/// bytes with the excursions' counts by level and by class of crossing), and a share of the
/// study's results.
const PARTICLE_BYTES: u64 = 1536;

fn check_transient(src: &SceneSource, transient: f64) -> Result<(), Error> {
    if (0.0..1.0).contains(&transient) {
        Ok(())
    } else {
        Err(src.at(&["run.transient"], format!("`run.transient` = {transient} must be in [0, 1)")))
    }
}

/// Bins holding less of the modes' mass than this are an error: the answers would be of a
/// sliver of the distribution.
const MIN_BINNED_SHARE: f64 = 0.5;

/// Bins holding less of the modes' mass than this are warned of.
const WARN_BINNED_SHARE: f64 = 0.99;

/// The size distribution of a room scene's `[particles]`: its `modes` or its `size_bins`
/// file, or none. A mode's density defaults to `particles.density`, and its amount to a share
/// of 1 (of number for a count median, of mass for a mass median). Errors name the file, the
/// line and the key.
fn distribution(
    path: &Path,
    src: &SceneSource,
    particles: &RoomParticles,
    density: f64,
    air: &Air,
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
        let file = path.parent().unwrap_or(Path::new(".")).join(name.get_ref());
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
        eprintln!(
            "depo: warning: {}: the bins hold {:.1} % of the modes' mass; the rest is left out of the mass balance",
            path.display(),
            100.0 * binned
        );
    }
    Ok(Some(distribution))
}

/// How far (relative to the first step) the steps in `ln d` between a CSV's midpoints may
/// differ: instruments' midpoints are rounded to a few digits.
const MIDPOINT_SPACING: f64 = 0.02;

/// The size classes of a CSV file: a header naming the edges (`lower` and `upper`, m, or
/// `lower_um` and `upper_um`) or the midpoints (`diameter` or `diameter_um`, at least two, in
/// increasing order and evenly spaced in `ln d`: edges at the geometric means between them), and `number` (1/m^3) or
/// `mass` (kg/m^3) per class; a `density` column (kg/m^3) is optional, `density` standing in.
/// `#` starts a comment.
fn size_classes(path: &Path, density: f64) -> Result<Vec<SizeClass>, Error> {
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

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use depo::tracker::{ParticleTally, Record, SceneError};

    use super::{channel, line_of_key, room_scene};

    #[test]
    fn a_particle_s_memory_is_counted_generously() {
        let kept = std::mem::size_of::<ParticleTally>() + std::mem::size_of::<Record>();
        assert!(kept as u64 * 3 / 2 <= super::PARTICLE_BYTES, "{kept} bytes a particle");
    }

    /// A small room's first lines, so that a bad key below them is on line 9 or later and the
    /// runs that reach their checks are quick.
    const ROOM: &str = "# A test room.\n\
                        [room]\n\
                        size = [2.0, 2.0, 2.0]\n\
                        [particles]\n\
                        diameters = [1e-6]\n\
                        count = 10\n\
                        target_error = 0.0\n";

    /// The scene file `name` holding `text`, in the temporary directory.
    fn scene_file(name: &str, text: &str) -> PathBuf {
        let path = std::env::temp_dir().join(format!("depo-scene-file-{}-{name}.toml", std::process::id()));
        std::fs::write(&path, text).unwrap();
        path
    }

    /// The error of a scene file `text` as the CLI gives it, reading it or else running it
    /// (its scene is validated as the run starts), without the file's path it starts with.
    fn error(name: &str, text: &str, kind: &str) -> String {
        let path = scene_file(name, text);
        let result = if kind == "room" {
            room_scene(Some(&path)).and_then(|s| s.study.run(|_| {}).map(drop).map_err(|e| s.source.scene_error(&e)))
        } else {
            channel(Some(&path)).and_then(|(study, src)| study.run(|_| {}).map(drop).map_err(|e| src.scene_error(&e)))
        };
        std::fs::remove_file(&path).unwrap();
        let message = result.expect_err("a bad scene");
        let name = path.display().to_string();
        message.strip_prefix(&name).unwrap_or_else(|| panic!("{message} names {name}")).to_string()
    }

    fn room_error(name: &str, lines: &str) -> String {
        error(name, &format!("{ROOM}{lines}"), "room")
    }

    #[test]
    fn value_errors_name_the_line_of_their_key() {
        assert_eq!(
            room_error("air", "[air]\npressure = 101325.0\ntemperature = -5.0\n"),
            " line 10: `air.temperature` = -5 must be finite and positive"
        );
        assert_eq!(
            room_error("dt", "[run]\nduration = 10.0\n\ndt = 0.0\n"),
            " line 11: `dt` = 0 must be finite and positive"
        );
        assert_eq!(
            room_error("duration", "[run]\n\nduration = 0.0\n"),
            " line 10: `run.duration` = 0 must be finite and positive"
        );
        assert_eq!(
            room_error("scheme", "[run]\nduration = 10.0\nscheme = \"euler\"\n"),
            " line 10: `run.scheme` = \"euler\": expected \"exponential\" or \"midpoint\""
        );
        assert_eq!(
            room_error("transient", "[run]\nduration = 10.0\ntransient = 1.5\n"),
            " line 10: `run.transient` = 1.5 must be in [0, 1)"
        );
        assert_eq!(
            room_error("law", "[walls]\nceiling = { behaviour = \"sink\" }\nfloor = { behaviour = \"law\" }\n"),
            " line 10: `walls.floor.preset` (or the constants `k`, `kappa`, `vc`) is needed for a wall law"
        );
        assert_eq!(
            room_error("behaviour", "[walls.x1]\nbehaviour = \"bounce\"\n"),
            " line 9: `walls.x1.behaviour` = \"bounce\": expected \"sink\", \"reflect\" or \"law\""
        );
        assert_eq!(
            room_error("penetration", "[ventilation]\nair_changes_per_hour = 0.5\npenetration = 2.0\n"),
            " line 10: `ventilation.penetration` = 2 must be in [0, 1]"
        );
        assert_eq!(
            room_error("friction", "[flow]\ncore_rms = 0.01\n\n\nfriction_velocity = -1.0\n"),
            " line 12: `flow.friction_velocity` = -1 must be finite and positive"
        );
        // A furnishing's face: the line of its key, in the second entry.
        let furnished = "[[furnishings]]\nlow = [0.5, 0.5, 0.5]\nhigh = [0.7, 0.7, 0.7]\n\
                         [[furnishings]]\nlow = [1.0, 1.0, 1.0]\nhigh = [1.5, 1.5, 1.5]\n\
                         top = { preset = \"nope\" }\n";
        let message = room_error("face", furnished);
        assert!(message.starts_with(" line 14: `furnishings[1].top.preset`: "), "{message}");
        // A law's own constant at fault: its line, not the surface's.
        let message = room_error("p", "[walls.floor]\nk = 10.0\nkappa = 0.2\nvc = 0.07\n\np = -1.0\n");
        assert!(message.starts_with(" line 13: `walls.floor`: "), "{message}");
        let sized = "[walls.floor]\npreset = \"dunn1995-copper\"\nsize_exponent = 1.5\n\nreference_diameter = -1.0\n";
        let message = room_error("reference", sized);
        assert!(message.starts_with(" line 12: `walls.floor`: "), "{message}");
    }

    #[test]
    fn channel_errors_name_the_line_of_their_key() {
        let head = "[channel]\nre_tau = 150.0\n[particles]\ntau_plus = [1.0]\ncount = 10\n";
        let message = error("lower", &format!("{head}[walls]\nlower = {{ preset = \"nope\" }}\n"), "channel");
        assert!(message.starts_with(" line 7: `walls.lower.preset`: "), "{message}");
        // Room walls in a channel: the first of them in the file.
        let foreign = format!("{head}[walls]\nx0 = {{ behaviour = \"sink\" }}\nceiling = {{ behaviour = \"sink\" }}\n");
        let message = error("foreign", &foreign, "channel");
        assert!(message.starts_with(" line 7: `walls`: a room has"), "{message}");
        assert_eq!(
            error("seconds", &format!("{head}[run]\nduration_plus = 10.0\ndt = 0.1\n"), "channel"),
            " line 8: a channel takes `run.dt_plus` and `run.duration_plus` in wall units"
        );
        assert_eq!(
            error("tau_plus", "[channel]\nre_tau = 150.0\n[particles]\ntau_plus = []\ncount = 10\n", "channel"),
            " line 4: `particles.tau_plus` is empty"
        );
        assert_eq!(
            error("duration_plus", &format!("{head}[run]\nduration_plus = 0.0\n"), "channel"),
            " line 7: `run.duration_plus` = 0 must be finite and positive"
        );
        let message = error("dt_plus", &format!("{head}[run]\nduration_plus = 10.0\ndt_plus = -0.1\n"), "channel");
        assert!(
            message.starts_with(" line 8: `dt` = -") && message.ends_with(" must be finite and positive"),
            "{message}"
        );
    }

    /// Errors of what the file gives as a whole, or through other keys, name the keys it wrote.
    #[test]
    fn errors_name_the_keys_the_file_wrote() {
        let filled = "[[furnishings]]\nlow = [0.001, 0.001, 0.001]\nhigh = [1.999, 1.999, 1.999]\n";
        let message = room_error("filled", filled);
        assert!(message.starts_with(" line 8: `[[furnishings]]` take up 99.7"), "{message}");
        assert!(!message.contains("particles.region"), "{message}");
        let shallow = "[channel]\nre_tau = 0.5\n[particles]\ntau_plus = [100.0]\ncount = 10\n";
        let message = error("shallow", shallow, "channel");
        assert!(
            message.starts_with(" line 2: `channel.re_tau` = 0.5: the channel, 2 Re_tau wall units high, must be"),
            "{message}"
        );
        assert!(message.contains("its largest particle, 73.6924 um across (`particles.tau_plus`)"), "{message}");
        let heavy = "[channel]\nre_tau = 150.0\n[particles]\ntau_plus = [30000.0]\ncount = 10\n";
        let message = error("heavy", heavy, "channel");
        assert!(message.starts_with(" line 4: `particles.tau_plus`: a particle of "), "{message}");
        assert!(message.contains(" um must be at most 1 mm"), "{message}");
    }

    /// A key the file leaves out is the default's: no line (none in the file is the key's).
    #[test]
    fn a_default_value_s_error_has_no_line() {
        let path = scene_file("default", &format!("{ROOM}[run]\nduration = 10.0\n"));
        let scene = room_scene(Some(&path)).unwrap();
        std::fs::remove_file(&path).unwrap();
        let e = SceneError { field: "flow.core_time".into(), value: 0.0, requirement: "must be finite and positive" };
        assert_eq!(
            scene.source.scene_error(&e),
            format!("{}: `flow.core_time` = 0 must be finite and positive", path.display())
        );
        let e = SceneError { field: "duration".into(), ..e };
        assert!(scene.source.scene_error(&e).contains(" line 9: `duration` = 0"), "{e}");
        let built_in = room_scene(None).unwrap().source;
        assert_eq!(built_in.scene_error(&e), "the built-in room: `duration` = 0 must be finite and positive");
    }

    /// Dotted keys in tables, inline tables, headers and arrays of tables.
    #[test]
    fn keys_are_found_by_their_spans() {
        let text = "title = 1\n\
                    [walls]\n\
                    floor = { preset = \"a\",\n  mu = 0.3 }\n\
                    [walls.x0]\n\
                    k = 1.0\n\
                    [[furnishings]]\n\
                    low = [1, 2, 3]\n\
                    [[furnishings]]\n\
                    top.preset = \"b\"\n";
        let root = toml::de::DeTable::parse(text).unwrap();
        let line = |key: &str| line_of_key(text, root.get_ref(), key);
        assert_eq!(line("title"), Some(1));
        assert_eq!(line("walls"), Some(2));
        assert_eq!(line("walls.floor"), Some(3));
        assert_eq!(line("walls.floor.mu"), Some(4));
        assert_eq!(line("walls.x0"), Some(5));
        assert_eq!(line("walls.x0.k"), Some(6));
        assert_eq!(line("furnishings[0]"), Some(7));
        assert_eq!(line("furnishings[0].low"), Some(8));
        assert_eq!(line("furnishings[1].top.preset"), Some(10));
        for absent in
            ["run.dt", "walls.x1", "walls.floor.k", "furnishings[2]", "title.x", "walls[0]", "furnishings.low"]
        {
            assert_eq!(line(absent), None, "{absent}");
        }
    }
}
