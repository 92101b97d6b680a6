//! A room scene file: `[room]`, `[flow]` and the sections it shares with a channel, read
//! into a [`RoomStudy`] and, with one, the size distribution it runs at.

use depo_tracker::air::STANDARD_GRAVITY;
use depo_tracker::distribution::Distribution;
use depo_tracker::openings;
use depo_tracker::studies::RoomStudy;
use depo_tracker::{Flow, Geometry};
use serde::Deserialize;
use toml::Spanned;

use super::air::{apply_air, AirFile};
use super::furnishings::{furnishings, FurnishingFile};
use super::openings::{openings, OpeningFile};
use super::particles::{distribution, RoomParticles};
use super::run::{apply_run_choices, check_count, check_duration, check_transient, gravity, set_target_error, RunFile};
use super::source::{apply_source, SourceFile};
use super::ventilation::{apply_ventilation, VentilationFile};
use super::walls::{apply_walls, WallsFile};
use super::{parse, set, text_of, Error, SceneInput, SceneSource};
use crate::text::shown;

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RoomSection {
    pub(super) size: Option<[f64; 3]>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RoomFlowFile {
    pub(super) friction_velocity: Option<f64>,
    pub(super) core_rms: Option<f64>,
    pub(super) core_tke: Option<f64>,
    pub(super) core_time: Option<f64>,
    pub(super) blend_length: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RoomFile {
    #[serde(default)]
    pub(super) furnishings: Vec<Spanned<FurnishingFile>>,
    #[serde(default)]
    pub(super) openings: Vec<Spanned<OpeningFile>>,
    #[serde(default)]
    pub(super) room: RoomSection,
    #[serde(default)]
    pub(super) air: AirFile,
    #[serde(default)]
    pub(super) flow: RoomFlowFile,
    #[serde(default)]
    pub(super) particles: RoomParticles,
    #[serde(default)]
    pub(super) walls: WallsFile,
    #[serde(default)]
    pub(super) ventilation: VentilationFile,
    #[serde(default)]
    pub(super) run: RunFile,
    #[serde(default)]
    pub(super) source: SourceFile,
}

/// A room scene: its study, the size distribution it runs instead of the study's diameters,
/// if it gives one, and where it came from (for the lines of the run's errors).
pub struct RoomScene {
    pub study: RoomStudy,
    pub distribution: Option<Distribution>,
    pub source: SceneSource,
    /// What the reader warns of (one line each): the run goes ahead.
    pub warnings: Vec<String>,
}

/// The room scene of `input` (its study and its size distribution), or the built-in one.
pub(super) fn room_scene(input: &SceneInput) -> Result<RoomScene, Error> {
    let mut study = RoomStudy::default();
    let Some((text, name, dir, lines)) = text_of(input)? else {
        let source = SceneSource::built_in("the built-in room");
        return Ok(RoomScene { study, distribution: None, source, warnings: Vec::new() });
    };
    let (file, src): (RoomFile, SceneSource) = parse(text, &name, lines)?;
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
    let settings = &mut study.settings;
    set(&mut settings.dt, file.run.dt);
    set(&mut settings.duration, file.run.duration);
    set(&mut settings.seed, file.run.seed);
    set(&mut scene.brownian, file.run.brownian);
    set(&mut scene.lift, file.run.lift);
    apply_run_choices(&src, (scene, settings), &file.run)?;
    set(&mut study.excursions, file.run.excursions);
    scene.gravity = gravity(file.run.gravity.unwrap_or(STANDARD_GRAVITY));
    if file.run.dt_plus.is_some() || file.run.duration_plus.is_some() {
        return Err(
            src.at(&["run.dt_plus", "run.duration_plus"], "a room takes `run.dt` and `run.duration` in seconds")
        );
    }
    check_duration(&src, "run.duration", file.run.duration)?;
    if settings.dt > settings.duration {
        return Err(src.at(
            &["run.dt", "run.duration"],
            format!("`run.dt` = {} s is longer than the run, `run.duration` = {} s", settings.dt, settings.duration),
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
    apply_ventilation(&src, &mut study, &file.ventilation)?;
    apply_source(&src, &mut study, &file.source)?;
    check_count(&src, "particles.count", &["particles.count"], study.count)?;
    if study.target_error.is_some() {
        check_count(&src, "particles.max_count", &["particles.max_count"], study.max_count)?;
    }
    if study.diameters.is_empty() {
        return Err(src.at(&["particles.diameters"], "`particles.diameters` is empty"));
    }
    let mut warnings = Vec::new();
    let distribution = distribution(&dir, &src, &file.particles, (study.density, &study.scene.air), &mut warnings)?;
    Ok(RoomScene { study, distribution, source: src, warnings })
}
