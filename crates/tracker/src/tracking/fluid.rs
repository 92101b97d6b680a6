//! The fluid velocity a particle sees: the mean flow, the turbulent fluctuation carried by
//! its Langevin model, and Saffman's lift in a shear flow.

use glam::DVec3;

use crate::model::furnishing::{nearest_surfaces_within, Furnishing};
use crate::physics::intermittency::Intermittent;
use crate::physics::turbulence::{tangential_products, Component, FlowField, Node, Table};

use super::wall_distance;

/// The mean flow plus the fluctuation `sigma zeta` at `x`.
#[inline(always)]
pub(super) fn fluid_velocity<const TURB: bool>(field: &FlowField, size: [f64; 3], x: DVec3, zeta: &[f64; 3]) -> DVec3 {
    let mut u = DVec3::from_array(field.uniform);
    if let Some(profile) = &field.profile {
        u.x += profile.at(wall_distance(x.z, size[2]).0).sigma;
    }
    if TURB {
        if let Some(turb) = &field.turbulence {
            let at = |comp: &Component| comp.table.at(wall_distance(x.to_array()[comp.axis], size[comp.axis]).0);
            // Arrays written out: `array::map` here was left as a call per element.
            let nodes = [at(&turb[0]), at(&turb[1]), at(&turb[2])];
            let g = tangential_products([nodes[0].tangential, nodes[1].tangential, nodes[2].tangential]);
            for a in 0..3 {
                u[a] += g[a] * (nodes[a].sigma * zeta[a]);
            }
            if let Some(coupling) = &field.stress_coupling {
                u.x += stress_part(coupling, size, x, zeta[2]);
            }
        }
    }
    u
}

/// The part of a channel's streamwise fluctuation correlated with the wall-normal `zeta`,
/// `sign rho_uv u_rms zeta` (m/s; [`FlowField::stress_coupling`]).
#[inline(always)]
pub(super) fn stress_part(coupling: &Table, size: [f64; 3], x: DVec3, zeta_normal: f64) -> f64 {
    let (distance, sign) = wall_distance(x.z, size[2]);
    (sign * coupling.at(distance).sigma) * zeta_normal
}

/// The fluid velocity seen at `x` in a furnished room (mean plus `sigma zeta`), each
/// component's profile taken at its distance to the nearest surface along its axis, room
/// wall or furnishing face ([`nearest_surfaces`]); with `normals`, `zeta` is then taken one
/// exact Ornstein-Uhlenbeck step there ([`langevin_step`]), with the drift's sign that of
/// the change of that distance along the axis. The components along a surface are damped
/// by the room's walls only (see the comment below): a box's faces shape the component
/// across them, not those along them. Also returns each component's scale `g sigma` there,
/// what the midpoint scheme's next predictor reuses in a room (`Flyer::half_step_position`).
#[inline(always)]
pub(super) fn furnished_fluid_velocity(
    field: &FlowField,
    size: [f64; 3],
    boxes: &[Furnishing],
    x: DVec3,
    zeta: &mut [f64; 3],
    normals: Option<[f64; 3]>,
) -> (DVec3, [f64; 3]) {
    let mut u = DVec3::from_array(field.uniform);
    let mut scale = [0.0; 3];
    if let Some(profile) = &field.profile {
        u.x += profile.at(wall_distance(x.z, size[2]).0).sigma;
    }
    if let Some(turb) = &field.turbulence {
        let at = x.to_array();
        // A box beyond where the tables are flat changes no read.
        let nearest = nearest_surfaces_within(at, size, boxes, field.turbulence_flat_from);
        let ds = [nearest[turb[0].axis], nearest[turb[1].axis], nearest[turb[2].axis]];
        let nodes = [turb[0].table.at(ds[0].0), turb[1].table.at(ds[1].0), turb[2].table.at(ds[2].0)];
        // The tangential factors from the room's walls alone: the distance to the nearest
        // surface along an axis jumps where a box's shadow begins, and a factor that jumped
        // along another component's own axis would break the well-mixed condition there.
        // Where the nearest surface is a room wall the node read above is the one wanted
        // (the same distance in the same table): no second read.
        let tangential = |a: usize| {
            let room = wall_distance(at[turb[a].axis], size[turb[a].axis]).0;
            if room == ds[a].0 {
                nodes[a].tangential
            } else {
                turb[a].table.at(room).tangential
            }
        };
        let g = tangential_products([tangential(0), tangential(1), tangential(2)]);
        for a in 0..3 {
            scale[a] = g[a] * nodes[a].sigma;
            let sign = ds[a].1;
            match normals {
                Some(normals) => {
                    let (du, next) = langevin_step(&nodes[a], g[a], sign, zeta[a], normals[a]);
                    u[a] += du;
                    zeta[a] = next;
                }
                None => u[a] += g[a] * (nodes[a].sigma * zeta[a]),
            }
        }
    }
    (u, scale)
}

