//! One subject, hence one file over 700 lines: the tabulated dispersion model a run reads (its profiles' table and look-ups).
//!
//! The air flow a particle sees: a mean velocity and, for turbulent scenes, velocity
//! fluctuations from a stochastic model that respects the near-wall anisotropy.
//!
//! One subject, kept whole though long: the dispersion model and its tables (its unit tests
//! are over a third of it).
//!
//! ## Mean flow
//! Still air, a uniform velocity, laminar Poiseuille flow in a channel, or a turbulent
//! channel's law-of-the-wall profile after Reichardt (1951):
//!
//! ```text
//! U+ = ln(1 + 0.41 y+) / 0.41 + 7.8 (1 - exp(-y+/11) - (y+/11) exp(-y+/3))
//! ```
//!
//! with `y+ = y u* / nu` the distance `y` from the nearer wall in wall units.
//!
//! ## Turbulent dispersion
//! Each velocity component's fluctuation seen by a particle is `u'_i = sigma_i(y) zeta_i`,
//! where `zeta_i` follows the *normalised* Langevin equation (a continuous random walk) of
//! Iliopoulos & Hanratty (1999), as used for wall deposition by Dehbi (2008):
//!
//! ```text
//! d zeta = -zeta dt / T_L + (d sigma / dy) dt + sqrt(2 / T_L) dW
//! ```
//!
//! The drift `d sigma / dy` (along the component's own wall-normal axis) is Thomson's (1987)
//! well-mixed condition written for `zeta`: without it, tracers drift into the low-turbulence
//! layer at the wall and the well-mixed state is lost (a test shows both). Over a step the
//! equation is solved exactly for frozen `sigma`, `T_L` and drift, so it is stable for any `dt`.
//!
//! The profiles are the fits to channel DNS used by Dehbi (2008) after Kallio & Reeks (1989),
//! in wall units, valid to `y+ ~ 200`:
//!
//! ```text
//! u+_rms = 0.4 y+ / (1 + 0.0239 y+^1.496)                   streamwise
//! v+_rms = 0.0116 y+^2 / (1 + 0.203 y+ + 0.0014 y+^2.421)   wall-normal
//! w+_rms = 0.19 y+ / (1 + 0.0361 y+^1.21)                   spanwise
//! T_L+   = 10 (y+ < 5),  7.122 + 0.5731 y+ - 0.00129 y+^2  (5 <= y+ <= 200)
//! ```
//!
//! **Channel**: these profiles of the distance to the nearer wall, the mean flow along `x`.
//! The streamwise and wall-normal fluctuations carry the Reynolds shear stress: the streamwise
//! one is `u_rms (rho_uv zeta_v + sqrt(1 - rho_uv^2) zeta_u)` (`zeta_v` the wall-normal
//! component's, with the sign that makes `<u'v'>` negative away from each wall), with
//! `rho_uv` from channel DNS ([`STRESS_CORRELATION`](super::profiles::STRESS_CORRELATION)). The two keep their variances, and the
//! tracers' wall-normal motion, hence their well-mixed state and every deposition rate, is
//! untouched; what changes is the streamwise velocity a particle meets a wall with, which the
//! wall law and Saffman's lift see.
//! **Room** (depo's own construction, as no standard model exists for a whole room): each
//! component `i` is treated as wall-normal to the pair of walls across axis `i` and takes the
//! wall-normal profile of its distance to them up to the profile's peak (`y+ = 67`, where
//! `v+_rms = 1.01`); beyond it `sigma` and `T_L` blend linearly over `blend_length` into the
//! well-mixed core's `core_rms` and `core_time`. No mean flow. The near-wall layer is what
//! Lai & Nazaroff (2000) model; the core stands for the room's air motion, which keeps it well
//! mixed.
//!
//! Near a wall the components *along* it are damped too: component `i` is multiplied by
//! `g(d_j) g(d_k)`, the tangential factors of its distances to the walls across the two other
//! axes, where `g(y) = sigma_t(y) / core_rms` and `sigma_t` is the tangential profile
//! `u* t+_rms(y+)` ([`tangential_rms`], the mean of the streamwise and spanwise variances, as
//! a room's near-wall air has no mean-flow direction) up to the same peak, blended into the
//! core the same way. So a particle meets the floor with the sublayer's tangential
//! fluctuation (`0.29 y+ u*` at the wall), not the core's, which is what the wall law's
//! friction and rolling see. Each component keeps the Lagrangian time of its own axis. Near
//! one wall the product is the single wall's profile; in a corner the two damp together.
//! In a furnished room the factors come from the room's walls alone (a box's faces shape
//! the component across them, not those along them): the distance to the nearest surface
//! jumps at the edge of a box's shadow, and a factor that jumped along another component's
//! own axis would need a drift the model does not have (a test saw tracers thinned to 0.80
//! of uniform at the floor).
//! The well-mixed drift needs no new term: for the normalised fluctuation `zeta_i = u_i /
//! sigma_i` Thomson's (1987) Gaussian solution leaves only `d sigma_i / dx_i` (the terms in
//! `d sigma_i / dx_j`, `j != i`, cancel between `du_i` and the change of `sigma_i` along the
//! path), and that derivative is the wall-normal profile's slope times `g(d_j) g(d_k)`.
//!
//! The crossing-trajectories effect (inertial particles leaving their fluid eddies early) is
//! not modelled: a particle sees the fluid-element time scale `T_L` whatever its inertia.

use std::sync::Arc;

use crate::model::flow::Flow;
use crate::physics::intermittency::Intermittent;
use crate::physics::profiles::{
    lagrangian_time, reichardt, spanwise_rms, streamwise_rms, stress_correlation, tangential_rms, wall_normal_rms,
    ROOM_PEAK_Y_PLUS,
};

