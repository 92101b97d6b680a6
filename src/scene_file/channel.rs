//! A channel scene file: `[channel]` (its friction velocity and `Re_tau`) and the sections
//! it shares with a room, in wall units, read into a [`ChannelStudy`].

use depo_tracker::studies::ChannelStudy;
use depo_tracker::{Flow, Geometry};
use serde::Deserialize;

use super::air::{apply_air, AirFile};
use super::particles::ChannelParticles;
use super::run::{apply_run_choices, check_count, check_duration, check_transient, gravity, set_target_error, RunFile};
use super::walls::{apply_walls, WallsFile};
use super::{parse, set, text_of, Error, SceneInput, SceneSource};

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct ChannelSection {
    pub(super) friction_velocity: Option<f64>,
    pub(super) re_tau: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct ChannelFile {
    #[serde(default)]
    pub(super) channel: ChannelSection,
    #[serde(default)]
    pub(super) air: AirFile,
    #[serde(default)]
    pub(super) particles: ChannelParticles,
    #[serde(default)]
    pub(super) walls: WallsFile,
    #[serde(default)]
    pub(super) run: RunFile,
}

/// A channel scene: its study, and where it came from (for the lines of the run's errors).
pub struct ChannelScene {
    pub study: ChannelStudy,
    pub source: SceneSource,
}

/// The channel study of `input`, or the built-in one, and where it came from (for the lines
/// of the run's errors).
pub(super) fn channel(input: &SceneInput) -> Result<ChannelScene, Error> {
    let mut study = ChannelStudy::default();
    let Some((text, name, _, lines)) = text_of(input)? else {
        // Half the height in wall units.
        let unit = study.scene.air.kinematic_viscosity() / study.scene.flow.friction_velocity().unwrap_or(1.0);
        let re_tau = study.scene.geometry.size()[2] / 2.0 / unit;
        let source = SceneSource { re_tau: Some(re_tau), ..SceneSource::built_in("the built-in channel") };
        return Ok(ChannelScene { study, source });
    };
    let (file, mut src): (ChannelFile, SceneSource) = parse(text, &name, lines)?;
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
    let settings = &mut study.settings;
    settings.dt = dt_plus * time;
    settings.duration = duration_plus * time;
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
    set(&mut settings.seed, file.run.seed);
    set(&mut scene.brownian, file.run.brownian);
    set(&mut scene.lift, file.run.lift);
    apply_run_choices(&src, (scene, settings), &file.run)?;
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
    Ok(ChannelScene { study, source: src })
}
