//! `depo room`: deposition onto the floor, ceiling and walls of a room, per particle size,
//! beside Lai & Nazaroff (2000). The study and its reports are the library's
//! ([`depo::report::room`]); this reads the arguments and prints.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use depo::report::room::{self, csv, figures, json, table};
use depo::scene_file::{self, SceneInput};

use depo::plot;

use super::{Bar, Error, Format};

#[derive(ClapArgs, Debug)]
pub struct RoomArgs {
    /// A scene file (TOML; see examples/room.toml). Without it, the built-in room.
    scene: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    format: Format,
    /// Directory for the figures and maps, written unless --no-plot (61 files for the built-in
    /// room, more with furnishings): room-deposition.svg, room-beta.svg, room-decay.svg and
    /// the decay curves room-decay.csv; room-steady.svg, the steady state under the scene's
    /// continuous source ([source] in a scene file); each size's deposition velocity per cell
    /// of every surface (room-map-SIZEum.svg, room-flux-SIZEum.csv) and the tracked particles'
    /// deposits per cell (room-map-SURFACE-SIZEum.csv); room-indoor-outdoor.svg when
    /// ventilated; room-distribution.svg and room-pm.svg with a size distribution.
    #[arg(long, default_value = "depo-room")]
    plot: PathBuf,
    /// Write no figures or maps.
    #[arg(long)]
    no_plot: bool,
}

pub fn run(args: &RoomArgs) -> Result<(), Error> {
    let scene = scene_file::room_scene(&SceneInput::from_path(args.scene.as_deref()))?;
    for warning in &scene.warnings {
        eprintln!("depo: {warning}");
    }
    if !args.no_plot {
        plot::check_directory(&args.plot)?;
    }
    let result = room::run(scene, &mut Bar::default())?;
    match args.format {
        Format::Json => out!("{}", json::to_json(&result)?),
        Format::Csv => out!("{}", csv::to_csv(&result)?),
        Format::Table => super::emit_text(&table::table(&result)),
    }
    if !args.no_plot {
        figures::figures(&args.plot, &result, &mut |line| eprintln!("{line}"))?;
    }
    Ok(())
}