/// Cells of each of a table's two grids. 1024 put the fine grid's cells 0.1 wall units apart:
/// the interpolated rms profiles and Reichardt's `U+` are then within 1e-4 wall units of the
/// fits, and the cell's own `T_L` within 0.6 % (most of it the fit's own step at `y+ = 5`).
/// More cells gain little accuracy and cost the table its place in a core's L2 cache (4096
/// made a room's table 393 KB instead of 98 KB; the timings are in docs/performance-log.md).
const TABLE_CELLS: usize = 1024;
/// Where a turbulent profile's fine grid ends, in wall units: the viscous and buffer layers
/// and the room profile's peak (`y+ = 67`).
const FINE_Y_PLUS: f64 = 100.0;

/// One node of a tabulated profile (`repr(C)`: the four-lane look-up reads its fields by
/// offset).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub(crate) struct Node {
    /// `sigma`, m/s (or the mean velocity for a mean-flow table).
    pub sigma: f64,
    /// The rise of `sigma` to the next node, m/s (what [`Table::at`] interpolates with).
    pub rise: f64,
    /// `d sigma / dy` over the cell from this node to the next, 1/s.
    pub slope: f64,
    /// `exp(-dt / T_L)`.
    pub decay: f64,
    /// `sqrt(1 - decay^2)`.
    pub noise: f64,
    /// The well-mixed drift added to the normalised fluctuation `zeta` over a step,
    /// `T_L (1 - decay) d sigma / dy` (dimensionless), for a step away from the wall; zero in
    /// a table made without drift.
    pub drift: f64,
    /// A room's tangential factor `g(y)` at this distance (see the module doc), interpolated
    /// as `sigma` is; 1 in a table without one.
    pub tangential: f64,
    /// The rise of `tangential` to the next node.
    pub tangential_rise: f64,
}

/// A profile of the distance `y` to the nearer wall, tabulated once per run on two uniform
/// grids, a fine one across the near-wall layer (where the profiles change fastest) and a
/// coarser one beyond: `sigma` interpolated linearly in the hot loop, the rest taken from the
/// cell's lower node. The cell index is a multiply and a truncation, with no square root or
/// logarithm on the particle step's critical path.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Table {
    split: f64,
    inv_fine: f64,
    inv_coarse: f64,
    /// Shared by clones: components with the same profile read the same nodes.
    nodes: Arc<[Node; NODES]>,
    /// The distance (m) from which every read gives the same node (the last nodes equal,
    /// as in a room's well-mixed core); the table's end where the profile changes to the end.
    flat_from: f64,
}

/// Nodes of a table: the fine grid's `TABLE_CELLS + 1` and the coarse grid's `TABLE_CELLS`.
const NODES: usize = 2 * TABLE_CELLS + 1;

impl Table {
    /// Tabulates `sigma(y)` and `T_L(y)` on `[0, y_max]` for time step `dt`, finely up to
    /// `y_split` (clamped into `(0, y_max)`), with the well-mixed drift when `drift` (zero
    /// otherwise: a component without it then adds zero in the same arithmetic, and the
    /// step needs no per-component switch).
    fn new(y_max: f64, y_split: f64, dt: f64, drift: bool, f: impl Fn(f64) -> (f64, f64)) -> Self {
        Self::with_tangential(y_max, y_split, dt, drift, f, |_| 1.0)
    }

    /// [`Table::new`] with a room's tangential factor `g(y)` in the same nodes, so that one
    /// look-up at a distance gives both the profile of the walls across it and the damping
    /// of the components along them.
    fn with_tangential(
        y_max: f64,
        y_split: f64,
        dt: f64,
        drift: bool,
        f: impl Fn(f64) -> (f64, f64),
        g: impl Fn(f64) -> f64,
    ) -> Self {
        let split = y_split.clamp(1e-3 * y_max, 0.5 * y_max);
        let (fine, coarse) = (split / TABLE_CELLS as f64, (y_max - split) / TABLE_CELLS as f64);
        let ys: Vec<f64> = (0..=TABLE_CELLS)
            .map(|i| i as f64 * fine)
            .chain((1..=TABLE_CELLS).map(|j| split + j as f64 * coarse))
            .collect();
        let mut nodes: Vec<Node> = ys
            .iter()
            .map(|&y| {
                let (sigma, t) = f(y);
                let decay = if t > 0.0 { (-dt / t).exp() } else { 0.0 };
                // `drift` holds T_L (1 - decay) until the slope is known.
                Node {
                    sigma,
                    rise: 0.0,
                    slope: 0.0,
                    decay,
                    noise: (1.0 - decay * decay).max(0.0).sqrt(),
                    drift: t * (1.0 - decay),
                    tangential: g(y),
                    tangential_rise: 0.0,
                }
            })
            .collect();
        for i in 0..nodes.len() - 1 {
            nodes[i].rise = nodes[i + 1].sigma - nodes[i].sigma;
            nodes[i].slope = nodes[i].rise / (ys[i + 1] - ys[i]);
            nodes[i].tangential_rise = nodes[i + 1].tangential - nodes[i].tangential;
        }
        for node in &mut nodes {
            node.drift = if drift { node.drift * node.slope } else { 0.0 };
        }
        // From the first of the equal nodes at the end on, a read gives the last node's
        // values.
        let last = nodes[nodes.len() - 1];
        let first_flat = nodes.iter().rposition(|n| *n != last).map_or(0, |i| i + 1);
        // One cell on, so that no read at the flat part's first node rounds into the cell
        // before it.
        let flat_from = ys[(first_flat + 1).min(ys.len() - 1)];
        let nodes = Arc::<[Node]>::from(nodes).try_into().expect("NODES nodes");
        Self { split, inv_fine: 1.0 / fine, inv_coarse: 1.0 / coarse, nodes, flat_from }
    }

    /// The node at or below distance `y` (m) and the fraction of its cell up to `y`, clamped
    /// to the table's range.
    #[inline(always)]
    fn locate(&self, y: f64) -> (usize, f64) {
        let y = y.max(0.0);
        // Both grids' coordinates, then a choice, rather than a branch.
        let (fine, coarse) = (y * self.inv_fine, TABLE_CELLS as f64 + (y - self.split) * self.inv_coarse);
        let s = if y < self.split { fine } else { coarse };
        // `s >= 0`; clamping the index against the constant table length lets the compiler
        // drop the bounds checks.
        let (cell, i) = cell_of(s.min((NODES - 2) as f64));
        (i.min(NODES - 2), (s - cell).min(1.0))
    }

