//! One subject, hence one file over 700 lines: the four-lane step and its AVX2 form, tested against one particle alone.
//!
//! Turbulent scenes, and scenes of constant forcing, [`WIDTH`] particles side by side: the
//! same steps, random numbers and contacts as one particle alone, with the lanes' look-ups
//! overlapped and their arithmetic vectorised (see [`run_lanes`]).
//!
//! One subject, kept whole though long: the four-lane step, plain and AVX2 side by side
//! (its unit tests are a quarter of it).

use glam::DVec3;
use multiversion::multiversion;
use multiversion::target::target_cfg_f;

use crate::physics::turbulence::FlowField;
#[cfg(doc)]
use crate::physics::turbulence::Table;

use super::contacts::{contacts, inside, wrap, AfterContacts, Flight};
use super::fluid::{fluid_velocity, langevin_step, stress_part};
use super::{
    brownian_increment, inject, normals_per_step, relaxed, run_particle, wall_distance, Body, Fate, Injected, Prepared,
    Record, State, StepNormals, WallTally,
};
use crate::physics::turbulence::tangential_products;

/// Particles stepped side by side by [`run_lanes`].
const WIDTH: usize = 4;

/// A particle in one of [`run_lanes`]' lanes: what the step itself does not need.
struct Lane {
    id: u64,
    body: Body,
    start: [f64; 3],
    draws: StepNormals,
}

/// [`run_particle`] for turbulent scenes, and for scenes of constant forcing, with the
/// exponential scheme, Stokes drag and no lift, [`WIDTH`] particles at a time. Their states
/// sit side by side (one array per coordinate) and each part of the step runs for all lanes
/// before the next, so the compiler vectorises the arithmetic across lanes and the processor
/// overlaps the lanes' table look-ups, where one particle alone, each step waiting on the
/// last, leaves it idle (timings in docs/performance-log.md). Where the processor has AVX2
/// the whole step before the walls is [`step_lanes_avx2`], its look-ups [`Table::at4`] in
/// AVX2. Under constant forcing, whenever every lane
/// holds a particle they fly freely ([`fly_freely`]) up to the next step that needs more. (With Brownian motion
/// alone, or a laminar profile, there are no look-ups to overlap and no free flight, and one
/// particle at a time is faster: `track` does not send such scenes here.) A step that ends
/// for every lane in the air, without a contact or a wrap, is taken for all lanes at once
/// (fewer instructions and less time; docs/performance-log.md). Each
/// particle takes exactly the steps, random numbers and contacts it takes alone (a lane whose
/// particle is done takes the next one), so the records are identical to [`run_particle`]'s
/// (tested); only the order in which contacts add their energies to the tallies differs.
#[multiversion(targets("x86_64+avx2+fma"))]
pub(super) fn run_lanes<const BROWN: bool, const TURB: bool>(
    p: &Prepared<'_>,
    ids: std::ops::Range<usize>,
    tally: &mut [WallTally],
) -> Vec<Record> {
    // True in the build of this function for processors with AVX2.
    const AVX2: bool = target_cfg_f!(all(target_arch = "x86_64", target_feature = "avx2"));
    lanes::<BROWN, TURB, AVX2>(p, ids, tally)
}

