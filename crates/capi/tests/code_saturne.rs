//! depo inside a real CFD code: Code_Saturne 6.0 (Debian's `code-saturne`) runs the check case
//! of `integrations/code_saturne` with libdepo at every particle-wall contact, and every contact
//! it recorded must be what depo's own `WallLaw` gives for the same incoming velocity and
//! normal: the same outcome and the same outgoing velocity to round-off. Code_Saturne's own
//! boundary statistics of the run (its particle/boundary interactions, events, impact velocity
//! and angle, mass flux) must count those contacts. The check case runs on 1 rank and, where
//! `mpiexec` is installed, on 2 (a SKIPPED line otherwise), and the two must agree.
//!
//! It also runs a small version of the channel case with depo's deposition wall function on
//! both walls, and the deposition velocity it measures must be the one the wall function
//! applies, times the wall cells' concentration over the mean as counted in the same run.
//!
//! And it runs the duct case with depo's wall function (Lai & Nazaroff's correlation) on its
//! floor, ceiling and sides: each size's deposits must be the number the correlation's flux
//! predicts from the particles the wall cells held, step by step, within binomial errors. The
//! duct's figure must be what its report draws from the stored CSV files, Code_Saturne's
//! deposition model among its series (Python only, no Code_Saturne run).
//!
//! Without Code_Saturne the tests fail, saying what to install, unless `DEPO_SKIP_CODE_SATURNE`
//! is 1: then they say SKIPPED on stderr (never a silent pass), as the example tests do.

use std::collections::HashMap;
use std::process::Command;

use depo_wall_model::{LawParams, WallLaw};
use glam::DVec3;

mod common;
use common::{libdir, root, run};

/// The zones' names and laws the run reported, by boundary zone id: its log lines
/// `depo: zone "floor" (id 1): preset li1997-sio2`.
fn zone_laws(log: &str) -> HashMap<u32, (String, WallLaw)> {
    let mut laws = HashMap::new();
    for line in log.lines().filter_map(|l| l.strip_prefix("depo: zone ")) {
        let (name, rest) = line.split_once(" (id ").expect("a zone id");
        let (id, law) = rest.split_once("): ").expect("a zone law");
        let id: u32 = id.parse().unwrap();
        let law = match law.split_once(' ') {
            Some(("preset", id)) => WallLaw::preset(id.trim()).unwrap(),
            Some(("constants", numbers)) => {
                let c: Vec<f64> = numbers.split_whitespace().map(|x| x.parse().unwrap()).collect();
                let [k1, k2, kappa1, kappa2, p, q, vc, mu] = c[..] else { panic!("{line}") };
                WallLaw::new(LawParams { k1, k2, kappa1, kappa2, p, q, vc, mu }).unwrap()
            }
            _ => panic!("{line}"),
        };
        laws.insert(id, (name.trim_matches('"').to_string(), law));
    }
    laws
}

/// Whether Code_Saturne is there to run `test`; without it, false after a SKIPPED line when
/// `DEPO_SKIP_CODE_SATURNE` is 1, and a failure otherwise.
fn code_saturne_found(test: &str) -> bool {
    let found = Command::new("code_saturne").args(["info", "--version"]).output().is_ok_and(|o| o.status.success());
    if !found {
        if std::env::var_os("DEPO_SKIP_CODE_SATURNE").is_some_and(|v| v == "1") {
            // Written to the stream itself: the test harness captures `eprintln!`.
            use std::io::Write;
            let line = format!("SKIPPED {test}: code_saturne is not installed (DEPO_SKIP_CODE_SATURNE=1)\n");
            let _ = std::io::stderr().write_all(line.as_bytes());
            return false;
        }
        panic!(
            "code_saturne is not installed: install it (on Debian: apt-get install code-saturne \
             code-saturne-include; .ci/run does), or set DEPO_SKIP_CODE_SATURNE=1 to skip this test"
        );
    }
    true
}

/// libdepo installed in a prefix of the test's own, under `work`.
fn install_prefix(work: &std::path::Path) -> std::path::PathBuf {
    let lib = libdir().to_path_buf();
    let prefix = work.join("prefix");
    run(Command::new("bash").arg(root().join("crates/capi/install.sh")).arg(&prefix).arg(&lib));
    prefix
}