    /// The distance (m) from which every read of the table gives the same node, bit for bit
    /// (a room's well-mixed core).
    pub fn flat_from(&self) -> f64 {
        self.flat_from
    }

    /// The steepest `|d sigma / dy|` of the table, 1/s.
    pub fn steepest(&self) -> f64 {
        self.nodes.iter().map(|n| n.slope.abs()).fold(0.0, f64::max)
    }

    /// The largest tangential factor of the table.
    pub fn largest_tangential(&self) -> f64 {
        self.nodes.iter().map(|n| n.tangential).fold(0.0, f64::max)
    }

    /// The profile at distance `y >= 0` (m), clamped to the table's range.
    #[inline(always)]
    pub fn at(&self, y: f64) -> Node {
        let (i, f) = self.locate(y);
        let a = self.nodes[i];
        // sigma is interpolated (the fluid velocity seen is continuous in y); the time-scale
        // factors and the slope are the cell's own (T_L changes little across a cell).
        Node { sigma: a.sigma + f * a.rise, tangential: a.tangential + f * a.tangential_rise, ..a }
    }

    /// [`Table::at`] for the four distances of the tracker's four lanes, bit for bit. With
    /// `AVX2` (which the caller may set only where the processor has AVX2) the cell search
    /// and the gather of the four nodes are AVX2 instructions, fewer than what the compiler
    /// makes of four [`Table::at`]s (docs/performance-log.md); otherwise it is those four.
    #[inline(always)]
    pub fn at4<const AVX2: bool>(&self, y: [f64; 4]) -> Nodes4 {
        #[cfg(target_arch = "x86_64")]
        if AVX2 {
            // SAFETY: the caller sets `AVX2` only where the processor has AVX2.
            return unsafe { self.at4_avx2(y) };
        }
        let n = y.map(|y| self.at(y));
        Nodes4 {
            sigma: n.map(|n| n.sigma),
            rise: n.map(|n| n.rise),
            slope: n.map(|n| n.slope),
            decay: n.map(|n| n.decay),
            noise: n.map(|n| n.noise),
            drift: n.map(|n| n.drift),
            tangential: n.map(|n| n.tangential),
            tangential_rise: n.map(|n| n.tangential_rise),
        }
    }

    /// [`Table::at4`] in AVX2: [`Table::locate`] with a vector floor and conversion (both
    /// exact here), then each lane's node loaded whole (two 32-byte halves) and transposed.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn at4_avx2(&self, y: [f64; 4]) -> Nodes4 {
        use std::arch::x86_64::*;
        let splat = _mm256_set1_pd;
        // As `locate`: `max` and `min` give the second operand for a NaN first one, so a NaN
        // distance reads node 0, as `f64::max` makes it do there.
        // SAFETY: `y` holds four f64s.
        let y = _mm256_max_pd(unsafe { _mm256_loadu_pd(y.as_ptr()) }, _mm256_setzero_pd());
        let fine = _mm256_mul_pd(y, splat(self.inv_fine));
        let coarse = _mm256_add_pd(
            splat(TABLE_CELLS as f64),
            _mm256_mul_pd(_mm256_sub_pd(y, splat(self.split)), splat(self.inv_coarse)),
        );
        let s = _mm256_blendv_pd(coarse, fine, _mm256_cmp_pd::<_CMP_LT_OQ>(y, splat(self.split)));
        let cell = _mm256_floor_pd(_mm256_min_pd(s, splat((NODES - 2) as f64)));
        let f = _mm256_min_pd(_mm256_sub_pd(s, cell), splat(1.0));
        // `0 <= cell <= NODES - 2`, an integer: the conversion is exact and the nodes below
        // are within the table. A node is eight f64s.
        let i = _mm256_cvttpd_epi32(cell);
        let at = _mm_slli_epi32::<3>(i);
        let base = self.nodes.as_ptr().cast::<f64>();
        let lane = |k: i32| base.wrapping_add(k as usize);
        let p = [
            lane(_mm_cvtsi128_si32(at)),
            lane(_mm_extract_epi32::<1>(at)),
            lane(_mm_extract_epi32::<2>(at)),
            lane(_mm_extract_epi32::<3>(at)),
        ];
        // SAFETY: each `p` is the first of a node's eight f64s, within the table.
        let (head, tail) = unsafe { (p.map(|p| _mm256_loadu_pd(p)), p.map(|p| _mm256_loadu_pd(p.add(4)))) };
        // head[l] = (sigma, rise, slope, decay) of lane l; tail[l] = (noise, drift, tangential,
        // tangential_rise).
        let (t0, t1) = (_mm256_unpacklo_pd(head[0], head[1]), _mm256_unpackhi_pd(head[0], head[1]));
        let (t2, t3) = (_mm256_unpacklo_pd(head[2], head[3]), _mm256_unpackhi_pd(head[2], head[3]));
        let (u0, u1) = (_mm256_unpacklo_pd(tail[0], tail[1]), _mm256_unpackhi_pd(tail[0], tail[1]));
        let (u2, u3) = (_mm256_unpacklo_pd(tail[2], tail[3]), _mm256_unpackhi_pd(tail[2], tail[3]));
        let rise = _mm256_permute2f128_pd::<0x20>(t1, t3);
        let sigma = _mm256_add_pd(_mm256_permute2f128_pd::<0x20>(t0, t2), _mm256_mul_pd(f, rise));
        let tangential_rise = _mm256_permute2f128_pd::<0x31>(u1, u3);
        let tangential = _mm256_add_pd(_mm256_permute2f128_pd::<0x31>(u0, u2), _mm256_mul_pd(f, tangential_rise));
        let lanes = |v: __m256d| -> [f64; 4] {
            let mut a = [0.0; 4];
            // SAFETY: `a` holds four f64s.
            unsafe { _mm256_storeu_pd(a.as_mut_ptr(), v) };
            a
        };
        Nodes4 {
            sigma: lanes(sigma),
            rise: lanes(rise),
            slope: lanes(_mm256_permute2f128_pd::<0x31>(t0, t2)),
            decay: lanes(_mm256_permute2f128_pd::<0x31>(t1, t3)),
            noise: lanes(_mm256_permute2f128_pd::<0x20>(u0, u2)),
            drift: lanes(_mm256_permute2f128_pd::<0x20>(u1, u3)),
            tangential: lanes(tangential),
            tangential_rise: lanes(tangential_rise),
        }
    }
}