/// The body of [`run_lanes`], with its AVX2 parts on when `AVX2` (which the caller may set
/// only where the processor has AVX2). Inlined into each build of `run_lanes`; the tests also
/// run it with `AVX2` off, the path of processors without it.
#[inline(always)]
fn lanes<const BROWN: bool, const TURB: bool, const AVX2: bool>(
    p: &Prepared<'_>,
    ids: std::ops::Range<usize>,
    tally: &mut [WallTally],
) -> Vec<Record> {
    if p.steps == 0 {
        return ids.map(|id| run_particle::<BROWN, TURB, false, false, false>(p, id as u64, tally)).collect();
    }
    let dt = p.settings.dt;
    let field = &p.field;
    let first = ids.start;
    let mut records: Vec<Option<Record>> = vec![None; ids.len()];
    let mut next = ids.start;
    let (brownian_start, per_step) = normals_per_step(TURB, BROWN, false);

    let mut lanes: [Option<Lane>; WIDTH] = Default::default();
    let (mut x, mut v, mut zeta) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);
    let mut settling = [[0.0; WIDTH]; 3];
    let (mut decay, mut relax, mut radius) = ([0.0; WIDTH], [0.0; WIDTH], [0.0; WIDTH]);
    let mut brownian = [[0.0; WIDTH]; 3];
    // Steps taken, and the box each lane's position must stay in for a step to end without a
    // contact and without being wrapped ([`free_bounds`]).
    let mut n = [0usize; WIDTH];
    // Steps each lane's particle is tracked for (fewer than the run's when ventilation
    // exhausts it earlier).
    let mut end = [0usize; WIDTH];
    let (mut lo, mut hi) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);

    // Each lane's airborne time in the near-floor layer ([`Record::near_floor`]).
    let mut low = [0.0; WIDTH];
    let record = |lane: &Lane, fate: Fate, time: f64, at: [f64; 3], steps: u64, low: f64| Record {
        fate,
        time,
        start: lane.start,
        position: at,
        diameter: lane.body.aero.diameter,
        mass: lane.body.aero.mass,
        steps,
        near_floor: low,
    };

    // Some lane is empty (and may take the next particle).
    let mut vacant = true;
    for round in 0.. {
        if p.stopped_at(round) {
            return Vec::new(); // the stopped run discards its records
        }
        // Empty lanes take the next particles.
        for l in (0..WIDTH).filter(|_| vacant) {
            if lanes[l].is_none() && next < ids.end {
                let id = next as u64;
                next += 1;
                let Injected { body, start, x: x0, v: v0, zeta: z0, normals, end: last } = inject(p, id, TURB, BROWN);
                end[l] = last;
                for a in 0..3 {
                    (x[a][l], v[a][l], zeta[a][l], settling[a][l]) = (x0[a], v0[a], z0[a], body.settling[a]);
                    (lo[a][l], hi[a][l]) = free_bounds(p, a, body.contact);
                }
                (decay[l], relax[l], radius[l], n[l], low[l]) = (body.decay, body.relax, body.contact, 0, 0.0);
                for (k, b) in body.brownian.into_iter().enumerate() {
                    brownian[k][l] = b;
                }
                lanes[l] = Some(Lane { id, body, start, draws: StepNormals::new(normals) });
            }
        }
        if vacant && lanes.iter().all(Option::is_none) {
            break;
        }
        vacant = lanes.iter().any(Option::is_none);

        if !(TURB || BROWN || vacant) && field.profile.is_none() {
            // Constant forcing: every lane flies freely until one is due for more than that.
            let left = n.iter().zip(&end).map(|(&n, &end)| end - 1 - n).min().unwrap_or(0);
            let mut v_inf = [[0.0; WIDTH]; 3];
            for a in 0..3 {
                for l in 0..WIDTH {
                    v_inf[a][l] = field.uniform[a] + settling[a][l];
                }
            }
            let free = FreeLanes { v_inf, decay, relax, lo, hi, dt, floor: p.near_floor };
            let taken = fly_freely::<AVX2>(&mut x, &mut v, &mut low, free, left);
            for n in &mut n {
                *n += taken;
            }
        }

        // This step's normal variates, read where each lane's block holds them (copying them
        // into one array first cost more than the reads it saved).
        let mut z: [&[f64; 9]; WIDTH] = [&[0.0; 9]; WIDTH];
        for ((z, lane), &n) in z.iter_mut().zip(&mut lanes).zip(&n) {
            if let Some(lane) = lane {
                *z = lane.draws.step(n, per_step);
            }
        }

        // The step, for all lanes at once (an empty lane computes on stale values, unused).
        let constants = LaneConstants { settling: &settling, decay: &decay, relax: &relax, brownian: &brownian, dt };
        let step = (field, p.size, brownian_start);
        let Stepped { uf, x1, v1, bx, bv } = step_lanes::<BROWN, TURB, AVX2>(&x, &v, &mut zeta, &z, constants, step);

        // The common step, for all lanes at once: every lane holds a particle, and each step
        // ends inside its free box (no contact, nothing to wrap), with a finite velocity, before
        // the particle's last step. It is what the general path below does in that case.
        if !vacant {
            let mut plain = ends_free::<AVX2>(&x1, &v1, &lo, &hi);
            for (&n, &end) in n.iter().zip(&end) {
                plain &= n + 1 < end;
            }
            if plain {
                (x, v) = (x1, v1);
                for n in &mut n {
                    *n += 1;
                }
                for l in 0..WIDTH {
                    low[l] += if x[2][l] < p.near_floor { dt } else { 0.0 };
                }
                continue;
            }
        }

        let mut ok = [true; WIDTH];
        for l in 0..WIDTH {
            ok[l] = inside(DVec3::new(x1[0][l], x1[1][l], x1[2][l]), radius[l], p, p.boxes);
        }

        // What each particle does with its step.
        for l in 0..WIDTH {
            let Some(lane) = &mut lanes[l] else { continue };
            let taken = n[l];
            n[l] += 1;
            let t0 = taken as f64 * dt;
            let done = if ok[l] {
                let xw = wrap(DVec3::new(x1[0][l], x1[1][l], x1[2][l]), p);
                let vw = DVec3::new(v1[0][l], v1[1][l], v1[2][l]);
                for a in 0..3 {
                    (x[a][l], v[a][l]) = (xw[a], vw[a]);
                }
                if !(xw.is_finite() && vw.is_finite()) {
                    Some(record(lane, Fate::Escaped, t0 + dt, xw.to_array(), taken as u64 + 1, low[l]))
                } else {
                    low[l] += if xw.z < p.near_floor { dt } else { 0.0 };
                    None
                }
            } else {
                let body = &lane.body;
                let flight = Flight::<false> {
                    x0: DVec3::new(x[0][l], x[1][l], x[2][l]),
                    v0: DVec3::new(v[0][l], v[1][l], v[2][l]),
                    v_inf: DVec3::new(uf[0][l], uf[1][l], uf[2][l]) + body.settling,
                    tau: body.tau,
                    decay: body.decay,
                    relax: body.relax,
                    dt,
                    bx: DVec3::new(bx[0][l], bx[1][l], bx[2][l]),
                    bv: DVec3::new(bv[0][l], bv[1][l], bv[2][l]),
                };
                let state = State { x: flight.x0, v: flight.v0, zeta: [zeta[0][l], zeta[1][l], zeta[2][l]] };
                match contacts::<false>(p, body, flight, state, flight.x0, tally) {
                    AfterContacts::Airborne(s) => {
                        for a in 0..3 {
                            (x[a][l], v[a][l], zeta[a][l]) = (s.x[a], s.v[a], s.zeta[a]);
                        }
                        low[l] += if s.x.z < p.near_floor { dt } else { 0.0 };
                        None
                    }
                    AfterContacts::Left(fate, t, at) => {
                        Some(record(lane, fate, t0 + t, at.to_array(), taken as u64 + 1, low[l]))
                    }
                }
            };
            let done = done.or_else(|| {
                (n[l] == end[l]).then(|| {
                    let fate = if end[l] < p.steps { Fate::Exhausted } else { Fate::Airborne };
                    record(lane, fate, end[l] as f64 * dt, [x[0][l], x[1][l], x[2][l]], end[l] as u64, low[l])
                })
            });
            if let Some(rec) = done {
                records[lane.id as usize - first] = Some(rec);
                lanes[l] = None;
                vacant = true;
            }
        }
    }
    records.into_iter().map(|r| r.expect("every particle recorded")).collect()
}

