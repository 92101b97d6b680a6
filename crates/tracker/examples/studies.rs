//! Runs the channel and room studies with their defaults and prints each point beside its
//! correlation: `cargo run --release -p depo-tracker --example studies [channel|room]`.

use depo_tracker::studies::{ChannelStudy, RoomStudy};

fn main() {
    let which = std::env::args().nth(1).unwrap_or_else(|| "channel".into());
    let start = std::time::Instant::now();
    if which == "channel" {
        let study = ChannelStudy::default();
        for p in study.run(|_| {}).unwrap() {
            println!(
                "tau+ {:7.2}  d {:6.2} um  V+ {:.3e} +- {:.1e} ({:5} deposits)  Wood {:.3e}  P&H {:.3e}  ratio {:.2}",
                p.tau_plus,
                p.diameter * 1e6,
                p.v_plus.value,
                p.v_plus.error,
                p.v_plus.events,
                p.wood,
                p.papavergos_hedley,
                p.v_plus.value / p.wood
            );
        }
    } else {
        let study = RoomStudy::default();
        for p in study.run(|_| {}).unwrap() {
            println!(
                "d {:6.3} um  floor {:.2e} ({:.2e})  ceiling {:.2e} ({:.2e})  walls {:.2e} ({:.2e})  beta {:.3}/h ({:.3}/h) [{} {} {}]",
                p.diameter * 1e6,
                p.floor.value,
                p.model.floor,
                p.ceiling.value,
                p.model.ceiling,
                p.walls.value,
                p.model.wall,
                p.beta.value * 3600.0,
                p.model_beta * 3600.0,
                p.floor.events,
                p.ceiling.events,
                p.walls.events
            );
        }
    }
    eprintln!("{:.1} s", start.elapsed().as_secs_f64());
}
