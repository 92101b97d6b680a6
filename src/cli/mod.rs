//! Subcommands of the `depo` command line. Each prints a table (default), CSV or JSON; user
//! errors come back as one line naming what is wrong, never a panic.

/// `println!` for the command's output: a reader that closes the pipe early (`depo presets |
/// head`) ends the command quietly instead of with a panic.
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::cli::emit(format_args!($($arg)*))
    };
}

mod bench;
mod capture;
mod channel;
mod curve;
mod figures;
mod fit;
mod impact;
mod presets;
mod room;

use clap::{Args as ClapArgs, Parser, Subcommand, ValueEnum};
pub use depo::text::{check_memory, shown};
use depo::wall_model::{LawParams, WallLaw};

/// One line of what went wrong, for the user.
pub type Error = String;

#[derive(Parser, Debug)]
#[command(name = "depo", version, about = "Particle deposition with the Brach & Dunn (1998) wall law")]
pub struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// The presets of the paper's Table 1, with their sources.
    Presets(presets::PresetsArgs),
    /// R, rho, e and capture against the normal impact speed |vn|.
    Curve(curve::CurveArgs),
    /// One impact explained: coefficients, rolling or sliding, outcome, energy by mechanism.
    Impact(impact::ImpactArgs),
    /// Fit the law's constants to measured (vn, e) data, with uncertainties.
    Fit(fit::FitArgs),
    /// The capture velocity from material properties (JKR, Dahneke), per diameter.
    CaptureVelocity(capture::CaptureArgs),
    /// Redraw the paper's Figs. 6 and 8 and the presets' e curves as SVG files.
    Figures(figures::FiguresArgs),
    /// Deposition in a room per particle size and surface, beside Lai & Nazaroff (2000).
    ///
    /// Reading the table: +- is one standard error of the estimate over the run's randomness
    /// (delta method over the injected particles); [n] the deposit events it rests on; with
    /// none, < the 95 % upper bound. "excursions": deposits counted by near-wall excursions, an
    /// unbiased estimate of the steady deposition rate; in parentheses, when above 0.1 %, the
    /// share of their weight given up at their longest duration, a bound on what that may miss.
    /// That duration is 16000 wall time units, doubled while a pilot run or the size's run gave
    /// up more than 2.5 % of the weight, up to 8 times that. L&N < 1e-30: Lai & Nazaroff give
    /// below 1e-30 m/s (the ceiling for coarse particles), no deposition. "near floor": under
    /// a steady source spread over the room, the concentration in the lowest tenth of its
    /// height over the room's mean; marked ~ above 1.2, where the room is not well mixed for
    /// the size and its v_d and beta are not a well-mixed room's. * unresolved: no deposit
    /// event, or, where Lai & Nazaroff give at least 1e-7 m/s, a relative standard error or a
    /// share given up above 5 %; "To resolve to 5 %" then says about how many particles would
    /// (an error falls as one over the square root of the particles). + every particle left
    /// the air before the averaging window opened: that size's figures are averaged over the
    /// release from t = 0 (what became of it, not a well-mixed room's rates; v_d over the window
    /// does not exist, nothing being airborne there), its decay fitted from t = 0 (^ in the
    /// second table), and the times by which half and 90 % had deposited are in the second
    /// table. The second table reads the release as a decay experiment: beta fitted is the
    /// least-squares slope of ln N(t) over the window (from the averages' start while at least 50
    /// particles are airborne) less the exchange rate a, [n] the deposits in the window, ? fewer
    /// than 10, with none < its 95 % upper bound; z is the fitted beta less the study's over the
    /// standard error of that difference, paired over the particles both rest on (- where either
    /// has no event or no error). Its curve counts the tracked particles, which leave the air by
    /// their own deposits: where deposition is rare it resolves beta far less well than the
    /// study's excursions. Then where the released particles are at the end, in % of the number
    /// (for one size the same share of the mass): where none ended in a place, < 300/n [0], the
    /// rule of three's 95 % upper bound for n released; "none" exhausted where nothing can leave
    /// the room; and the floor's loading in ug/m^2 per mg released. The third table is the steady
    /// state under a continuous source entering where a scene's [source] says (indoor,
    /// infiltration or a supply opening; examples/room.toml), from its release followed from
    /// t = 0: the mean time in the air (the steady airborne number per particle emitted an
    /// hour), the deposition velocities (steady flux over the mean concentration), the share of
    /// the source ending in each place, in %, "beyond %" the share of the time in the air taken
    /// from the room's late rates past the run, the concentration in the lowest tenth of the
    /// height over the mean, and for outdoor air C_in/C_out.
    ///
    /// The furnishings' table: per box its deposition velocity onto all its faces, its top,
    /// its bottom and its sides (the four vertical faces), and the share of the released number
    /// it collected over the run, [n] the particles; with none, < the 95 % upper bound 3/n of
    /// the rule of three for n released. Lai & Nazaroff's beta in the first table is the bare
    /// room's.
    ///
    /// The size distribution's table: where its mass went, in ug in the room (modes given as
    /// concentrations) or as shares of the distribution's whole mass; +- one standard error over
    /// the runs' randomness; (x) a bound on the error of taking each bin's fate from one run at
    /// its midpoint, where each share is monotonic in d (?: a bin without neighbours). PM2.5 and
    /// PM10: mass of particles of aerodynamic diameter (unit density, with slip correction)
    /// below 2.5 and 10 um, a sharp cut at the 50 % points of the standards' inlets (EN
    /// 12341:2014, ISO 7708). beta of mass: the loss rate of the airborne mass by deposition
    /// (not ventilation) while its size distribution is the injected one; over part of the
    /// mass, a lower bound on the whole's.
    Room(room::RoomArgs),
    /// V+ against tau+ in a turbulent channel, beside Wood (1981).
    ///
    /// Reading the table: +- is one standard error of the estimate over the run's randomness
    /// (delta method over the injected particles); [n] the deposit events it rests on; with
    /// none, < the 95 % upper bound. "excursions": deposits counted by near-wall excursions, an
    /// unbiased estimate of the steady deposition rate; in parentheses, when above 0.1 %, the
    /// share of their weight given up at their longest duration, a bound on what that may miss.
    Channel(channel::ChannelArgs),
    /// Kernel throughput against a copy kernel moving the same bytes, and each kernel's error.
    Bench(bench::BenchArgs),
}