/// Saffman's (1965, erratum 1968) shear lift on a sphere in the mean shear `G = dU/dz` of a
/// channel, as an acceleration along `z` (m/s^2):
///
/// ```text
/// a_L = (9.69 / pi) sqrt(rho mu |G|) / (rho_p d) (u_x - v_x) sign(G)
/// ```
///
/// with `u_x - v_x` the streamwise slip of the particle against the fluid it sees: a particle
/// leading the fluid is pushed towards the slower fluid (the wall), a lagging one away from it.
/// Valid for `Re_G = |G| d^2 / nu << 1` and slip Reynolds numbers below `sqrt(Re_G)`; without
/// McLaughlin's (1993) wall correction it overstates the lift within a few diameters of the wall.
#[inline(always)]
pub(super) fn saffman_lift(field: &FlowField, size: [f64; 3], x: DVec3, uf: DVec3, v: DVec3, coefficient: f64) -> f64 {
    let Some(profile) = &field.profile else { return 0.0 };
    let (d, sign) = wall_distance(x.z, size[2]);
    let shear = profile.at(d).slope * sign;
    coefficient * shear.abs().sqrt() * (uf.x - v.x) * shear.signum()
}

/// The fluid velocity seen at `x` (mean plus `sigma zeta`), and one exact Ornstein-Uhlenbeck
/// step of the normalised fluctuations `zeta` there driven by the standard normals `normals`,
/// from one table lookup per component; and each component's scale `g sigma` there, as
/// [`furnished_fluid_velocity`] gives it.
#[inline(always)]
pub(super) fn fluid_velocity_and_fluctuation(
    field: &FlowField,
    size: [f64; 3],
    x: DVec3,
    zeta: &mut [f64; 3],
    normals: [f64; 3],
) -> (DVec3, [f64; 3]) {
    let mut u = fluid_velocity::<false>(field, size, x, zeta);
    let mut scale = [0.0; 3];
    if let Some(turb) = &field.turbulence {
        let distance = |comp: &Component| wall_distance(x.to_array()[comp.axis], size[comp.axis]);
        // Arrays written out: `array::map` here was left as a call per element.
        let ds = [distance(&turb[0]), distance(&turb[1]), distance(&turb[2])];
        let nodes = [turb[0].table.at(ds[0].0), turb[1].table.at(ds[1].0), turb[2].table.at(ds[2].0)];
        let g = tangential_products([nodes[0].tangential, nodes[1].tangential, nodes[2].tangential]);
        let zeta_normal = zeta[2];
        for a in 0..3 {
            scale[a] = g[a] * nodes[a].sigma;
            let (du, next) = langevin_step(&nodes[a], g[a], ds[a].1, zeta[a], normals[a]);
            u[a] += du;
            zeta[a] = next;
        }
        if let Some(coupling) = &field.stress_coupling {
            u.x += stress_part(coupling, size, x, zeta_normal);
        }
    }
    (u, scale)
}

/// As [`fluid_velocity_and_fluctuation`] in a channel with the intermittent near-wall model:
/// the streamwise and spanwise components as there, the wall-normal one's `zeta` stepped by
/// `model` over its step.
#[inline]
pub(super) fn intermittent_fluid_velocity(
    field: &FlowField,
    model: &Intermittent,
    size: [f64; 3],
    x: DVec3,
    zeta: &mut [f64; 3],
    normals: [f64; 3],
) -> DVec3 {
    let mut u = DVec3::from_array(field.uniform);
    let (distance, sign) = wall_distance(x.z, size[2]);
    if let Some(profile) = &field.profile {
        u.x += profile.at(distance).sigma;
    }
    if let Some(turb) = &field.turbulence {
        for a in 0..2 {
            let (du, next) = langevin_step(&turb[a].table.at(distance), 1.0, sign, zeta[a], normals[a]);
            u[a] += du;
            zeta[a] = next;
        }
        u.z += turb[2].table.at(distance).sigma * zeta[2];
        if let Some(coupling) = &field.stress_coupling {
            u.x += stress_part(coupling, size, x, zeta[2]);
        }
    }
    zeta[2] = model.step(distance, sign, zeta[2], normals[2]);
    u
}