/// The per-lane constants a step of [`run_lanes`] needs, side by side.
#[derive(Clone, Copy)]
struct LaneConstants<'a> {
    settling: &'a [[f64; WIDTH]; 3],
    decay: &'a [f64; WIDTH],
    relax: &'a [f64; WIDTH],
    brownian: &'a [[f64; WIDTH]; 3],
    dt: f64,
}

/// The scene's part of a step: the flow, the domain's size (m) and where the Brownian
/// variates start among a step's variates.
type StepScene<'a> = (&'a FlowField, [f64; 3], usize);

/// One step of [`run_lanes`]' four lanes, before any wall: the fluid velocity seen `uf`, the
/// position and velocity at the step's end, and the Brownian increments (for the contact
/// search of a lane that meets a wall). The lanes' `zeta` are advanced.
struct Stepped {
    uf: [[f64; WIDTH]; 3],
    x1: [[f64; WIDTH]; 3],
    v1: [[f64; WIDTH]; 3],
    bx: [[f64; WIDTH]; 3],
    bv: [[f64; WIDTH]; 3],
}

/// The step of [`run_lanes`] as [`run_particle`] takes it, lane by lane: [`fluid_velocity`],
/// [`fluctuation`](super::fluid::fluctuation) (four [`Table::at`]s through [`Table::at4`]), [`brownian_increment`] and
/// [`relaxed`]. With `AVX2` (set only where the processor has it) a turbulent scene's step is
/// [`step_lanes_avx2`].
#[inline(always)]
fn step_lanes<const BROWN: bool, const TURB: bool, const AVX2: bool>(
    x: &[[f64; WIDTH]; 3],
    v: &[[f64; WIDTH]; 3],
    zeta: &mut [[f64; WIDTH]; 3],
    z: &[&[f64; 9]; WIDTH],
    c: LaneConstants<'_>,
    scene: StepScene<'_>,
) -> Stepped {
    #[cfg(target_arch = "x86_64")]
    if AVX2 && TURB {
        // SAFETY: the caller sets `AVX2` only where the processor has AVX2.
        return unsafe { step_lanes_avx2::<BROWN>(x, v, zeta, z, c, scene) };
    }
    let (field, size, brownian_start) = scene;
    let LaneConstants { settling, decay, relax, brownian, dt } = c;
    let mut uf = [[0.0; WIDTH]; 3];
    for l in 0..WIDTH {
        let xl = DVec3::new(x[0][l], x[1][l], x[2][l]);
        let u = fluid_velocity::<false>(field, size, xl, &[0.0; 3]);
        for a in 0..3 {
            uf[a][l] = u[a];
        }
    }
    if let Some(turb) = field.turbulence.as_ref().filter(|_| TURB) {
        let (mut d, mut sign) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);
        for (a, comp) in turb.iter().enumerate() {
            for l in 0..WIDTH {
                (d[a][l], sign[a][l]) = wall_distance(x[comp.axis][l], size[comp.axis]);
            }
        }
        // (With AVX2 a turbulent step never gets here: it is `step_lanes_avx2`.)
        let nodes =
            [turb[0].table.at4::<false>(d[0]), turb[1].table.at4::<false>(d[1]), turb[2].table.at4::<false>(d[2])];
        for l in 0..WIDTH {
            let g = tangential_products([nodes[0].tangential[l], nodes[1].tangential[l], nodes[2].tangential[l]]);
            let zeta_normal = zeta[2][l];
            for a in 0..3 {
                let (du, next) = langevin_step(&nodes[a].lane(l), g[a], sign[a][l], zeta[a][l], z[l][a]);
                uf[a][l] += du;
                zeta[a][l] = next;
            }
            if let Some(coupling) = &field.stress_coupling {
                let xl = DVec3::new(x[0][l], x[1][l], x[2][l]);
                uf[0][l] += stress_part(coupling, size, xl, zeta_normal);
            }
        }
    }
    let (mut x1, mut v1) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);
    let (mut bx, mut bv) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);
    for a in 0..3 {
        for l in 0..WIDTH {
            if BROWN {
                let (za, zb) = (z[l][brownian_start + 2 * a], z[l][brownian_start + 2 * a + 1]);
                let coefficients = [brownian[0][l], brownian[1][l], brownian[2][l]];
                (bx[a][l], bv[a][l]) = brownian_increment(coefficients, za, zb);
            }
            let v_inf = uf[a][l] + settling[a][l];
            let relaxation = (dt, decay[l], relax[l]);
            (x1[a][l], v1[a][l]) = relaxed(x[a][l], v[a][l], v_inf, relaxation, bx[a][l], bv[a][l]);
        }
    }
    Stepped { uf, x1, v1, bx, bv }
}