/// Four nodes side by side, one per lane of the tracker's step ([`Table::at4`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Nodes4 {
    pub sigma: [f64; 4],
    pub rise: [f64; 4],
    pub slope: [f64; 4],
    pub decay: [f64; 4],
    pub noise: [f64; 4],
    pub drift: [f64; 4],
    pub tangential: [f64; 4],
    pub tangential_rise: [f64; 4],
}

/// The tangential factors `[g_1 g_2, g_0 g_2, g_0 g_1]` of the three components from the
/// factors `g_a` read at their distances along the three axes (see the module doc).
#[inline(always)]
pub(crate) fn tangential_products(g: [f64; 3]) -> [f64; 3] {
    [g[1] * g[2], g[0] * g[2], g[0] * g[1]]
}

impl Nodes4 {
    /// Lane `l`'s node.
    #[inline(always)]
    pub fn lane(&self, l: usize) -> Node {
        Node {
            sigma: self.sigma[l],
            rise: self.rise[l],
            slope: self.slope[l],
            decay: self.decay[l],
            noise: self.noise[l],
            drift: self.drift[l],
            tangential: self.tangential[l],
            tangential_rise: self.tangential_rise[l],
        }
    }
}

/// The cell holding the table coordinate `s` (`0 <= s < 2^31`): `floor(s)`, as a float and as
/// an index.
///
/// Adding `2^52` rounds `s` to the nearest integer and leaves it in the low bits of the sum's
/// mantissa; one comparison turns the rounding into a floor. All of it is vector arithmetic
/// when the compiler vectorises look-ups across the tracker's lanes (on processors without
/// AVX2, see [`Table::at4`]), where `s as i32` became a scalar conversion with a branch for
/// NaN in each lane, three times a step.
#[inline(always)]
fn cell_of(s: f64) -> (f64, usize) {
    const SHIFT: f64 = 4_503_599_627_370_496.0; // 2^52
    let nearest = (s + SHIFT) - SHIFT;
    let cell = if nearest > s { nearest - 1.0 } else { nearest };
    // The low 32 bits hold `cell` exactly (an integer below 2^31).
    (cell, (cell + SHIFT).to_bits() as u32 as usize)
}

/// One fluctuating component: its profile (with the well-mixed drift in its nodes when the
/// component carries one: in a channel the wall-normal one, in a room all three) and the axis
/// whose walls it is measured from.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Component {
    pub table: Table,
    pub axis: usize,
}

/// A scene's flow prepared for a time step: mean flow and turbulence as tables.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FlowField {
    /// A constant part of the mean velocity, m/s.
    pub uniform: [f64; 3],
    /// A mean velocity along `x` that varies with the distance from the `z` walls.
    pub profile: Option<Table>,
    /// The three fluctuating components, when turbulent.
    pub turbulence: Option<[Component; 3]>,
    /// A room's components are damped along walls: component `i` is scaled by the
    /// tangential factors `g` (in its table's nodes, 1 in the core) of its distances along
    /// the two other axes (see the module doc). Not in a channel, whose components already
    /// follow their own profiles (there every node's factor is 1).
    pub tangential: bool,
    /// A channel's intermittent wall-normal model ([`crate::intermittency`]), which then
    /// steps the wall-normal component's `zeta` in place of its Gaussian table (whose
    /// `sigma` still scales it).
    pub intermittent: Option<Intermittent>,
    /// A channel's Reynolds shear stress: the streamwise fluctuation takes `sign rho_uv
    /// u_rms` times the wall-normal `zeta` (this table's `sigma`, m/s, with `sign` that of
    /// `d(distance)/dz`), and its own `zeta` with the rest of its variance, `u_rms sqrt(1 -
    /// rho_uv^2)` (see [`stress_correlation`]).
    pub stress_coupling: Option<Table>,
    /// The distance (m) from which all three fluctuating components read the same, bit for
    /// bit, whatever the distance ([`Table::flat_from`]: a room's well-mixed core); infinite
    /// without turbulence.
    pub turbulence_flat_from: f64,
}

impl FlowField {
    /// The steepest gradient of a velocity fluctuation's rms along its own direction,
    /// `max |d sigma_i / dx_i|`, 1/s (zero without turbulence): what the well-mixed drift
    /// corrects for. (A channel's streamwise and spanwise rms change across the channel, not
    /// along their own directions, and need no drift.)
    /// In a room each is the wall-normal slope times the tangential factors of the two other
    /// axes, bounded here by the largest factor squared.
    pub fn steepest_gradient(&self) -> f64 {
        let along_own_axis = |(i, c): (usize, &Component)| (c.axis == i).then(|| c.table.steepest());
        let steepest =
            self.turbulence.iter().flat_map(|t| t.iter().enumerate().filter_map(along_own_axis)).fold(0.0, f64::max);
        let largest = |t: &[Component; 3]| t.iter().map(|c| c.table.largest_tangential()).fold(0.0, f64::max);
        let g = self.turbulence.as_ref().filter(|_| self.tangential).map_or(1.0, largest);
        steepest * g * g
    }

