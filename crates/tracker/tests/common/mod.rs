//! Checks shared by the furnishings' and the openings' tests: what a run's records must
//! satisfy that the mass balance's own counts cannot make true.

use std::collections::HashSet;

use depo_tracker::{Fate, Injection, OpeningKind, Record, Run, Scene, WallBehaviour};

/// Whether a particle of `record` overlaps a box's interior (touching a face is allowed).
pub fn inside_a_box(scene: &Scene, record: &Record) -> bool {
    let r = 0.5 * record.diameter;
    // Touching means a centre exactly `r` from the face: shrink the reach by a rounding margin.
    scene.furnishings.iter().any(|b| b.holds(record.position, r * (1.0 - 1e-9) - 1e-15))
}

/// Checks of a run's records that the mass balance's own counts cannot make true: each one
/// compares a record with something counted or known apart from it.
///
/// - One record per injected particle, no two from the same start (none lost or duplicated).
/// - No particle escaped (none left the room through a wall or went non-finite).
/// - Each surface's deposits by the records equal its own tally, counted at the contact
///   (captures plus resting), surface by surface and summed over every wall and face; a sink
///   captures at every contact and a mirror captures nothing.
/// - A deposit rests on the air side of its surface, its centre one radius off the plane and
///   within the surface's extent (a face's box grown by a few radii).
/// - An airborne particle ends in the room's air, a radius or more from every wall, at the
///   run's end.
/// - An exhausted particle left within an exhaust opening, at the opening's wall; the
///   uniform exhaust (no openings) takes a particle from the air.
/// - A particle that left (deposited or exhausted) left within its last step.
/// - No particle ends overlapping a box's interior.
pub fn check_records(scene: &Scene, injection: &Injection, result: &Run) {
    let n = injection.count;
    assert_eq!(result.records.len(), n, "one record per injected particle");
    assert_eq!(result.particles.len(), n);
    let starts: HashSet<[u64; 3]> = result.records.iter().map(|r| r.start.map(f64::to_bits)).collect();
    assert_eq!(starts.len(), n, "no particle is recorded twice");
    let b = result.balance();
    assert_eq!(b.escaped, 0, "{b:?}");
    let behaviours = scene.surface_behaviours();
    assert_eq!(result.tallies.len(), result.walls.len());
    let mut tallied = 0;
    for (w, t) in result.tallies.iter().enumerate() {
        let from_records = result.records.iter().filter(|r| r.fate == Fate::Deposited(w)).count();
        assert_eq!((t.captures + t.resting) as usize, from_records, "surface {w}: {t:?}");
        match behaviours[w] {
            WallBehaviour::Sink => assert!(t.captures == t.contacts && t.rebounds == 0, "sink {w}: {t:?}"),
            WallBehaviour::Reflect => assert_eq!(t.captures, 0, "mirror {w}: {t:?}"),
            WallBehaviour::Law { .. } => {}
        }
        tallied += (t.captures + t.resting) as usize;
    }
    let deposited = result.records.iter().filter(|r| matches!(r.fate, Fate::Deposited(_))).count();
    assert_eq!(tallied, deposited, "deposits tallied at contact against deposits recorded");
    let size = scene.geometry.size();
    let steps = result.steps();
    // In the room's air: a radius or more from every wall (with a rounding margin).
    let in_air = |r: &Record| {
        let (radius, slack) = (0.5 * r.diameter, 5e-10 * r.diameter + 1e-15);
        (0..3).all(|a| r.position[a] > radius - slack && r.position[a] < size[a] - radius + slack)
    };
    for r in &result.records {
        let radius = 0.5 * r.diameter;
        // A rounding margin on distances of a radius.
        let slack = 1e-9 * radius + 1e-15;
        match r.fate {
            Fate::Deposited(w) => {
                let wall = result.walls[w];
                let gap = (r.position[wall.axis] - wall.position) * wall.normal()[wall.axis];
                assert!((gap - radius).abs() < 1e-12, "{r:?} on {wall:?}");
                let (low, high) = match wall.furnishing {
                    Some(k) => (scene.furnishings[k].low, scene.furnishings[k].high),
                    None => ([0.0; 3], size),
                };
                let reach = if wall.furnishing.is_some() { 3.0 * radius } else { slack };
                assert!(
                    (0..3).all(|a| r.position[a] > low[a] - reach && r.position[a] < high[a] + reach),
                    "{r:?} off {wall:?}"
                );
            }
            Fate::Airborne => {
                assert!(in_air(r) && r.steps == steps && r.time == result.duration, "{r:?}");
            }
            Fate::Exhausted if scene.openings.is_empty() => {
                // The uniform exhaust takes a particle from wherever it is in the air.
                assert!(in_air(r), "{r:?}");
            }
            Fate::Exhausted => {
                // Within an exhaust opening, at its wall's contact plane: a radius off the wall,
                // plus with Brownian motion the continuity correction's part of a step (a few
                // um at most here).
                let at_exhaust = scene.openings.iter().filter(|o| o.kind == OpeningKind::Exhaust).any(|o| {
                    let wall = result.walls[o.wall];
                    let gap = (r.position[wall.axis] - wall.position) * wall.normal()[wall.axis];
                    o.holds(r.position) && gap > radius - slack && gap < radius + 5e-6
                });
                assert!(at_exhaust, "{r:?}");
            }
            Fate::Escaped => {}
        }
        if r.fate != Fate::Airborne {
            let step = r.steps as f64 * result.dt;
            assert!(r.steps >= 1 && r.steps <= steps, "{r:?}");
            assert!(r.time > step - result.dt * (1.0 + 1e-9) && r.time <= step * (1.0 + 1e-12), "{r:?}");
        }
        assert!(!inside_a_box(scene, r), "{r:?}");
    }
}