/// Whether an MPI launcher is there for a parallel run; without it, a SKIPPED line for `what`.
fn mpi_found(what: &str) -> bool {
    let found = Command::new("mpiexec").arg("--version").output().is_ok_and(|o| o.status.success());
    if !found {
        use std::io::Write;
        let line = format!("SKIPPED {what}: mpiexec is not installed (on Debian: apt-get install openmpi-bin)\n");
        let _ = std::io::stderr().write_all(line.as_bytes());
    }
    found
}

/// What one run of the check case gave on one boundary zone.
#[derive(Debug, Default, Clone, Copy)]
struct ZoneCounts {
    rebounds: usize,
    captures: usize,
}

/// Each rank's file of a run: `name.csv` in a serial run, `name_<rank>.csv` in a parallel one.
fn rank_files(resu: &std::path::Path, name: &str) -> Vec<String> {
    let mut files: Vec<_> = std::fs::read_dir(resu)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|f| f == &format!("{name}.csv") || (f.starts_with(&format!("{name}_")) && f.ends_with(".csv")))
        .collect();
    files.sort();
    files.iter().map(|f| std::fs::read_to_string(resu.join(f)).unwrap()).collect()
}

/// Runs the check case on `nprocs` ranks and checks it: every recorded contact against depo's
/// own `WallLaw`, Code_Saturne's deposited count against depo's captures, and Code_Saturne's
/// boundary statistics against the contacts. Returns the contacts per zone name.
fn check_case(work: &std::path::Path, prefix: &std::path::Path, nprocs: usize) -> HashMap<String, ZoneCounts> {
    let integration = root().join("integrations/code_saturne");
    let case = work.join(format!("check-{nprocs}"));
    run(Command::new("bash")
        .arg(integration.join("run_case.sh"))
        .arg(integration.join("check_case"))
        .arg(&case)
        .arg(nprocs.to_string())
        .env("DEPO_PREFIX", prefix)
        // OpenMPI refuses to start as root (a container's user) without these.
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"));

    let resu = case.join("study/case/RESU/run");
    let listing = std::fs::read_to_string(resu.join("listing")).unwrap();
    let laws = zone_laws(&listing);
    assert_eq!(laws.len(), 3, "the check case sets a law on the floor, the ceiling and the walls");
    let impacts = rank_files(&resu, "depo_impacts");
    assert_eq!(impacts.len(), nprocs, "one impacts file per rank");
    let mut counts = [0usize; 4];
    let mut zones: HashMap<u32, ZoneCounts> = HashMap::new();
    // Per zone: the sum of the incoming speeds and of the angles between the incoming velocity
    // and the face's outward normal, over the contacts (Code_Saturne's impact statistics).
    let mut speeds: HashMap<u32, (f64, f64)> = HashMap::new();
    let mut diameter = 0.0;
    for (row, line) in impacts.iter().flat_map(|csv| csv.lines().skip(1)).enumerate() {
        let f: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let zone = f[0] as u32;
        diameter = f[1];
        let (v, n, out, outcome) =
            (DVec3::new(f[2], f[3], f[4]), DVec3::new(f[5], f[6], f[7]), [f[8], f[9], f[10]], f[11]);
        let (name, law) = &laws[&zone];
        // depo's normal points into the air: up from the floor, down from the ceiling,
        // horizontal at the side walls.
        let inward = match name.as_str() {
            "floor" => n.distance(DVec3::Z) < 1e-12,
            "ceiling" => n.distance(-DVec3::Z) < 1e-12,
            _ => n.z.abs() < 1e-12 && (n.length() - 1.0).abs() < 1e-12,
        };
        assert!(inward, "row {row}: {line}: not the {name}'s normal into the air");
        let result = law.impact(v, None, n);
        let (expected, velocity) = if result.normal_velocity >= 0.0 {
            (2.0, v.to_array())
        } else if result.coefficients.captured {
            (1.0, [0.0; 3])
        } else {
            (0.0, result.velocity)
        };
        assert_eq!(outcome, expected, "row {row}: {line}");
        for k in 0..3 {
            assert!((out[k] - velocity[k]).abs() <= 1e-14 * v.length(), "row {row}: {line}: {velocity:?}");
        }
        counts[outcome as usize] += 1;
        let zone_counts = zones.entry(zone).or_default();
        match outcome as usize {
            0 => zone_counts.rebounds += 1,
            1 => zone_counts.captures += 1,
            _ => {}
        }
        let sums = speeds.entry(zone).or_default();
        sums.0 += v.length();
        sums.1 += (-v.dot(n) / v.length()).clamp(-1.0, 1.0).acos();
    }
    eprintln!(
        "Code_Saturne check case on {nprocs} rank(s): {} contacts, {} rebounds, {} captured",
        counts.iter().sum::<usize>(),
        counts[0],
        counts[1]
    );
    // The case is built so that all three zones are hit, and slow particles are captured.
    assert!(counts[0] > 500 && counts[1] >= 10 && zones.len() == 3, "{counts:?} {zones:?}");
    assert_eq!(counts[2] + counts[3], 0, "every recorded contact moves into the wall with finite velocity");
    // Code_Saturne's own accounting counts depo's captures as its deposits: the listing's
    // per-step "deposited" lines add up to them (over all ranks).
    let deposited: usize = listing
        .lines()
        .filter_map(|l| l.strip_prefix("ln  deposited"))
        .map(|l| l.split_whitespace().next().unwrap().parse::<usize>().unwrap())
        .sum();
    assert_eq!(deposited, counts[1], "Code_Saturne's deposited count against depo's captures");

    // Code_Saturne's boundary statistics, accumulated over the run and written per face at the
    // last step (depo_check_statistics.c), summed over each zone's faces and the ranks.
    let stats = rank_files(&resu, "depo_boundary_stats");
    assert_eq!(stats.len(), nprocs, "one statistics file per rank");
    // The check case's step and duration (cs_user_parameters.c) and particle density
    // (cs_user_lagr_volume_conditions.c); every particle has a statistical weight of 1.
    let (dt, duration, density) = (1e-3, 0.1, 8000.0);
    let mass = density * std::f64::consts::PI / 6.0 * diameter.powi(3);
    #[derive(Default, Debug)]
    struct Sums {
        impact_number: f64,
        events: f64,
        speed: f64,
        angle: f64,
        mass: f64,
    }
    let mut sums: HashMap<u32, Sums> = HashMap::new();
    for csv in &stats {
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let col = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}"));
        for line in lines {
            let f: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
            let s = sums.entry(f[col("zone")] as u32).or_default();
            // The events' weight accumulates each event's statistical weight times the step.
            let weight = f[col("particle_events_weight")] / dt;
            s.impact_number += f[col("impact_number")];
            s.events += weight;
            s.speed += weight * f[col("mean_particle_impact_velocity")];
            s.angle += weight * f[col("mean_particle_impact_angle")];
            s.mass += f[col("mean_particle_mass_flux")] * f[col("area")] * duration;
        }
    }
    for (zone, c) in &zones {
        let (name, _) = &laws[zone];
        let s = &sums[zone];
        let contacts = (c.rebounds + c.captures) as f64;
        let (speed, angle) = speeds[zone];
        let what = format!("{name} on {nprocs} rank(s): {c:?}, Code_Saturne's statistics {s:?}");
        assert!(contacts > 0.0 && s.impact_number > 0.0 && s.speed > 0.0, "{what}");
        // Its "particle/boundary interactions" (counted by the hook on a depo zone) and its
        // events: one per contact, rebound or capture.
        assert_eq!(s.impact_number, contacts, "Part_impact_number: {what}");
        assert!((s.events - contacts).abs() < 1e-9 * contacts, "events' weight: {what}");
        // The impact velocity and angle take every contact, captures included.
        assert!((s.speed - speed).abs() <= 1e-12 * speed, "impact velocity: {speed} against {what}");
        assert!((s.angle - angle).abs() <= 1e-7 * contacts, "impact angle: {angle} against {what}");
        // The mass flux takes the captures.
        let captured = c.captures as f64 * mass;
        assert!((s.mass - captured).abs() <= 1e-9 * mass, "mass flux: {captured} kg against {what}");
    }
    zones.into_iter().map(|(zone, c)| (laws[&zone].0.clone(), c)).collect()
}