/// Output format.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Format {
    #[default]
    Table,
    Csv,
    Json,
}

/// A law given by preset id or by its constants (Eq. 10 form), with optional friction.
#[derive(ClapArgs, Debug, Clone)]
pub struct LawArgs {
    /// A preset id of `depo presets` (e.g. li1997-sio2).
    #[arg(long, conflicts_with_all = ["k", "kappa", "vc"])]
    preset: Option<String>,
    /// Restitution velocity k = k1 = k2 (m/s).
    #[arg(long, requires_all = ["kappa", "vc"], allow_negative_numbers = true)]
    k: Option<f64>,
    /// Adhesion velocity kappa = kappa1 = kappa2 (m/s).
    #[arg(long, allow_negative_numbers = true)]
    kappa: Option<f64>,
    /// Capture velocity (m/s); <= 0: never captured by speed.
    #[arg(long, allow_negative_numbers = true)]
    vc: Option<f64>,
    /// Exponent p of Eq. (8) [default: the preset's, or 1].
    #[arg(long, allow_negative_numbers = true)]
    p: Option<f64>,
    /// Exponent q of Eq. (9) [default: the preset's, or 1].
    #[arg(long, allow_negative_numbers = true)]
    q: Option<f64>,
    /// Friction coefficient [default: the preset's (0), or 0].
    #[arg(long, allow_negative_numbers = true)]
    mu: Option<f64>,
}

impl LawArgs {
    /// The law these arguments describe, or a one-line error.
    pub fn law(&self) -> Result<WallLaw, Error> {
        let base = match (&self.preset, self.k, self.kappa, self.vc) {
            (Some(id), ..) => *WallLaw::preset(id).map_err(|e| e.to_string())?.params(),
            (None, Some(k), Some(kappa), Some(vc)) => LawParams::symmetric(k, kappa, vc, 1.0, 1.0),
            _ => return Err("give a law: --preset ID, or --k K --kappa KAPPA --vc VC".into()),
        };
        let params = LawParams {
            p: self.p.unwrap_or(base.p),
            q: self.q.unwrap_or(base.q),
            mu: self.mu.unwrap_or(base.mu),
            ..base
        };
        WallLaw::new(params).map_err(|e| e.to_string())
    }
}

/// The largest speed the commands take (m/s): every energy per unit mass they print, `v^2 / 2`,
/// stays finite, far beyond any particle's.
pub const MAX_SPEED: f64 = 1e100;

/// `x` for a table: with `decimals` decimals from 1e-3 to 1e6 (and 0), in e-notation with as
/// many in the mantissa beyond that (`1.500000e-7`), so that no value is hundreds of digits
/// long nor a small one `0.000000`.
pub fn fixed(x: f64, decimals: usize) -> String {
    let a = x.abs();
    if a == 0.0 || (1e-3..1e6).contains(&a) {
        format!("{x:.decimals$}")
    } else {
        format!("{x:.decimals$e}")
    }
}

