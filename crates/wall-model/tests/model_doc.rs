//! `docs/MODEL.md` is the contract of the law: its Table 1 must be the presets the code ships,
//! constant for constant, and every mention of `MODEL.md` in the project must point at it.

use std::path::{Path, PathBuf};

use depo_wall_model::law::{material_restitution, LawConstants};
use depo_wall_model::power::Exact;
use depo_wall_model::PRESETS;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

fn model_doc() -> String {
    std::fs::read_to_string(root().join("docs/MODEL.md")).expect("docs/MODEL.md exists")
}

/// A number as the table prints it: a decimal or a fraction such as `1/2`.
fn number(cell: &str) -> f64 {
    match cell.split_once('/') {
        Some((a, b)) => a.trim().parse::<f64>().unwrap() / b.trim().parse::<f64>().unwrap(),
        None => cell.parse().unwrap_or_else(|_| panic!("not a number: '{cell}'")),
    }
}

/// The rows of the Table 1 section, as cells keyed by the header's names.
fn table_rows(doc: &str) -> Vec<Vec<(String, String)>> {
    let section = doc.split("## Table 1 as shipped").nth(1).expect("a '## Table 1 as shipped' section");
    let section = section.split("\n## ").next().unwrap();
    let mut lines = section.lines().filter(|l| l.trim_start().starts_with('|'));
    let cells = |line: &str| -> Vec<String> {
        line.trim().trim_matches('|').split('|').map(|c| c.trim().to_string()).collect()
    };
    let header = cells(lines.next().expect("a table header"));
    lines
        .skip(1) // the |---| line
        .map(|line| header.iter().cloned().zip(cells(line)).collect())
        .collect()
}

fn cell<'a>(row: &'a [(String, String)], name: &str) -> &'a str {
    &row.iter()
        .find(|(h, _)| h == name || h.starts_with(&format!("{name} (")))
        .unwrap_or_else(|| panic!("no column {name}"))
        .1
}

#[test]
fn table_1_in_model_md_is_the_shipped_presets() {
    let doc = model_doc();
    let rows = table_rows(&doc);
    let ids: Vec<&str> = rows.iter().map(|r| cell(r, "id").trim_matches('`')).collect();
    let shipped: Vec<&str> = PRESETS.iter().map(|p| p.id).collect();
    assert_eq!(ids, shipped, "docs/MODEL.md lists other presets, or in another order, than the code");
    for (row, preset) in rows.iter().zip(&PRESETS) {
        let lp = preset.params;
        let id = preset.id;
        assert_eq!(lp.k1, lp.k2, "{id}: the table has one k");
        assert_eq!(lp.kappa1, lp.kappa2, "{id}: the table has one kappa");
        assert_eq!(lp.mu, 0.0, "{id}: the table says presets have no friction");
        for (name, value) in [("k", lp.k1), ("kappa", lp.kappa1), ("vc", lp.vc), ("p", lp.p), ("q", lp.q)] {
            assert_eq!(number(cell(row, name)), value, "{id}: {name} in docs/MODEL.md differs from the code");
        }
        assert_eq!(cell(row, "source"), preset.source, "{id}: source");
        assert_eq!(cell(row, "particle"), preset.particle, "{id}: particle");
        assert_eq!(cell(row, "surface"), preset.surface, "{id}: surface");
        let last = cell(row, "last column");
        match preset.last_column {
            Some(v) => assert_eq!(number(last), v, "{id}: last column"),
            None => assert_eq!(last, "-", "{id}: the paper prints no last column"),
        }
        let rc = cell(row, "R(vc)");
        if lp.vc > 0.0 {
            let c = LawConstants::<f64>::new(&lp);
            let computed = material_restitution(&c, Exact(lp.p), lp.vc);
            assert!((number(rc) - computed).abs() <= 0.5e-4, "{id}: R(vc) printed {rc}, computed {computed}");
        } else {
            assert_eq!(rc, "-", "{id}: no capture velocity, no R(vc)");
        }
        assert_eq!(preset.reconstructed, preset.source.contains("reconstructed"), "{id}: reconstructed flag");
    }
}

/// The README and every source, header and document under `src/`, `crates/` and `docs/`
/// (`depo.h` included): where they name the contract, they name it by its path.
#[test]
fn every_mention_of_model_md_points_at_docs() {
    let mut files = vec![root().join("README.md")];
    let mut dirs = vec![root().join("src"), root().join("crates"), root().join("docs")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs" || e == "md" || e == "h" || e == "hpp" || e == "f90") {
                files.push(path);
            }
        }
    }
    let this_file = Path::new(file!()).file_name().unwrap();
    let mut bad = Vec::new();
    for file in files.iter().filter(|f| f.file_name() != Some(this_file)) {
        let text = std::fs::read_to_string(file).unwrap();
        for (n, line) in text.lines().enumerate() {
            for (at, _) in line.match_indices("MODEL.md") {
                let before = &line[..at];
                let is_this_doc = file.ends_with("docs/MODEL.md");
                if !(before.ends_with("docs/") || is_this_doc) {
                    bad.push(format!("{}:{}: {line}", file.display(), n + 1));
                }
            }
        }
    }
    assert!(bad.is_empty(), "mentions of MODEL.md that do not say docs/MODEL.md:\n{}", bad.join("\n"));
}
