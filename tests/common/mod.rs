//! Running the built `depo` command from the end-to-end tests.

#![allow(dead_code)] // each test binary uses its own part

use std::process::{Command, Output};

use serde_json::Value;

/// Runs `depo` with `args`, whatever its outcome.
pub fn depo(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_depo")).args(args).output().expect("run depo")
}

/// stdout of a run that must succeed.
pub fn ok_text(args: &[&str]) -> String {
    let out = depo(args);
    assert!(out.status.success(), "depo {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// stdout of a run that must succeed, as JSON.
pub fn ok_json(args: &[&str]) -> Value {
    serde_json::from_str(&ok_text(args)).expect("JSON output")
}