    /// Tabulates `flow` for a domain of `size` (m), kinematic viscosity `nu` (m^2/s) and step
    /// `dt` (s). `drift_correction = false` drops the well-mixed drift (for comparison only).
    pub fn new(flow: &Flow, size: [f64; 3], nu: f64, dt: f64, drift_correction: bool) -> Self {
        let half = size.map(|l| 0.5 * l);
        let mut field = FlowField {
            uniform: [0.0; 3],
            profile: None,
            turbulence: None,
            tangential: false,
            intermittent: None,
            stress_coupling: None,
            turbulence_flat_from: f64::INFINITY,
        };
        match *flow {
            Flow::Still => {}
            Flow::Uniform { velocity } => field.uniform = velocity,
            Flow::Poiseuille { max_speed } => {
                let h = size[2];
                field.profile = Some(Table::new(half[2], 0.25 * half[2], dt, false, |y| {
                    (4.0 * max_speed * y * (h - y) / (h * h), 0.0)
                }));
            }
            Flow::TurbulentChannel { friction_velocity: us } => {
                let plus = us / nu;
                let time = nu / (us * us);
                let split = FINE_Y_PLUS / plus;
                field.profile = Some(Table::new(half[2], split, dt, false, |y| (us * reichardt(y * plus), 0.0)));
                let comp = |rms: &dyn Fn(f64) -> f64, drift: bool| Component {
                    table: Table::new(half[2], split, dt, drift && drift_correction, |y| {
                        (us * rms(y * plus), time * lagrangian_time(y * plus))
                    }),
                    axis: 2,
                };
                // The streamwise fluctuation is split into its part correlated with the
                // wall-normal one, `rho_uv u_rms zeta_v`, and an independent rest.
                let rho = |y_plus: f64| stress_correlation(y_plus / (half[2] * plus));
                let independent = |y_plus: f64| streamwise_rms(y_plus) * (1.0 - rho(y_plus).powi(2)).sqrt();
                field.turbulence =
                    Some([comp(&independent, false), comp(&spanwise_rms, false), comp(&wall_normal_rms, true)]);
                field.stress_coupling = Some(Table::new(half[2], split, dt, false, |y| {
                    (us * rho(y * plus) * streamwise_rms(y * plus), 1.0)
                }));
            }
            Flow::TurbulentRoom { friction_velocity: us, core_rms, core_time, blend_length } => {
                let plus = us / nu;
                let time = nu / (us * us);
                let y_peak = ROOM_PEAK_Y_PLUS / plus;
                let (sigma_peak, t_peak) =
                    (us * wall_normal_rms(ROOM_PEAK_Y_PLUS), time * lagrangian_time(ROOM_PEAK_Y_PLUS));
                let profile = move |y: f64| {
                    if y <= y_peak {
                        (us * wall_normal_rms(y * plus), time * lagrangian_time(y * plus))
                    } else {
                        let f = ((y - y_peak) / blend_length).min(1.0);
                        (sigma_peak + f * (core_rms - sigma_peak), t_peak + f * (core_time - t_peak))
                    }
                };
                // The table ends at least two coarse cells past the core's start (a coarse cell
                // is at most `y_end / TABLE_CELLS`, and `y_end - core = 4 core / TABLE_CELLS`), so
                // its last cell is flat (no drift) and the clamp beyond it gives the core.
                // Particles in the core all read that one cell, and the near-wall layer's nodes
                // are dense: the table stays in cache. One table serves all three components.
                let split = FINE_Y_PLUS / plus;
                let core = y_peak + blend_length;
                let y_max = half.iter().copied().fold(0.0, f64::max);
                let y_end = (core * (1.0 + 4.0 / TABLE_CELLS as f64)).min(y_max);
                let t_peak = us * tangential_rms(ROOM_PEAK_Y_PLUS);
                let tangential = move |y: f64| {
                    let sigma = if y <= y_peak {
                        us * tangential_rms(y * plus)
                    } else {
                        t_peak + ((y - y_peak) / blend_length).min(1.0) * (core_rms - t_peak)
                    };
                    sigma / core_rms
                };
                let table = Table::with_tangential(y_end, split, dt, drift_correction, profile, tangential);
                let comp = |axis| Component { table: table.clone(), axis };
                field.turbulence = Some([comp(0), comp(1), comp(2)]);
                field.tangential = true;
            }
        }
        if let Some(turbulence) = &field.turbulence {
            field.turbulence_flat_from = turbulence.iter().map(|c| c.table.flat_from()).fold(0.0, f64::max);
        }
        field
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_room_table_reads_the_same_from_its_flat_distance_on() {
        // The indoor room (u* = 1 cm/s, blended into the core over 0.25 m): the profile's peak
        // is a few centimetres out, so the core starts about 0.3 m from a wall.
        let field = FlowField::new(&Flow::indoor_room(), [4.0, 3.0, 2.5], 1.5e-5, 0.1, true);
        let table = &field.turbulence.as_ref().expect("a room's turbulence")[0].table;
        let flat = table.flat_from();
        assert!(flat > 0.25 && flat < 0.4, "{flat}");
        let core = table.at(flat);
        for y in [flat, flat * 1.001, 0.5, 1.0, 1.25, 10.0] {
            assert_eq!(table.at(y), core, "{y}");
        }
        // Short of it the profile still changes.
        assert_ne!(table.at(0.8 * flat).sigma, core.sigma);
        assert_eq!(core.drift, 0.0);
        assert_eq!(core.sigma, 0.05);
    }

    #[test]
    fn wall_functions_have_their_textbook_limits() {
        // Viscous sublayer U+ = y+ and the log law U+ = ln(y+)/0.41 + 5.5 far out.
        assert!((reichardt(0.5) - 0.5).abs() < 0.01, "{}", reichardt(0.5));
        assert!((reichardt(1000.0) - (1000f64.ln() / 0.41 + 5.5)).abs() < 0.3, "{}", reichardt(1000.0));
        // Fluctuations vanish at the wall, wall-normal fastest (~ y+^2).
        assert_eq!(wall_normal_rms(0.0), 0.0);
        assert!((wall_normal_rms(1e-3) / 1e-6 - 0.0116).abs() < 1e-3);
        // Streamwise peak near y+ = 20-30 of about 2.5 u*.
        let peak = (1..200).map(|y| streamwise_rms(f64::from(y))).fold(0.0, f64::max);
        assert!((2.3..2.6).contains(&peak), "{peak}");
        assert!((wall_normal_rms(ROOM_PEAK_Y_PLUS) - 1.011).abs() < 1e-3);
        assert_eq!(lagrangian_time(1.0), 10.0);
        assert_eq!(lagrangian_time(500.0), lagrangian_time(200.0));
    }

    /// Kallio & Reeks' (1989) fits as Dehbi (2008) gives them, worked out by hand at `y+` =
    /// 1, 5, 10, 30 and 100 (the denominators `1 + 0.0239 y+^1.496`, `1 + 0.203 y+ + 0.0014
    /// y+^2.421` and `1 + 0.0361 y+^1.21` are 1.0239, 1.2044; 1.26549, 2.08392, 1.25308;
    /// 1.74885, 3.39909, 1.58548; 4.87410, 12.36520, 3.21220; 24.46377, 118.60340, 10.49527),
    /// with `d v+_rms / dy+` by the quotient rule: `[u+, v+, w+, T_L+, dv+/dy+]`.
    const KALLIO_REEKS_BY_HAND: [(f64, [f64; 5]); 5] = [
        (1.0, [0.390663, 0.00963135, 0.183380, 10.0, 0.0176124]),
        (5.0, [1.580409, 0.139161, 0.758131, 9.95525, 0.0398798]),
        (10.0, [2.287210, 0.341268, 1.198380, 12.724, 0.0389009]),
        (30.0, [2.461991, 0.844305, 1.774486, 23.154, 0.0133578]),
        (100.0, [1.635071, 0.978049, 1.810340, 51.532, -0.00153858]),
    ];

    /// `T_L` (s) of a node from its `decay = exp(-dt / T_L)`.
    fn time_of(node: &Node, dt: f64) -> f64 {
        -dt / node.decay.ln()
    }

    /// The fits and the channel's tables against the source's numbers worked out by hand: the
    /// three rms profiles, the Lagrangian time and the well-mixed drift `T_L (1 - exp(-dt /
    /// T_L)) d sigma / dy` of the wall-normal component. The tables' own discretisation (an
    /// interpolated `sigma`, a cell's lower node's `T_L`, a cell's slope) is within 0.12 %,
    /// 0.45 % and 1.9 % of the source here: the bands are 0.5 %, 1 % and 3 %.
    #[test]
    fn channel_profiles_and_time_scale_are_kallio_and_reeks_at_five_distances() {
        let (us, nu, half, dt) = (0.3, 1.5e-5, 0.02, 1e-5);
        let field =
            FlowField::new(&Flow::TurbulentChannel { friction_velocity: us }, [0.1, 0.1, 2.0 * half], nu, dt, true);
        let (plus, time) = (us / nu, nu / (us * us));
        let [x, y, z] = field.turbulence.as_ref().unwrap();
        let coupling = field.stress_coupling.as_ref().unwrap();
        let near = |a: f64, b: f64, rel: f64| (a / b - 1.0).abs() < rel;
        for (y_plus, [u, v, w, t_l, dv]) in KALLIO_REEKS_BY_HAND {
            assert!(near(streamwise_rms(y_plus), u, 2e-6), "u+ at {y_plus}: {}", streamwise_rms(y_plus));
            assert!(near(wall_normal_rms(y_plus), v, 2e-6), "v+ at {y_plus}: {}", wall_normal_rms(y_plus));
            assert!(near(spanwise_rms(y_plus), w, 2e-6), "w+ at {y_plus}: {}", spanwise_rms(y_plus));
            assert!(near(lagrangian_time(y_plus), t_l, 1e-9), "T_L+ at {y_plus}: {}", lagrangian_time(y_plus));
            let d = y_plus / plus;
            // The streamwise rms is split into a part correlated with the wall-normal one and
            // the rest: together they keep its variance.
            let streamwise = x.table.at(d).sigma.hypot(coupling.at(d).sigma);
            assert!(near(streamwise / us, u, 5e-3), "u+ table at {y_plus}: {}", streamwise / us);
            assert!(near(y.table.at(d).sigma / us, w, 5e-3), "w+ table at {y_plus}");
            let normal = z.table.at(d);
            assert!(near(normal.sigma / us, v, 5e-3), "v+ table at {y_plus}: {}", normal.sigma / us);
            for (axis, c) in [x, y, z].into_iter().enumerate() {
                let t = time_of(&c.table.at(d), dt);
                assert!(near(t / time, t_l, 1e-2), "T_L+ of component {axis} at {y_plus}: {}", t / time);
            }
            let drift = t_l * time * (1.0 - (-dt / (t_l * time)).exp()) * us * plus * dv;
            assert!(near(normal.drift, drift, 3e-2), "drift at {y_plus}: {} against {drift}", normal.drift);
        }
    }

    /// The room's tables against the same hand values (`u* = 1 cm/s`, so `y+ = 1` is 1.5 mm):
    /// the wall-normal profile, its Lagrangian time and drift, and the tangential factor
    /// `u* t+_rms / core_rms` up to the profile's peak (`y+ = 67`); at `y+ = 100` (0.15 m),
    /// 0.198 of the way through the blend into the core (0.0495 m of 0.25 m), by hand:
    /// `sigma = 0.0101105 + 0.198 (0.05 - 0.0101105) = 0.0180086 m/s`, `T_L = 5.95933 + 0.198
    /// (2 - 5.95933) = 5.17539 s` (`T_L+(67) = 39.7289` times `nu / u*^2 = 0.15 s`), slope
    /// `(0.05 - 0.0101105) / 0.25 = 0.159558 /s`, tangential factor 0.501882 (`t+_rms(67) =
    /// 1.894528`).
    #[test]
    fn room_profile_and_time_scale_are_kallio_and_reeks_near_a_wall() {
        let (us, nu, dt) = (0.01, 1.5e-5, 0.01);
        let field = FlowField::new(&Flow::indoor_room(), [4.0, 3.0, 2.5], nu, dt, true);
        let (plus, time) = (us / nu, nu / (us * us));
        let near = |a: f64, b: f64, rel: f64| (a / b - 1.0).abs() < rel;
        let t_plus = |u: f64, w: f64| (0.5 * (u * u + w * w)).sqrt();
        for component in field.turbulence.as_ref().unwrap() {
            let table = &component.table;
            for (y_plus, [u, v, w, t_l, dv]) in &KALLIO_REEKS_BY_HAND[..4] {
                let node = table.at(y_plus / plus);
                assert!(near(node.sigma, us * v, 5e-3), "sigma at {y_plus}: {}", node.sigma);
                assert!(near(time_of(&node, dt), time * t_l, 1e-2), "T_L at {y_plus}: {}", time_of(&node, dt));
                let drift = t_l * time * (1.0 - (-dt / (t_l * time)).exp()) * us * plus * dv;
                assert!(near(node.drift, drift, 3e-2), "drift at {y_plus}: {} against {drift}", node.drift);
                let g = us * t_plus(*u, *w) / 0.05;
                assert!(near(node.tangential, g, 5e-3), "tangential at {y_plus}: {}", node.tangential);
            }
            let node = table.at(0.15);
            assert!(near(node.sigma, 0.0180086, 1e-4), "{}", node.sigma);
            assert!(near(time_of(&node, dt), 5.17539, 1e-3), "{}", time_of(&node, dt));
            assert!(near(node.slope, 0.159558, 1e-4), "{}", node.slope);
            assert!(near(node.tangential, 0.501882, 1e-4), "{}", node.tangential);
        }
    }

    #[test]
    fn cell_of_is_the_floor() {
        let below = |x: f64| f64::from_bits(x.to_bits() - 1);
        for s in [0.0, 0.25, 0.5, 1.0, 1.5, 2.5, below(3.0), 3.0, 4095.5, below(8191.0), (NODES - 2) as f64] {
            let (cell, i) = cell_of(s);
            assert_eq!((cell, i), (s.floor(), s.floor() as usize), "{s}");
        }
    }

    #[test]
    fn table_interpolates_within_a_cell_and_clamps_outside() {
        let t = Table::new(1.0, 0.25, 0.1, true, |y| (y * y, 1.0));
        for y in [0.0, 1e-6, 0.01, 0.3, 0.999] {
            assert!((t.at(y).sigma - y * y).abs() < 1e-5, "{y}");
            assert!((t.at(y).slope - 2.0 * y).abs() < 2e-3, "{y}: {}", t.at(y).slope);
        }
        assert!((t.at(5.0).sigma - 1.0).abs() < 1e-3);
        let n = t.at(0.5);
        assert!((n.decay - (-0.1f64).exp()).abs() < 1e-12);
        assert!((n.noise - (1.0 - n.decay * n.decay).sqrt()).abs() < 1e-12);
        assert!((n.drift - (1.0 - n.decay) * n.slope).abs() < 1e-12);
    }

    #[test]
    fn four_lane_lookups_are_the_scalar_lookups_bit_for_bit() {
        // With a tangential factor that varies too, so its transposition is checked.
        let table = Table::with_tangential(1.0, 0.25, 0.1, true, |y| (y.sqrt() + y * y, 0.5 + y), |y| 0.2 + y.cbrt());
        let fine = 0.25 / TABLE_CELLS as f64;
        let mut ys =
            vec![0.0, -0.0, -1.0, 0.25, 1.0, 1.0 + 1e-9, 7.0, 1e300, f64::INFINITY, f64::NAN, f64::NEG_INFINITY];
        for k in [0.0, 1.0, 17.0, 1023.0, 1024.0] {
            let y: f64 = k * fine;
            ys.extend([y, f64::from_bits(y.to_bits() + 1), f64::from_bits(y.to_bits().max(1) - 1)]);
        }
        ys.extend((0..4000).map(|k| 1.1 * f64::from(k) / 4000.0));
        let same = |a: Node, b: Node| {
            let bits = |n: Node| {
                [n.sigma, n.rise, n.slope, n.decay, n.noise, n.drift, n.tangential, n.tangential_rise].map(f64::to_bits)
            };
            bits(a) == bits(b)
        };
        #[cfg(target_arch = "x86_64")]
        let avx2 = std::arch::is_x86_feature_detected!("avx2");
        #[cfg(not(target_arch = "x86_64"))]
        let avx2 = false;
        for y in ys.chunks(4).filter(|c| c.len() == 4) {
            let y: [f64; 4] = y.try_into().unwrap();
            let portable = table.at4::<false>(y);
            // Only where the processor has AVX2, as the tracker's step does.
            let vector = if avx2 { table.at4::<true>(y) } else { portable };
            for (l, &y) in y.iter().enumerate() {
                let scalar = table.at(y);
                assert!(same(portable.lane(l), scalar) && same(vector.lane(l), scalar), "{y}");
            }
        }
    }

    #[test]
    fn channel_tables_follow_the_fits() {
        let (us, nu, half) = (0.3, 1.5e-5, 0.005);
        let field =
            FlowField::new(&Flow::TurbulentChannel { friction_velocity: us }, [0.1, 0.1, 2.0 * half], nu, 1e-4, true);
        let plus = us / nu;
        let [x, y, z] = field.turbulence.as_ref().unwrap();
        let mean = field.profile.as_ref().unwrap();
        let coupling = field.stress_coupling.as_ref().unwrap();
        // The streamwise rms split into its part correlated with the wall-normal one and the rest.
        let rho = |y_plus: f64| stress_correlation(y_plus / (half * plus));
        let correlated = |y_plus: f64| rho(y_plus) * streamwise_rms(y_plus);
        let rest = |y_plus: f64| streamwise_rms(y_plus) * (1.0 - rho(y_plus).powi(2)).sqrt();
        for k in 0..=10_000 {
            let d = half * f64::from(k) / 10_000.0;
            // The split parts carry the kinks of the DNS table's linear pieces: 5e-4.
            for (table, fit, tolerance) in [
                (&x.table, &rest as &dyn Fn(f64) -> f64, 5e-4),
                (coupling, &correlated, 5e-4),
                (&y.table, &spanwise_rms, 1e-4),
                (&z.table, &wall_normal_rms, 1e-4),
                (mean, &reichardt, 1e-4),
            ] {
                let error = (table.at(d).sigma / us - fit(d * plus)).abs();
                assert!(error < tolerance, "y+ {}: {error}", d * plus);
            }
        }
    }

    #[test]
    fn only_the_wall_normal_channel_component_carries_the_drift() {
        let flow = Flow::TurbulentChannel { friction_velocity: 0.3 };
        let drifts = |correction: bool| {
            let field = FlowField::new(&flow, [0.1, 0.1, 0.01], 1.5e-5, 1e-4, correction);
            // y+ = 10, in the buffer layer where the rms profiles rise steeply.
            field.turbulence.unwrap().map(|c| c.table.at(10.0 * 1.5e-5 / 0.3).drift)
        };
        let [x, y, z] = drifts(true);
        assert!(x == 0.0 && y == 0.0 && z > 1e-3, "{x} {y} {z}");
        assert_eq!(drifts(false), [0.0; 3]);
        let room = FlowField::new(&Flow::indoor_room(), [4.0, 3.0, 2.5], 1.5e-5, 0.01, true);
        assert!(room.turbulence.unwrap().iter().all(|c| c.table.at(0.01).drift > 0.0));
    }

    #[test]
    fn room_profile_joins_the_core_continuously() {
        let flow = Flow::indoor_room();
        let field = FlowField::new(&flow, [4.0, 4.0, 3.0], 1.5e-5, 0.1, true);
        let comp = &field.turbulence.as_ref().unwrap()[2];
        let y_peak = ROOM_PEAK_Y_PLUS * 1.5e-5 / 0.01;
        let below = comp.table.at(y_peak * 0.999).sigma;
        let above = comp.table.at(y_peak * 1.001).sigma;
        assert!((below - above).abs() < 1e-4, "{below} {above}");
        assert!((comp.table.at(1.5).sigma - 0.05).abs() < 1e-9);
        assert!(comp.table.at(1e-4).sigma < 1e-4);
        // The table ends soon after the core starts (0.1 + 0.25 m here), and from just past
        // the core's start to the room's centre it gives the core: no drift, the core's time.
        let core = y_peak + 0.25;
        for y in [core * (1.0 + 2e-3), 0.5, 1.5, 2.0, 1e9] {
            let node = comp.table.at(y);
            assert!((node.sigma - 0.05).abs() < 1e-12, "{y}: {}", node.sigma);
            assert!(node.drift.abs() < 1e-15, "{y}: {}", node.drift);
            assert!((node.decay - (-0.1f64 / 2.0).exp()).abs() < 1e-12, "{y}: {}", node.decay);
        }
        // All three components read one table.
        let [a, b, c] = field.turbulence.as_ref().unwrap();
        assert!(Arc::ptr_eq(&a.table.nodes, &b.table.nodes) && Arc::ptr_eq(&b.table.nodes, &c.table.nodes));
    }

    #[test]
    fn room_components_along_a_wall_take_its_tangential_profile() {
        // u* = 1 cm/s, nu = 1.5e-5 m^2/s: y+ = 1 at 1.5 mm. By hand, u+_rms(1) = 0.4 / 1.0239
        // = 0.390663, w+_rms(1) = 0.19 / 1.0361 = 0.183380, t+_rms = sqrt((0.152618 +
        // 0.033628) / 2) = 0.305161, and g = 0.305161 * 0.01 / 0.05 = 0.0610322.
        assert!((tangential_rms(1.0) - 0.305161).abs() < 1e-6, "{}", tangential_rms(1.0));
        let field = FlowField::new(&Flow::indoor_room(), [4.0, 3.0, 2.5], 1.5e-5, 0.05, true);
        assert!(field.tangential);
        let table = &field.turbulence.as_ref().unwrap()[0].table;
        let factors = |d: [f64; 3]| tangential_products(d.map(|d| table.at(d).tangential));
        let near_floor = factors([2.0, 1.5, 1.5e-3]);
        for g in &near_floor[..2] {
            assert!((g - 0.0610322).abs() < 2e-5, "{g}");
        }
        // The floor's own normal component is not damped by the floor, nor is anything in the
        // core; in a corner two walls damp together.
        assert_eq!(near_floor[2], 1.0);
        assert_eq!(factors([2.0, 1.5, 1.2]), [1.0; 3]);
        let corner = factors([1.5e-3, 1.5, 1.5e-3]);
        assert!((corner[1] - 0.0610322 * 0.0610322).abs() < 1e-5, "{corner:?}");
        // At the profile's peak the tangential value joins the blend continuously.
        let y_peak = ROOM_PEAK_Y_PLUS * 1.5e-5 / 0.01;
        let (below, above) = (table.at(y_peak * 0.999).tangential, table.at(y_peak * 1.001).tangential);
        assert!((below - above).abs() < 1e-3, "{below} {above}");
        assert!((below - 0.01 * tangential_rms(ROOM_PEAK_Y_PLUS) / 0.05).abs() < 1e-3);
        // A channel's nodes carry 1.
        let channel =
            FlowField::new(&Flow::TurbulentChannel { friction_velocity: 0.3 }, [1.0, 1.0, 0.02], 1.5e-5, 1e-5, true);
        assert!(!channel.tangential);
        let wall_normal = &channel.turbulence.as_ref().unwrap()[2].table;
        assert!([0.0, 1e-5, 0.01].iter().all(|&y| wall_normal.at(y).tangential == 1.0));
    }
}