#[test]
fn check_case_contacts_are_the_wall_law_to_round_off() {
    if !code_saturne_found("check_case_contacts_are_the_wall_law_to_round_off") {
        return;
    }
    let work = libdir().join("code-saturne");
    let prefix = install_prefix(&work);
    let serial = check_case(&work, &prefix, 1);

    // The same case on 2 ranks, as a user runs it: its particles start at random places (the
    // injection draws them in each cell, and each rank draws its own), so the counts are not
    // the serial run's, but each zone's captures (at most one a particle: binomial over the
    // 540 particles) and rebounds (several a particle: Poisson) must agree within three
    // standard errors.
    if !mpi_found("check_case_contacts_are_the_wall_law_to_round_off on 2 ranks") {
        return;
    }
    let parallel = check_case(&work, &prefix, 2);
    let particles = 540.0;
    for (name, one) in &serial {
        let two = parallel.get(name).copied().unwrap_or_default();
        let (p1, p2) = (one.captures as f64 / particles, two.captures as f64 / particles);
        let p = (p1 + p2) / 2.0;
        let captures_error = (2.0 * p * (1.0 - p) / particles).sqrt();
        assert!((p1 - p2).abs() <= 3.0 * captures_error, "{name}: captures {one:?} on 1 rank, {two:?} on 2");
        let rebounds_error = ((one.rebounds + two.rebounds) as f64).sqrt();
        assert!(
            (one.rebounds as f64 - two.rebounds as f64).abs() <= 3.0 * rebounds_error,
            "{name}: rebounds {one:?} on 1 rank, {two:?} on 2"
        );
    }
}

