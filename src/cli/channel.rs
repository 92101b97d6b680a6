//! `depo channel`: V+ against tau+ in a turbulent channel, beside Wood (1981). The study and
//! its reports are the library's ([`depo::report::channel`]); this reads the arguments and
//! prints.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use depo::report::channel::{self, csv, figures, json, table, ChannelOptions, NearWallChoice as Choice};
use depo::scene_file::{self, SceneInput};

use depo::plot;

use super::{Bar, Error, Format};

#[derive(ClapArgs, Debug)]
pub struct ChannelArgs {
    /// A scene file (TOML; see examples/channel.toml). Without it, the built-in channel.
    scene: Option<PathBuf>,
    /// The tau+ values to run, e.g. 1,3,10 (overrides the scene's).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    tau_plus: Option<Vec<f64>>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    format: Format,
    /// Write the figure (V+ against tau+) to this SVG file.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// How deposition at the walls is modelled: `resolved` (the near-wall layer tracked to
    /// the wall), `wall-function` (a particle within 30 wall units deposits at the rate of
    /// Wood's correlation; docs/tracker.md), or `all`: both, and the figure beside Code_Saturne's
    /// own deposition model and the measurements. Without it, the scene's `run.near_wall`.
    #[arg(long, value_enum)]
    near_wall: Option<NearWallChoice>,
}

/// The deposition models `--near-wall` chooses between.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum NearWallChoice {
    Resolved,
    WallFunction,
    All,
}

pub fn run(args: &ChannelArgs) -> Result<(), Error> {
    let input = SceneInput::from_path(args.scene.as_deref());
    let scene = scene_file::channel_scene(&input)?;
    if let Some(path) = &args.plot {
        plot::check_writable(path)?;
    }
    let options = ChannelOptions {
        tau_plus: args.tau_plus.clone(),
        near_wall: args.near_wall.map(|choice| match choice {
            NearWallChoice::Resolved => Choice::Resolved,
            NearWallChoice::WallFunction => Choice::WallFunction,
            NearWallChoice::All => Choice::All,
        }),
        ..ChannelOptions::new(input)
    };
    let result = channel::run(scene, &options, &mut Bar::default())?;
    for run in &result.runs {
        match args.format {
            Format::Json => out!("{}", json::to_json(run)?),
            Format::Csv => out!("{}", csv::to_csv(run)?),
            Format::Table => super::emit_text(&table::table(run)),
        }
    }
    if result.all && args.format == Format::Table {
        super::emit_text(&table::peer_table());
    }
    if let Some(path) = &args.plot {
        figures::figure(path, &result, &mut |line| eprintln!("{line}"))?;
    }
    Ok(())
}
