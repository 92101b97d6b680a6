//! The deposition wall function for host solvers whose meshes do not resolve the near-wall
//! layer (see the tracker's `wall_function` module, the one source of its formulas).

use depo_tracker::correlations::HUSSEIN_TOP;
use depo_tracker::wall_function::{deposition_probability, deposition_velocity_cached, Correlation};
use depo_tracker::{Aerodynamics, Air, Orientation};

use super::{check_disjoint, required, set_last_error, slice, slice_mut, span, Failure, DEPO_ERR_PANIC, DEPO_OK};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Wood (1981): `V+ = 0.057 Sc^(-2/3) + 4.5e-4 tau+^2`, at most 0.13; ducts and channels,
/// every surface alike.
pub const DEPO_CORRELATION_WOOD: i32 = 0;
/// Papavergos & Hedley (1984): `0.065 Sc^(-2/3)`, `3.5e-4 tau+^2`, `0.18` by regime; ducts
/// and channels, every surface alike.
pub const DEPO_CORRELATION_PAPAVERGOS_HEDLEY: i32 = 1;
/// Lai & Nazaroff (2000): a room's floor, ceiling and walls by orientation, with settling.
pub const DEPO_CORRELATION_LAI_NAZAROFF: i32 = 2;
/// Hussein, Smolík, Kerminen & Kulmala (2012, Aerosol Sci. Technol. 46:44-59): by orientation
/// as Lai & Nazaroff's, with settling and turbophoresis (an Eulerian drift-flux model across
/// the layer from the particle's radius to `y+ = 100`, where its reference concentration is
/// taken), for vertical surfaces under stronger turbulence than a room's. Its velocity is an
/// integral across that layer, far costlier than the others; each thread keeps the velocities
/// of up to 65536 distinct inputs (friction velocity, diameter, density, orientation, gas and
/// gravity; then it starts again empty), so a host calling per particle per step pays the
/// integral once per particle size and friction velocity while these stay the same. A
/// particle whose radius reaches 100 wall units (`d u* / (2 nu) >= 100`) is outside the
/// model's layer and refused.
pub const DEPO_CORRELATION_HUSSEIN: i32 = 3;

/// An upward-facing surface (a floor; gravity towards it).
pub const DEPO_SURFACE_FLOOR: i32 = 0;
/// A downward-facing surface (a ceiling).
pub const DEPO_SURFACE_CEILING: i32 = 1;
/// A vertical surface.
pub const DEPO_SURFACE_WALL: i32 = 2;

/// The carrier gas: temperature (K), pressure (Pa), density (kg/m^3) and dynamic viscosity
/// (Pa s). Dry air at 20 C and one atmosphere is `{293.15, 101325, 1.204, 1.81e-5}`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DepoAir {
    pub temperature: f64,
    pub pressure: f64,
    pub density: f64,
    pub viscosity: f64,
}

/// The smallest and largest particle diameters the correlations are used for, m.
const DIAMETERS: (f64, f64) = (1e-9, 1e-3);

/// The call's inputs, checked: everything a particle's velocity needs but its own values.
struct Surface {
    correlation: Correlation,
    orientation: Orientation,
    air: Air,
    gravity: f64,
}

impl Surface {
    unsafe fn new(correlation: i32, orientation: i32, air: *const DepoAir, gravity: f64) -> Result<Self, Failure> {
        let correlation = match correlation {
            DEPO_CORRELATION_WOOD => Correlation::Wood,
            DEPO_CORRELATION_PAPAVERGOS_HEDLEY => Correlation::PapavergosHedley,
            DEPO_CORRELATION_LAI_NAZAROFF => Correlation::LaiNazaroff,
            DEPO_CORRELATION_HUSSEIN => Correlation::Hussein,
            other => return Err(Failure::invalid(format!("correlation = {other} is not a DEPO_CORRELATION_*"))),
        };
        let orientation = match orientation {
            DEPO_SURFACE_FLOOR => Orientation::Floor,
            DEPO_SURFACE_CEILING => Orientation::Ceiling,
            DEPO_SURFACE_WALL => Orientation::Wall,
            other => return Err(Failure::invalid(format!("orientation = {other} is not a DEPO_SURFACE_*"))),
        };
        let a = required(air, "air")?;
        for (name, v) in [
            ("temperature", a.temperature),
            ("pressure", a.pressure),
            ("density", a.density),
            ("viscosity", a.viscosity),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Failure::invalid(format!("air.{name} = {v} is not finite and positive")));
            }
        }
        if !(gravity.is_finite() && gravity >= 0.0) {
            return Err(Failure::invalid(format!("gravity = {gravity} is not finite and not negative")));
        }
        let air = Air { temperature: a.temperature, pressure: a.pressure, density: a.density, viscosity: a.viscosity };
        Ok(Self { correlation, orientation, air, gravity })
    }

    /// The deposition velocity (m/s) of particle `i`, its inputs checked.
    fn velocity(&self, i: usize, friction_velocity: f64, diameter: f64, density: f64) -> Result<f64, Failure> {
        let bad = |name: &str, v: f64, what: &str| Err(Failure::invalid(format!("{name}[{i}] = {v} {what}")));
        if !(friction_velocity.is_finite() && friction_velocity > 0.0) {
            return bad("friction_velocity", friction_velocity, "is not finite and positive");
        }
        if !(diameter >= DIAMETERS.0 && diameter <= DIAMETERS.1) {
            return bad("diameter", diameter, "is not between 1 nm and 1 mm");
        }
        if !(density.is_finite() && density > self.air.density) {
            return bad("density", density, "is not finite and above the gas's");
        }
        if self.correlation == Correlation::Hussein {
            let r_plus = 0.5 * diameter * friction_velocity / self.air.kinematic_viscosity();
            if r_plus >= HUSSEIN_TOP {
                return Err(Failure::invalid(format!(
                    "diameter[{i}] = {diameter} at friction_velocity[{i}] = {friction_velocity} is a radius of \
                     {r_plus} wall units, not below the {HUSSEIN_TOP} of Hussein et al.'s layer"
                )));
            }
        }
        let aero = Aerodynamics::new(diameter, density, &self.air, self.gravity);
        // Hussein et al.'s velocity is an integral across the layer (about 0.8 ms); the
        // tracker's per-thread cache keeps it, so a host calling per particle per step pays
        // it once per size, surface and `u*`.
        Ok(deposition_velocity_cached(self.correlation, &aero, &self.air, friction_velocity, self.orientation))
    }
}