/// The wall function in the channel case, small: the flow developed as in the full case, then
/// 10000 particles of each of two classes, `tau+` 3 (the diffusion-impaction regime, where
/// Wood's `V+` rises as `tau+^2`) and 30 (Wood's plateau), for 0.3 s, the first 0.05 s left
/// out. A particle in a wall cell deposits at the rate `v_wf / layer`, so the walls take the
/// flux `v_wf C_w`: `V+ = v_wf / u* x C_w / C`, with `C_w / C` the wall cells' concentration
/// over the mean, counted in the same run. Measured and expected must agree within three
/// combined standard errors (the deposits' Poisson error and the block error of `C_w / C`).
/// The only bias, the second-order term of `1 - exp(-v_wf dt / layer)` and the census counting
/// the wall cells after the step's deposits, is below 0.3 % here: no tolerance is added.
#[test]
fn channel_wall_function_deposits_what_the_correlation_gives() {
    if !code_saturne_found("channel_wall_function_deposits_what_the_correlation_gives") {
        return;
    }
    let start = std::time::Instant::now();
    let work = libdir().join("code-saturne-wall-function");
    let prefix = install_prefix(&work);
    let channel = work.join("channel");
    let out = run(Command::new("bash")
        .arg(root().join("integrations/code_saturne/run_channel.sh"))
        .arg(&channel)
        .env("DEPO_PREFIX", &prefix)
        .env("CHANNEL_STAGES", "wall-function")
        .env("CHANNEL_CLASSES", "3,30")
        .env("CHANNEL_WF_PARTICLES", "10000")
        .env("CHANNEL_PARTICLE_STEPS", "1500")
        .env("CHANNEL_TRANSIENT", "0.05"));
    eprintln!("{}", String::from_utf8_lossy(&out.stdout));
    let csv = std::fs::read_to_string(channel.join("channel_peer.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}"));
    let mut checked = 0;
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f[col("model")], "depo-wall-function", "{line}");
        let num = |name: &str| f[col(name)].parse::<f64>().unwrap_or_else(|_| panic!("{name} in {line}"));
        let (v_plus, v_error, expected, e_error) =
            (num("v_plus"), num("v_plus_error"), num("expected"), num("expected_error"));
        let deposits = num("deposits");
        assert!(deposits >= 100.0, "too few deposits to test: {line}");
        let combined = (v_error * v_error + e_error * e_error).sqrt();
        assert!(
            (v_plus - expected).abs() <= 3.0 * combined,
            "tau+ {}: V+ {v_plus:.4e} against v_wf/u* x C_w/C = {expected:.4e} (3 errors: {:.2e}): {line}",
            f[col("tau_plus")],
            3.0 * combined
        );
        checked += 1;
    }
    assert_eq!(checked, 2, "both classes reported");
    eprintln!("Code_Saturne channel with the wall function: {:.0} s", start.elapsed().as_secs_f64());
}

