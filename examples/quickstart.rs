//! The wall law in a few lines: the paper's presets, their coefficients, and one batch of a
//! million random impacts on a floor with the tally it produces.
//!
//! `cargo run --release --example quickstart`

use depo::bench::Workload;
use depo::wall_model::{Impacts, LawParams, Normals, Tally, WallLaw, PRESETS};

fn main() {
    println!("Brach & Dunn (1998) Table 1 presets (p = 1, mu = 0 as published)");
    println!(
        "{:<22} {:>8} {:>7} {:>7} {:>4} {:>8} {:>8} {:>8}",
        "id", "k", "kappa", "vc", "q", "R(vc)", "e(1m/s)", "e(5m/s)"
    );
    for preset in &PRESETS {
        let law = WallLaw::new(preset.params).expect("presets are valid");
        let lp = preset.params;
        let rc = if lp.vc > 0.0 { format!("{:.3}", law.restitution(lp.vc)) } else { "-".into() };
        println!(
            "{:<22} {:>8.1} {:>7.3} {:>7.3} {:>4} {:>8} {:>8.4} {:>8.4}{}",
            preset.id,
            lp.k1,
            lp.kappa1,
            lp.vc,
            lp.q,
            rc,
            law.overall_restitution(1.0),
            law.overall_restitution(5.0),
            if preset.reconstructed { "  (k reconstructed)" } else { "" }
        );
    }

    // A million impacts of 70 um steel spheres on SiO2, with friction, on a floor (normal +z).
    let law =
        WallLaw::new(LawParams { mu: 0.3, ..depo::wall_model::presets::preset("sim-70um").unwrap().params }).unwrap();
    let n = 1_000_000;
    let mut work = Workload::<f64>::random(n, false, 1);
    let [vx, vy, vz] = &mut work.v;
    let batch = Impacts::new([vx, vy, vz], Normals::Uniform([0.0, 0.0, 1.0]), &mut work.outcome).unwrap();
    let mut tally = Tally::default();
    let start = std::time::Instant::now();
    law.apply(batch, Some(&mut tally));
    let elapsed = start.elapsed();
    let e = tally.energy;
    println!("\n{n} impacts (|vn| 0.01..10 m/s, log-uniform) with sim-70um and mu = 0.3:");
    println!(
        "  rebound {}  captured {}  skipped {}  invalid {}",
        tally.rebound, tally.captured, tally.skipped, tally.invalid
    );
    println!(
        "  energy lost per unit mass, summed (J/kg): material {:.4e}  adhesion {:.4e}  friction {:.4e}  deposited {:.4e}",
        e.material, e.adhesion, e.friction, e.deposition
    );
    println!(
        "  {:.1} ms ({:.0} million impacts/s, tally on)",
        elapsed.as_secs_f64() * 1e3,
        n as f64 / elapsed.as_secs_f64() / 1e6
    );
}