/// [`step_lanes`] in AVX2 for turbulent scenes: the same operations in the same order on the
/// four lanes at once, so the same results bit for bit (the records of [`run_lanes`] are
/// tested identical to [`run_particle`]'s). The compiler's vectorisation of `step_lanes` mixed
/// 128- and 256-bit halves, gathered each variate lane by lane and kept the arrays on the
/// stack (the instruction counts and timings are in docs/performance-log.md).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn step_lanes_avx2<const BROWN: bool>(
    x: &[[f64; WIDTH]; 3],
    v: &[[f64; WIDTH]; 3],
    zeta: &mut [[f64; WIDTH]; 3],
    z: &[&[f64; 9]; WIDTH],
    c: LaneConstants<'_>,
    (field, size, brownian_start): StepScene<'_>,
) -> Stepped {
    use std::arch::x86_64::*;
    // SAFETY (both): each array holds four f64s.
    let load = |a: &[f64; WIDTH]| unsafe { _mm256_loadu_pd(a.as_ptr()) };
    let lanes = |v: __m256d| -> [f64; WIDTH] {
        let mut a = [0.0; WIDTH];
        unsafe { _mm256_storeu_pd(a.as_mut_ptr(), v) };
        a
    };
    let splat = |x: f64| _mm256_set1_pd(x);

    // The variates side by side: `normal[k]` is variate k of the four lanes (the first eight
    // by two 4 x 4 transposes, the ninth lane by lane).
    let mut normal = [_mm256_setzero_pd(); 9];
    for half in 0..if BROWN { 2 } else { 1 } {
        // SAFETY: each row holds nine f64s; these are its four from `4 * half`.
        let r = z.map(|row| unsafe { _mm256_loadu_pd(row.as_ptr().add(4 * half)) });
        let (t0, t1) = (_mm256_unpacklo_pd(r[0], r[1]), _mm256_unpackhi_pd(r[0], r[1]));
        let (t2, t3) = (_mm256_unpacklo_pd(r[2], r[3]), _mm256_unpackhi_pd(r[2], r[3]));
        normal[4 * half] = _mm256_permute2f128_pd::<0x20>(t0, t2);
        normal[4 * half + 1] = _mm256_permute2f128_pd::<0x20>(t1, t3);
        normal[4 * half + 2] = _mm256_permute2f128_pd::<0x31>(t0, t2);
        normal[4 * half + 3] = _mm256_permute2f128_pd::<0x31>(t1, t3);
    }
    if BROWN {
        normal[8] = _mm256_set_pd(z[3][8], z[2][8], z[1][8], z[0][8]);
    }

    // `wall_distance` of the lanes' coordinates along `axis`: the distance and the sign.
    let distance = |axis: usize| {
        let c = load(&x[axis]);
        let upper = _mm256_sub_pd(splat(size[axis]), c);
        let lower = _mm256_cmp_pd::<_CMP_LE_OQ>(c, upper);
        (_mm256_blendv_pd(upper, c, lower), _mm256_blendv_pd(splat(-1.0), splat(1.0), lower))
    };
    // `fluid_velocity` without turbulence: the uniform part, and the profile along `x`.
    let mut uf = field.uniform.map(splat);
    if let Some(profile) = &field.profile {
        let (d, _) = distance(2);
        uf[0] = _mm256_add_pd(uf[0], load(&profile.at4::<true>(lanes(d)).sigma));
    }
    // `fluctuation` of each component (`langevin_step`): each component's node consumed as
    // it is read, keeping only what the tangential factors (`tangential_products` of the
    // three nodes' factors, where the flow has them) then scale.
    if let Some(turb) = field.turbulence.as_ref() {
        let mut parts = [(_mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd()); 3];
        for (a, comp) in turb.iter().enumerate() {
            let (d, sign) = distance(comp.axis);
            let node = comp.table.at4::<true>(lanes(d));
            let z0 = load(&zeta[a]);
            let moved = _mm256_mul_pd(load(&node.sigma), z0);
            let relaxed =
                _mm256_add_pd(_mm256_mul_pd(z0, load(&node.decay)), _mm256_mul_pd(load(&node.noise), normal[a]));
            parts[a] = (moved, relaxed, _mm256_mul_pd(sign, load(&node.drift)), load(&node.tangential));
        }
        let g = field.tangential.then(|| {
            let t = parts.map(|p| p.3);
            [_mm256_mul_pd(t[1], t[2]), _mm256_mul_pd(t[0], t[2]), _mm256_mul_pd(t[0], t[1])]
        });
        // `stress_part`, from the wall-normal zeta before its step.
        let stress = field.stress_coupling.as_ref().map(|coupling| {
            let (d, sign) = distance(2);
            _mm256_mul_pd(_mm256_mul_pd(sign, load(&coupling.at4::<true>(lanes(d)).sigma)), load(&zeta[2]))
        });
        for (a, &(moved, relaxed, drift, _)) in parts.iter().enumerate() {
            let (du, drift) = match g {
                Some(g) => (_mm256_mul_pd(g[a], moved), _mm256_mul_pd(g[a], drift)),
                None => (moved, drift),
            };
            zeta[a] = lanes(_mm256_add_pd(relaxed, drift));
            uf[a] = _mm256_add_pd(uf[a], du);
        }
        if let Some(stress) = stress {
            uf[0] = _mm256_add_pd(uf[0], stress);
        }
    }
    // `brownian_increment` and `relaxed` along each axis.
    let [sx, cxv, sv] = c.brownian.map(|k| load(&k));
    let (dt, decay, relax) = (splat(c.dt), load(c.decay), load(c.relax));
    let mut out = Stepped {
        uf: [[0.0; WIDTH]; 3],
        x1: [[0.0; WIDTH]; 3],
        v1: [[0.0; WIDTH]; 3],
        bx: [[0.0; WIDTH]; 3],
        bv: [[0.0; WIDTH]; 3],
    };
    for a in 0..3 {
        let (bx, bv) = if BROWN {
            let (za, zb) = (normal[brownian_start + 2 * a], normal[brownian_start + 2 * a + 1]);
            (_mm256_mul_pd(sx, za), _mm256_add_pd(_mm256_mul_pd(cxv, za), _mm256_mul_pd(sv, zb)))
        } else {
            (_mm256_setzero_pd(), _mm256_setzero_pd())
        };
        let v_inf = _mm256_add_pd(uf[a], load(&c.settling[a]));
        let dv = _mm256_sub_pd(load(&v[a]), v_inf);
        let moved = _mm256_add_pd(_mm256_add_pd(load(&x[a]), _mm256_mul_pd(v_inf, dt)), _mm256_mul_pd(dv, relax));
        out.x1[a] = lanes(_mm256_add_pd(moved, bx));
        out.v1[a] = lanes(_mm256_add_pd(_mm256_add_pd(v_inf, _mm256_mul_pd(dv, decay)), bv));
        (out.uf[a], out.bx[a], out.bv[a]) = (lanes(uf[a]), lanes(bx), lanes(bv));
    }
    out
}