/// Parses "X,Y,Z" into three numbers.
pub fn parse_vector(text: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!("expected three comma-separated numbers, got '{text}'"));
    }
    let mut out = [0.0f64; 3];
    for (slot, part) in out.iter_mut().zip(&parts) {
        *slot = part.parse().map_err(|_| format!("'{part}' is not a number"))?;
        if !slot.is_finite() {
            return Err(format!("'{part}' is not finite"));
        }
    }
    Ok(out)
}

/// Writes one line to stdout; exits quietly with success when the reader has gone away.
pub fn emit(line: std::fmt::Arguments<'_>) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    if let Err(error) = writeln!(stdout, "{line}") {
        if error.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        eprintln!("depo: cannot write output: {error}");
        std::process::exit(1);
    }
}

/// Prints CSV: the header, then one record per row, each field quoted only where it needs it
/// (the `csv` crate's rules). The caller formats its own numbers.
pub fn print_csv<R>(header: &[&str], rows: impl IntoIterator<Item = R>) -> Result<(), Error>
where
    R: IntoIterator,
    R::Item: AsRef<[u8]>,
{
    out!("{}", depo::report::csv_text(header, rows)?);
    Ok(())
}

/// Prints `text`, whose lines are each ended, as [`emit`] prints a line.
pub fn emit_text(text: &str) {
    if let Some(body) = text.strip_suffix('\n') {
        emit(format_args!("{body}"));
    } else if !text.is_empty() {
        emit(format_args!("{text}"));
    }
}

/// Prints rows whose fields are the CSV's columns: the header from the field names (as in
/// the JSON), numbers as serde writes them.
pub fn print_csv_rows<R: serde::Serialize>(rows: &[R]) -> Result<(), Error> {
    emit_csv(|writer| rows.iter().try_for_each(|row| writer.serialize(row)))
}

/// Runs `write` on a CSV writer and prints what it wrote.
fn emit_csv(write: impl FnOnce(&mut csv::Writer<Vec<u8>>) -> csv::Result<()>) -> Result<(), Error> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    write(&mut writer).map_err(|e| e.to_string())?;
    let bytes = writer.into_inner().map_err(|e| e.to_string())?;
    let text = String::from_utf8(bytes).map_err(|e| e.to_string())?;
    out!("{}", text.trim_end_matches('\n'));
    Ok(())
}

/// A progress bar for a long run: `[bar] done/len WHAT elapsed message`, on stderr.
///
/// It shows whenever stderr is a terminal, whatever stdout is: a table or JSON piped into a
/// file or another program still shows its progress on the terminal. It is drawn at once and
/// redrawn every second, so a first step of a minute shows its elapsed time rather than
/// nothing. With stderr not a terminal (a log file) or `TERM=dumb` it stays hidden, so
/// captured output holds no escape codes.
pub fn progress_bar(len: usize, what: &str) -> Result<indicatif::ProgressBar, Error> {
    use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
    let bar = ProgressBar::with_draw_target(Some(len as u64), ProgressDrawTarget::stderr());
    let template = format!("{{bar:30}} {{pos}}/{{len}} {what} {{elapsed}} {{msg}}");
    bar.set_style(ProgressStyle::with_template(&template).map_err(|e| e.to_string())?);
    bar.tick();
    bar.enable_steady_tick(std::time::Duration::from_secs(1));
    Ok(bar)
}

/// A study's progress as a bar ([`progress_bar`]), drawn from its start to its end.
#[derive(Default)]
pub struct Bar(Option<indicatif::ProgressBar>);

impl depo::report::Progress for Bar {
    fn start(&mut self, total: usize, what: &str) {
        self.0 = progress_bar(total, what).ok();
    }

    fn done(&mut self, done: usize) {
        if let Some(bar) = &self.0 {
            bar.set_position(done as u64);
        }
    }

    fn finish(&mut self) {
        if let Some(bar) = self.0.take() {
            bar.finish_and_clear();
        }
    }
}

/// Runs the parsed command.
pub fn run(args: Args) -> Result<(), Error> {
    match args.command {
        Command::Presets(a) => presets::run(&a),
        Command::Curve(a) => curve::run(&a),
        Command::Impact(a) => impact::run(&a),
        Command::Fit(a) => fit::run(&a),
        Command::CaptureVelocity(a) => capture::run(&a),
        Command::Figures(a) => figures::run(&a),
        Command::Room(a) => room::run(&a),
        Command::Channel(a) => channel::run(&a),
        Command::Bench(a) => bench::run(&a),
    }
}

#[cfg(test)]
mod tests {
    use super::fixed;

    #[test]
    fn fixed_numbers_switch_to_e_notation_outside_their_range() {
        assert_eq!(fixed(0.1, 6), "0.100000");
        assert_eq!(fixed(-1e100, 6), "-1.000000e100");
        assert_eq!(fixed(1e-5, 4), "1.0000e-5");
    }
}