/// The deposition velocity (m/s) that `correlation` gives onto a smooth surface facing
/// `orientation`, for `n` particles of `diameter` (m) and `density` (kg/m^3) in `air` under
/// `gravity` (m/s^2, magnitude; it acts towards floors), each with the friction velocity of its
/// wall cell `friction_velocity` (m/s): what an Eulerian wall function multiplies the wall
/// cell's concentration by. A correlation or orientation that is not a `DEPO_*` value, an air
/// value that is not finite and positive, a negative gravity, a friction velocity that is not
/// finite and positive, a diameter outside 1 nm to 1 mm, a density not above the gas's, with
/// `DEPO_CORRELATION_HUSSEIN` a radius of 100 wall units or more, or `velocity` overlapping an
/// input is `DEPO_ERR_INVALID` and writes nothing.
#[no_mangle]
pub unsafe extern "C" fn depo_deposition_velocity(
    correlation: i32,
    orientation: i32,
    air: *const DepoAir,
    gravity: f64,
    n: usize,
    friction_velocity: *const f64,
    diameter: *const f64,
    density: *const f64,
    velocity: *mut f64,
) -> i32 {
    ffi_guard!({
        let surface = Surface::new(correlation, orientation, air, gravity)?;
        let u = slice(friction_velocity, n, "friction_velocity")?;
        let d = slice(diameter, n, "diameter")?;
        let rho = slice(density, n, "density")?;
        let out = slice_mut(velocity, n, "velocity")?;
        let inputs = [("friction_velocity", span(u)), ("diameter", span(d)), ("density", span(rho))];
        check_disjoint(&[inputs[0], inputs[1], inputs[2], ("velocity", span(out))])?;
        let v: Vec<f64> = (0..n).map(|i| surface.velocity(i, u[i], d[i], rho[i])).collect::<Result<_, _>>()?;
        out.copy_from_slice(&v);
        Ok(())
    })
}

/// The chance that a particle in a wall cell deposits within a step of `dt` (s), for `n`
/// particles: `probability[i] = 1 - exp(-v_d dt / layer[i])`, with `v_d` the deposition
/// velocity of `depo_deposition_velocity` and `layer[i]` the thickness (m) of the near-wall
/// layer the particle is in: its wall cell's extent normal to the wall (twice the cell centre's
/// wall distance for a cell with a face on the wall).
///
/// A wall cell holding the concentration `C` then deposits the correlation's flux `v_d C`. Draw
/// a uniform number per particle; below `probability[i]` the particle reaches the wall in this
/// step: deposit it, or hand its velocity (its normal component turned towards the wall) to
/// `depo_apply_f64` where the wall has a Brach & Dunn law. The wall itself should then
/// reflect particles, so that none deposits twice. Its errors are those of
/// `depo_deposition_velocity`, and a `dt` or `layer[i]` that is not finite and positive.
#[no_mangle]
pub unsafe extern "C" fn depo_wall_function_probability(
    correlation: i32,
    orientation: i32,
    air: *const DepoAir,
    gravity: f64,
    dt: f64,
    n: usize,
    friction_velocity: *const f64,
    layer: *const f64,
    diameter: *const f64,
    density: *const f64,
    probability: *mut f64,
) -> i32 {
    ffi_guard!({
        let surface = Surface::new(correlation, orientation, air, gravity)?;
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Failure::invalid(format!("dt = {dt} is not finite and positive")));
        }
        let u = slice(friction_velocity, n, "friction_velocity")?;
        let y = slice(layer, n, "layer")?;
        let d = slice(diameter, n, "diameter")?;
        let rho = slice(density, n, "density")?;
        let out = slice_mut(probability, n, "probability")?;
        check_disjoint(&[
            ("friction_velocity", span(u)),
            ("layer", span(y)),
            ("diameter", span(d)),
            ("density", span(rho)),
            ("probability", span(out)),
        ])?;
        let p: Vec<f64> = (0..n)
            .map(|i| {
                if !(y[i].is_finite() && y[i] > 0.0) {
                    return Err(Failure::invalid(format!("layer[{i}] = {} is not finite and positive", y[i])));
                }
                Ok(deposition_probability(surface.velocity(i, u[i], d[i], rho[i])?, y[i], dt))
            })
            .collect::<Result<_, _>>()?;
        out.copy_from_slice(&p);
        Ok(())
    })
}