/// The velocity `g sigma zeta` a fluctuating component adds to the fluid's at `node`, with
/// `g` its tangential factor ([`tangential_products`]; 1 in a channel), and `zeta` after one
/// exact Ornstein-Uhlenbeck step driven by the standard normal `normal`, with the well-mixed
/// drift where the table has one (`sign` the sign of `d(distance)/d(coordinate)`; the drift
/// follows the slope of `g sigma`, so it is scaled by `g` too).
#[inline(always)]
pub(super) fn langevin_step(node: &Node, g: f64, sign: f64, zeta: f64, normal: f64) -> (f64, f64) {
    (g * (node.sigma * zeta), (zeta * node.decay + node.noise * normal) + g * (sign * node.drift))
}

#[cfg(test)]
mod tests {
    use rand_distr::{Distribution, StandardNormal};

    use super::*;
    #[test]
    fn channel_fluctuations_carry_the_reynolds_shear_stress() {
        // At y+ = 20 (y/h = 0.1333 of a Re_tau = 150 channel; u* = 1 m/s, nu = 1 m^2/s, so
        // metres are wall units), with the three zetas standard normals as the Langevin steps
        // keep them: the streamwise and wall-normal velocities' correlation is rho_uv of the
        // DNS table, interpolated here between its points at y/h 0.1299 and 0.1423, and the
        // streamwise rms the Kallio & Reeks fit, 0.4 * 20 / (1 + 0.0239 * 20^1.496). Near the
        // upper wall the correlation changes sign.
        let size = [1000.0, 300.0, 300.0];
        let field = FlowField::new(&crate::Flow::TurbulentChannel { friction_velocity: 1.0 }, size, 1.0, 0.2, true);
        let (y0, r0, y1, r1) = (1.2991e-01, -0.4480, 1.4227e-01, -0.4459);
        let rho = r0 + (r1 - r0) * (20.0 / 150.0 - y0) / (y1 - y0);
        let u_rms = 0.4 * 20.0 / (1.0 + 0.0239 * 20f64.powf(1.496));
        let mut rng = crate::physics::noise::particle_rng(1, 0);
        let mut normal = || -> f64 { StandardNormal.sample(&mut rng) };
        for (z, sign) in [(20.0, 1.0), (280.0, -1.0)] {
            let x = DVec3::new(1.0, 1.0, z);
            let mean = fluid_velocity::<false>(&field, size, x, &[0.0; 3]).x;
            let (mut uu, mut ww, mut uw) = (0.0, 0.0, 0.0);
            let n = 200_000;
            for _ in 0..n {
                let u = fluid_velocity::<true>(&field, size, x, &[normal(), normal(), normal()]);
                let (du, w) = (u.x - mean, u.z);
                (uu, ww, uw) = (uu + du * du, ww + w * w, uw + du * w);
            }
            let correlation = uw / (uu * ww).sqrt();
            assert!((correlation - sign * rho).abs() < 0.01, "z {z}: {correlation} against {}", sign * rho);
            let rms = (uu / n as f64).sqrt();
            assert!((rms / u_rms - 1.0).abs() < 0.01, "z {z}: u_rms {rms} against {u_rms}");
        }
    }

    #[test]
    fn saffman_lift_pushes_leading_particles_to_the_wall() {
        // Poiseuille flow, U_max = 1 m/s over H = 0.01 m: G = 4 U_max (H - 2z) / H^2.
        let field = FlowField::new(&crate::Flow::Poiseuille { max_speed: 1.0 }, [1.0, 1.0, 0.01], 1.5e-5, 1e-4, true);
        let size = [1.0, 1.0, 0.01];
        let x = DVec3::new(0.5, 0.5, 0.001);
        let shear: f64 = 4.0 * (0.01 - 0.002) / 1e-4; // 320 1/s
        let uf = DVec3::new(0.32, 0.0, 0.0);
        let lead = saffman_lift(&field, size, x, uf, DVec3::new(0.42, 0.0, 0.0), 2.0);
        // By hand: 2 * sqrt(320) * (0.32 - 0.42) * (+1) = -3.578 m/s^2 (towards the lower wall).
        assert!((lead - 2.0 * shear.sqrt() * -0.1).abs() < 0.02 * lead.abs(), "{lead}");
        let lag = saffman_lift(&field, size, x, uf, DVec3::new(0.22, 0.0, 0.0), 2.0);
        assert!(lag > 0.0 && (lag + lead).abs() < 1e-9);
        // Near the upper wall the shear changes sign, and so does the lift.
        let upper = saffman_lift(&field, size, DVec3::new(0.5, 0.5, 0.009), uf, DVec3::new(0.42, 0.0, 0.0), 2.0);
        assert!((upper + lead).abs() < 1e-9, "{upper} {lead}");
    }
}