/// What [`fly_freely`] needs of its lanes: the constant velocity each relaxes to, the step's
/// constants, and the box each position must stay in for its step to be plain flight.
struct FreeLanes {
    v_inf: [[f64; WIDTH]; 3],
    decay: [f64; WIDTH],
    relax: [f64; WIDTH],
    lo: [[f64; WIDTH]; 3],
    hi: [[f64; WIDTH]; 3],
    dt: f64,
    /// The top of the near-floor layer, m ([`Prepared::near_floor`]).
    floor: f64,
}

/// The coordinates along `axis` between which a sphere of radius `r` flies on without a
/// contact and without being wrapped: `[lower + r, upper - r]` across walls (the bounds of
/// [`inside`], rounded the same way) and `[0, size)` along a periodic axis (where [`wrap`]
/// leaves the coordinate as it is).
#[inline(always)]
fn free_bounds(p: &Prepared<'_>, axis: usize, r: f64) -> (f64, f64) {
    if p.walled[axis] {
        (p.lower[axis] + r, p.upper[axis] - r)
    } else {
        (0.0, f64::from_bits(p.size[axis].to_bits() - 1))
    }
}

/// Steps all lanes under constant forcing (no turbulence, no Brownian motion, uniform flow)
/// for at most `limit` steps, stopping before the first step after which some lane is outside
/// its [`FreeLanes`] box or not finite; returns the steps taken. Each step is [`relaxed`], as
/// in [`run_particle`], so the lanes end bit for bit where the general step would take them;
/// the loop keeps the lanes in registers and does nothing else (the drag-and-gravity bench
/// scene's speed with and without it is in docs/performance-log.md).
#[inline(always)]
fn fly_freely<const AVX2: bool>(
    x: &mut [[f64; WIDTH]; 3],
    v: &mut [[f64; WIDTH]; 3],
    low: &mut [f64; WIDTH],
    c: FreeLanes,
    limit: usize,
) -> usize {
    let (mut xs, mut vs) = (*x, *v);
    let mut taken = 0;
    while taken < limit {
        let (mut x1, mut v1) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);
        for a in 0..3 {
            for l in 0..WIDTH {
                (x1[a][l], v1[a][l]) =
                    relaxed(xs[a][l], vs[a][l], c.v_inf[a][l], (c.dt, c.decay[l], c.relax[l]), 0.0, 0.0);
            }
        }
        if !ends_free::<AVX2>(&x1, &v1, &c.lo, &c.hi) {
            break;
        }
        (xs, vs) = (x1, v1);
        for l in 0..WIDTH {
            low[l] += if xs[2][l] < c.floor { c.dt } else { 0.0 };
        }
        taken += 1;
    }
    (*x, *v) = (xs, vs);
    taken
}

