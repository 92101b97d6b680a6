//! The `depo` command: a person's way into depo. See `depo --help` and the README.

mod cli;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let args = cli::Args::parse();
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("depo: {error}");
            ExitCode::FAILURE
        }
    }
}
