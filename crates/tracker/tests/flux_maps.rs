//! Deposition maps of the run's estimator (`depo_tracker::maps`): per cell, the deposition
//! velocity the surface's figure is made of.

use depo_tracker::maps::{FluxMap, MAP_RESOLVED_ERROR};
use depo_tracker::{
    run, Correlation, Excursions, Flow, Furnishing, Geometry, Injection, RunSettings, Scene, SizeDistribution,
    WallFunction,
};

fn mono(count: usize, diameter: f64) -> Injection {
    Injection::new(count, SizeDistribution::Monodisperse { diameter }, 1000.0)
}

/// The box a surface's map spans: the room's, or its furnishing's.
fn extent(scene: &Scene, furnishing: Option<usize>) -> ([f64; 3], [f64; 3]) {
    match furnishing {
        Some(k) => (scene.furnishings[k].low, scene.furnishings[k].high),
        None => ([0.0; 3], scene.geometry.size()),
    }
}

/// With excursions (weighted deposits) in a turbulent room with a table: on every surface,
/// every map's cells integrated over the surface give the surface's deposition velocity, and
/// its events, to rounding; on the one-cell grid the cell is the surface's figure, its
/// standard error too (the same estimator); a cell without an event has the bound of three
/// of the smallest deposits over its area.
#[test]
fn cells_add_up_to_each_surface_s_figure() {
    let mut scene = Scene::new(Geometry::Room { size: [1.5, 1.0, 1.0] });
    let mut settings = RunSettings::new(0.05, 300.0);
    scene.flow = Flow::indoor_room();
    scene.brownian = true;
    settings.average_from = 20.0;
    scene.furnishings = vec![Furnishing::new([0.2, 0.2, 0.4], [0.8, 0.8, 0.45]).named("table")];
    let nu = scene.air.kinematic_viscosity();
    settings.excursions = Some(Excursions::in_wall_units(0.01, nu, 0.05, 2.0, 4000.0));
    let result = run(&scene, &settings, &mono(400, 0.02e-6)).unwrap();
    let mut mapped = 0;
    for w in &result.walls {
        let figure = result.deposition_velocity(&[w.id]);
        let (low, high) = extent(&scene, w.furnishing);
        let resolved = result.resolved_flux_map(w.id, low, high).unwrap();
        for map in [resolved, result.flux_map(w.id, low, high, [7, 5]).unwrap()] {
            let events: usize = map.cells.iter().map(|c| c.events).sum();
            assert_eq!(events, figure.events, "surface {}", w.id);
            let v = map.integrated(w.area);
            assert!((v - figure.value).abs() <= 1e-9 * figure.value, "surface {}: {v} against {figure:?}", w.id);
            // Empty cells: the rule of three over the cell's area.
            let exposure: f64 = result.particles.iter().map(|p| p.exposure).sum();
            let bound = 3.0 * result.smallest_weight / exposure * result.volume / map.cell_area();
            for c in map.cells.iter().filter(|c| c.events == 0) {
                assert_eq!((c.value, c.error), (0.0, 0.0));
                assert!((c.upper_bound / bound - 1.0).abs() < 1e-12, "{c:?}");
            }
        }
        let whole = result.flux_map(w.id, low, high, [1, 1]).unwrap();
        let cell = whole.cells[0];
        let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-300);
        assert!(same(cell.value * whole.cell_area() / w.area, figure.value), "{cell:?} against {figure:?}");
        // The figure's area may leave an opening out; none here, so the errors agree.
        assert!(same(cell.error, figure.error), "{cell:?} against {figure:?}");
        mapped += usize::from(figure.events > 0);
    }
    assert!(mapped >= 6, "deposits on {mapped} surfaces only");
}

/// Settling particles of 30 um in still air in a 2 m x 1 m x 1 m box (no turbulence, no
/// Brownian motion): they fall straight, so the floor's deposits within the window are uniform
/// over it and its map is flat within its errors: every resolved cell within 4.5 standard errors of
/// the floor's value, and their chi-square about it within 5 of its standard deviations of
/// its degrees of freedom. The grid is fine (at least 8 x 4 cells, three in four
/// resolved), the walls and ceiling have nothing, and the floor's figure is the column's:
/// with `N(t) = N0 (1 - v_s t / H)` airborne, the deposits over the window `[t0, t1]` per area
/// over the mean concentration are `v_d = v_s / (1 - v_s (t0 + t1) / (2 H))`, with `v_s` the
/// Stokes settling speed with Cunningham's slip (Hinds Eqs. 3.21, 3.20) computed here.
#[test]
fn pure_settling_gives_a_flat_floor() {
    let (h, t0, t1) = (1.0, 5.0, 30.0);
    let scene = Scene::new(Geometry::Room { size: [2.0, 1.0, h] });
    let mut settings = RunSettings::new(0.1, t1);
    settings.average_from = t0;
    let d = 30e-6;
    let result = run(&scene, &settings, &mono(20_000, d)).unwrap();
    let floor = result.resolved_flux_map(0, [0.0; 3], scene.geometry.size()).unwrap();
    assert!(floor.bins[0] >= 8 && floor.bins[1] >= 4, "{:?}", floor.bins);
    assert!(floor.resolved_share() >= 0.75);
    let figure = result.deposition_velocity(&[0]);
    let mut chi2 = 0.0;
    for (k, c) in floor.cells.iter().enumerate() {
        assert!(floor.resolved(k), "cell {k}: {c:?}");
        let z = (c.value - figure.value) / c.error;
        assert!(z.abs() < 4.5, "cell {k}: {c:?} against the floor's {figure:?}");
        chi2 += z * z;
    }
    let dof = (floor.cells.len() - 1) as f64;
    assert!((chi2 - dof).abs() < 5.0 * (2.0 * dof).sqrt(), "chi-square {chi2} on {dof} degrees of freedom");
    for w in 1..6 {
        assert_eq!(result.deposition_velocity(&[w]).events, 0, "wall {w}");
    }
    let air = &scene.air;
    let lambda = air.mean_free_path();
    let slip = 1.0 + lambda / d * (2.34 + 1.05 * (-0.39 * d / lambda).exp());
    let g = 9.807;
    let v_s = (1000.0 - air.density) * d * d * g * slip / (18.0 * air.viscosity);
    let expected = v_s / (1.0 - v_s * (t0 + t1) / (2.0 * h));
    assert!(
        (figure.value - expected).abs() < 4.0 * figure.error + 0.01 * expected,
        "floor {figure:?} against {expected}"
    );
    assert!(figure.error < MAP_RESOLVED_ERROR * figure.value);
}

/// The wall function's walls keep expected deposits without a place: no map, rather than
/// one that would not add up to their figure.
#[test]
fn the_wall_function_s_walls_have_no_map() {
    let mut scene = Scene::new(Geometry::Room { size: [1.0, 1.0, 1.0] });
    let settings = RunSettings::new(0.05, 30.0);
    scene.flow = Flow::indoor_room();
    scene.wall_function = Some(WallFunction::new(Correlation::LaiNazaroff));
    let result = run(&scene, &settings, &mono(100, 5e-6)).unwrap();
    let map: Option<FluxMap> = result.resolved_flux_map(0, [0.0; 3], [1.0; 3]);
    assert!(result.deposition_velocity(&[0]).value > 0.0);
    assert_eq!(map, None);
}