/// True when every lane's step ends inside its box `[lo, hi]` ([`free_bounds`]: no contact,
/// nothing to wrap) with a finite velocity. With `AVX2` (set only where the processor has
/// it) the twelve tests are ANDed as vector masks and read with one `movmsk`; the compiler
/// made about 45 instructions of packing out of the plain version.
#[inline(always)]
fn ends_free<const AVX2: bool>(
    x1: &[[f64; WIDTH]; 3],
    v1: &[[f64; WIDTH]; 3],
    lo: &[[f64; WIDTH]; 3],
    hi: &[[f64; WIDTH]; 3],
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if AVX2 {
        // SAFETY: the caller sets `AVX2` only where the processor has AVX2.
        return unsafe { ends_free_avx2(x1, v1, lo, hi) };
    }
    let mut free = true;
    for a in 0..3 {
        for l in 0..WIDTH {
            free &= (x1[a][l] >= lo[a][l]) & (x1[a][l] <= hi[a][l]) & v1[a][l].is_finite();
        }
    }
    free
}

/// [`ends_free`] in AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn ends_free_avx2(
    x1: &[[f64; WIDTH]; 3],
    v1: &[[f64; WIDTH]; 3],
    lo: &[[f64; WIDTH]; 3],
    hi: &[[f64; WIDTH]; 3],
) -> bool {
    use std::arch::x86_64::*;
    // SAFETY: each row holds four f64s.
    let load = |row: &[f64; WIDTH]| unsafe { _mm256_loadu_pd(row.as_ptr()) };
    let magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(i64::MAX));
    let infinity = _mm256_set1_pd(f64::INFINITY);
    let mut free = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    for a in 0..3 {
        let x = load(&x1[a]);
        // Ordered comparisons: false for NaN, as in the plain version.
        let inside =
            _mm256_and_pd(_mm256_cmp_pd::<_CMP_GE_OQ>(x, load(&lo[a])), _mm256_cmp_pd::<_CMP_LE_OQ>(x, load(&hi[a])));
        let finite = _mm256_cmp_pd::<_CMP_LT_OQ>(_mm256_and_pd(load(&v1[a]), magnitude), infinity);
        free = _mm256_and_pd(free, _mm256_and_pd(inside, finite));
    }
    _mm256_movemask_pd(free) == 0b1111
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::flow::Flow;
    use crate::model::geometry::Geometry;
    use crate::model::scene::{Injection, Scene, SizeDistribution};
    use crate::model::settings::RunSettings;
    use crate::model::walls::WallBehaviour;
    use crate::physics::noise::particle_rng;
    use depo_wall_model::WallLaw;
    use rand::RngExt;

    /// `run_lanes` must give each particle exactly what `run_particle` gives it alone: same
    /// records bit for bit, same wall contacts.
    fn lanes_match_one_at_a_time<const BROWN: bool, const TURB: bool>(
        (scene, settings): (&Scene, &RunSettings),
        injection: &Injection,
    ) -> usize {
        let p = Prepared::new(scene, settings, injection).unwrap();
        let walls = p.walls.len();
        let (mut lane_tally, mut alone_tally) = (vec![WallTally::default(); walls], vec![WallTally::default(); walls]);
        let lanes = run_lanes::<BROWN, TURB>(&p, 0..injection.count, &mut lane_tally);
        let alone: Vec<Record> = (0..injection.count as u64)
            .map(|id| run_particle::<BROWN, TURB, false, false, false>(&p, id, &mut alone_tally))
            .collect();
        assert_eq!(lanes, alone);
        // The lanes as a processor without AVX2 runs them.
        let mut plain_tally = vec![WallTally::default(); walls];
        assert_eq!(super::lanes::<BROWN, TURB, false>(&p, 0..injection.count, &mut plain_tally), alone);
        for (a, b) in lane_tally.iter().zip(&alone_tally) {
            assert_eq!(
                (a.contacts, a.rebounds, a.captures, a.resting),
                (b.contacts, b.rebounds, b.captures, b.resting)
            );
            assert!((a.energy.material - b.energy.material).abs() <= 1e-12 * b.energy.material.abs());
        }
        let fates = |f: fn(&Fate) -> bool| lanes.iter().filter(|r| f(&r.fate)).count();
        let (deposited, airborne) =
            (fates(|f| matches!(f, Fate::Deposited(_))), fates(|f| matches!(f, Fate::Airborne)));
        let contacts: u64 = lane_tally.iter().map(|t| t.contacts).sum();
        assert!(contacts > 0 && airborne > 0, "{contacts} contacts, {airborne} airborne: both paths must be seen");
        deposited
    }

    #[test]
    fn lanes_give_each_particle_what_it_gets_alone() {
        // A small turbulent room whose walls rebound particles by the law (5 um particles
        // over 10 s: settling alone brings a quarter of them to the floor, where they bounce,
        // so the test does not depend on lucky random numbers), and a turbulent channel (periodic along and across) whose walls absorb
        // them. 37 particles, so that the lanes refill unevenly (as particles deposit) and the
        // last ones run part-empty.
        let law = WallLaw::preset("dunn1995-stainless").unwrap();
        let mut room =
            Scene::new(Geometry::Room { size: [0.05, 0.04, 0.03] }).with_walls(WallBehaviour::Law { law, size: None });
        let room_settings = RunSettings::new(0.01, 10.0);
        room.flow = Flow::TurbulentRoom { friction_velocity: 0.05, core_rms: 0.1, core_time: 0.5, blend_length: 0.01 };
        room.brownian = true;
        let settling = Injection::new(37, SizeDistribution::Monodisperse { diameter: 5e-6 }, 1000.0);
        lanes_match_one_at_a_time::<true, true>((&room, &room_settings), &settling);
        lanes_match_one_at_a_time::<false, true>((&room, &room_settings), &settling);

        let mut channel = Scene::new(Geometry::Channel { length: 0.05, width: 0.02, height: 0.01 });
        let channel_settings = RunSettings::new(1e-4, 0.3);
        channel.flow = Flow::TurbulentChannel { friction_velocity: 0.3 };
        channel.brownian = true;
        channel.gravity = [0.0; 3];
        let particles = Injection::new(37, SizeDistribution::Monodisperse { diameter: 20e-6 }, 1000.0);
        assert!(lanes_match_one_at_a_time::<true, true>((&channel, &channel_settings), &particles) > 0);
        assert!(lanes_match_one_at_a_time::<false, true>((&channel, &channel_settings), &particles) > 0);
    }

    #[test]
    fn the_avx2_step_is_the_plain_step_bit_for_bit() {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            let size = [0.05, 0.04, 0.01];
            let room =
                Flow::TurbulentRoom { friction_velocity: 0.05, core_rms: 0.1, core_time: 0.5, blend_length: 0.01 };
            let channel = Flow::TurbulentChannel { friction_velocity: 0.3 };
            let mut rng = particle_rng(7, 8);
            for flow in [room, channel] {
                let field = FlowField::new(&flow, size, 1.5e-5, 1e-3, true);
                for _ in 0..2000 {
                    let mut lanes = |scale: f64| -> [[f64; WIDTH]; 3] {
                        std::array::from_fn(|_| std::array::from_fn(|_| scale * rng.random_range(-0.2..1.2)))
                    };
                    // Positions across the walls' layers and a little beyond the domain.
                    let x = [0, 1, 2].map(|a| lanes(size[a])[a]);
                    let (v, mut zeta, settling, brownian) = (lanes(0.1), lanes(2.0), lanes(1e-3), lanes(1e-4));
                    let (decay, relax) = (lanes(1.0)[0], lanes(1e-3)[0]);
                    let rows: [[f64; 9]; WIDTH] =
                        std::array::from_fn(|_| std::array::from_fn(|_| rng.random_range(-4.0..4.0)));
                    let z = [&rows[0], &rows[1], &rows[2], &rows[3]];
                    let c = LaneConstants {
                        settling: &settling,
                        decay: &decay,
                        relax: &relax,
                        brownian: &brownian,
                        dt: 1e-3,
                    };
                    let mut zeta2 = zeta;
                    let bits = |s: Stepped| [s.uf, s.x1, s.v1, s.bx, s.bv].map(|q| q.map(|r| r.map(f64::to_bits)));
                    for (brown, start) in [(true, 3), (false, 3)] {
                        let (plain, vector) = if brown {
                            let plain =
                                step_lanes::<true, true, false>(&x, &v, &mut zeta, &z, c, (&field, size, start));
                            // SAFETY: the processor has AVX2.
                            (plain, unsafe {
                                step_lanes_avx2::<true>(&x, &v, &mut zeta2, &z, c, (&field, size, start))
                            })
                        } else {
                            let plain =
                                step_lanes::<false, true, false>(&x, &v, &mut zeta, &z, c, (&field, size, start));
                            // SAFETY: the processor has AVX2.
                            (plain, unsafe {
                                step_lanes_avx2::<false>(&x, &v, &mut zeta2, &z, c, (&field, size, start))
                            })
                        };
                        assert_eq!(bits(plain), bits(vector), "{flow:?}");
                        assert_eq!(zeta.map(|r| r.map(f64::to_bits)), zeta2.map(|r| r.map(f64::to_bits)));
                    }
                }
            }
        }
    }

    #[test]
    fn the_free_step_test_is_the_same_in_avx2() {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            let (lo, hi) = ([[0.0, -1.0, 1e-9, 2.0]; 3], [[1.0, 0.0, 1.0, 2.0]; 3]);
            let specials = [0.0, -0.0, 1.0, -1.0, 1e-9, 2.0, 0.5, f64::from_bits(1), 1.0 + f64::EPSILON];
            let odd = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
            let mut rng = particle_rng(1, 2);
            let (mut free, mut cases) = (0, 0);
            for _ in 0..20_000 {
                // Mostly inside each lane's box (its edges included), sometimes an edge case.
                let mut pick = |l: usize| -> f64 {
                    let r: f64 = rng.random();
                    if r < 0.003 {
                        odd[rng.random_range(0..3)]
                    } else if r < 0.05 {
                        specials[rng.random_range(0..specials.len())]
                    } else if r < 0.1 {
                        [lo[0][l], hi[0][l]][rng.random_range(0..2)]
                    } else {
                        lo[0][l] + (hi[0][l] - lo[0][l]) * rng.random::<f64>()
                    }
                };
                let x1: [[f64; WIDTH]; 3] = std::array::from_fn(|_| std::array::from_fn(&mut pick));
                let v1: [[f64; WIDTH]; 3] = std::array::from_fn(|_| std::array::from_fn(&mut pick));
                let expected = ends_free::<false>(&x1, &v1, &lo, &hi);
                // SAFETY: the processor has AVX2.
                assert_eq!(unsafe { ends_free_avx2(&x1, &v1, &lo, &hi) }, expected, "{x1:?} {v1:?}");
                free += usize::from(expected);
                cases += 1;
            }
            // Both answers occur often enough to be tested.
            assert!(free > 100 && cases - free > 100, "{free} of {cases}");
        }
    }

    #[test]
    fn lanes_without_turbulence_give_each_particle_what_it_gets_alone() {
        // Still air in a small room with rebounding walls, settling 30 um particles (most reach
        // the floor within the run, those injected high do not); and a uniform flow through a
        // channel, periodic along and across (so that particles wrap), whose floor absorbs them.
        let law = WallLaw::preset("dunn1995-stainless").unwrap();
        let room =
            Scene::new(Geometry::Room { size: [0.05, 0.04, 0.03] }).with_walls(WallBehaviour::Law { law, size: None });
        let settling = Injection::new(37, SizeDistribution::Monodisperse { diameter: 30e-6 }, 1000.0);
        assert!(lanes_match_one_at_a_time::<false, false>((&room, &RunSettings::new(0.01, 0.8)), &settling) > 0);

        let mut channel = Scene::new(Geometry::Channel { length: 0.05, width: 0.02, height: 0.01 });
        channel.flow = Flow::Uniform { velocity: [0.5, -0.2, 0.0] };
        assert!(lanes_match_one_at_a_time::<false, false>((&channel, &RunSettings::new(1e-3, 0.3)), &settling) > 0);
    }
}