/// The duct case (`integrations/code_saturne/duct_case`, 2 m at 1 m/s, gravity across it,
/// 8000 particles each of 10, 30 and 100 um) with the wall function on every wall, whole (its
/// flow stage, then the wall-function run restarted from the developed flow): per size, the
/// deposits the hook drew against the sum, over the steps and the particles in wall cells, of
/// the chance `1 - prod(1 - P_f)` the duct's census computes before the hook
/// draws, from the face's `ustar` and the cell's extent from the duct's geometry (the
/// correlation's flux `v_d C_w` in number), within three binomial standard errors. About
/// 45 s, both runs' compilation included. With the hook's chance halved it fails at every
/// size: 106, 1291 and 7942 deposits against 244, 2596 and 15924 predicted (9, 26 and 64
/// errors; the prediction grows as the particles stay longer in the wall cells).
#[test]
fn duct_wall_function_deposits_what_the_correlation_predicts() {
    if !code_saturne_found("duct_wall_function_deposits_what_the_correlation_predicts") {
        return;
    }
    let start = std::time::Instant::now();
    let work = libdir().join("code-saturne-duct-wall-function");
    let prefix = install_prefix(&work);
    let duct = work.join("duct");
    run(Command::new("bash")
        .arg(root().join("integrations/code_saturne/run_duct.sh"))
        .arg(&duct)
        .env("DEPO_PREFIX", &prefix)
        .env("DUCT_WALLS", "wall-function"));
    let resu = duct.join("wall-function/study/case/RESU/run");
    let listing = std::fs::read_to_string(resu.join("listing")).unwrap();
    for zone in ["floor", "ceiling", "sides"] {
        assert!(listing.contains(&format!("depo: zone \"{zone}\" (id ")), "{zone} not a wall-function zone");
    }
    let csv = std::fs::read_to_string(resu.join("duct_wall_function.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}"));
    let mut sizes = 0;
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let num = |name: &str| f[col(name)].parse::<f64>().unwrap_or_else(|_| panic!("{name} in {line}"));
        let (deposited, expected, variance) = (num("deposited"), num("expected"), num("expected_variance"));
        assert!(deposited >= 100.0, "too few deposits to test: {line}");
        assert!(
            (deposited - expected).abs() <= 3.0 * variance.sqrt(),
            "d {}: {deposited} deposits against {expected:.1} predicted (3 errors: {:.1}): {line}",
            f[col("diameter")],
            3.0 * variance.sqrt()
        );
        // The duct's faces all have the wall functions' friction velocity.
        assert!(num("floor_ustar") > 0.01 && num("sides_ustar") > 0.01, "{line}");
        sizes += 1;
    }
    assert_eq!(sizes, 3, "every size reported");
    eprintln!("Code_Saturne duct with the wall function: {:.0} s", start.elapsed().as_secs_f64());
}

/// The duct's figure (`docs/figures/code-saturne-duct.svg`) is what `duct_report.py --figure`
/// draws from the report's stored CSV files (`integrations/code_saturne/duct.csv`,
/// `duct_wall_function.csv`), byte for byte, so neither the figure nor the tables can drift from
/// the other; and Code_Saturne's deposition model is among its series: its bars in the
/// fates' panel for every size and place, and its triangle beside the wall function's deposits
/// for every size. Needs Python 3 only.
#[test]
fn duct_figure_is_what_the_stored_csvs_draw_with_the_deposition_model() {
    let dir = root().join("integrations/code_saturne");
    let work = libdir().join("code-saturne-duct-figure");
    std::fs::create_dir_all(&work).unwrap();
    let svg = work.join("duct.svg");
    run(Command::new("python3")
        .arg(dir.join("duct_report.py"))
        .arg("--figure")
        .arg(dir.join("duct.csv"))
        .arg(dir.join("duct_wall_function.csv"))
        .arg(&svg));
    let drawn = std::fs::read_to_string(&svg).unwrap();
    let stored = std::fs::read_to_string(root().join("docs/figures/code-saturne-duct.svg")).unwrap();
    assert!(
        drawn == stored,
        "docs/figures/code-saturne-duct.svg is not what duct_report.py --figure draws from the stored CSV files: redraw it"
    );
    let duct = std::fs::read_to_string(dir.join("duct.csv")).unwrap();
    let model_rows = duct.lines().filter(|l| l.split(',').nth(1) == Some("model")).count();
    assert_eq!(
        model_rows,
        3 * 5,
        "the model's fate of each size in duct.csv (floor, ceiling, sides, airborne, outlet)"
    );
    // The model's colour: one bar per size and place in the fates' panel (3 sizes x 4 places)
    // and its legend's square, and one triangle per size and its legend's in the other panel.
    let green = "fill=\"#2ca02c\"";
    let bars = drawn.lines().filter(|l| l.starts_with("<rect") && l.contains(green)).count();
    assert_eq!(bars, 3 * 4 + 1, "the model's bars and legend in the fates' panel");
    let triangles = drawn.lines().filter(|l| l.contains("<path") && l.contains(green)).count();
    assert_eq!(triangles, 3 + 1, "the model's deposited fraction for each size and its legend");
    assert!(drawn.contains("Code_Saturne deposition model"), "the model's legend");
}
