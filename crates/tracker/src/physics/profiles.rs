//! The near-wall turbulence profiles of a channel, in wall units: Reichardt's (1951) mean
//! velocity, the Kallio & Reeks (1989) fits to channel DNS of the fluctuations' rms and the
//! Lagrangian time (as used by Dehbi 2008), and the Reynolds-stress correlation of Moser, Kim
//! & Mansour (1999). The dispersion model's tables ([`super::turbulence`]) and the intermittent
//! near-wall model ([`super::intermittency`]) are built from them; the equations are in
//! [`super::turbulence`]'s module doc.

/// von Karman's constant of Reichardt's profile.
pub(crate) const KARMAN: f64 = 0.41;
/// Wall units in which the room's wall-normal profile reaches its peak.
pub(crate) const ROOM_PEAK_Y_PLUS: f64 = 67.0;
/// The fits' range.
pub(crate) const FIT_MAX_Y_PLUS: f64 = 200.0;
/// Reichardt's mean velocity `U+` at `y+`.
#[must_use]
pub fn reichardt(y_plus: f64) -> f64 {
    (1.0 + KARMAN * y_plus).ln() / KARMAN
        + 7.8 * (1.0 - (-y_plus / 11.0).exp() - (y_plus / 11.0) * (-y_plus / 3.0).exp())
}

/// Streamwise fluctuation `u+_rms(y+)` (Kallio & Reeks 1989 fit).
#[must_use]
pub fn streamwise_rms(y_plus: f64) -> f64 {
    0.4 * y_plus / (1.0 + 0.0239 * y_plus.powf(1.496))
}

/// Wall-normal fluctuation `v+_rms(y+)` (Kallio & Reeks 1989 fit).
#[must_use]
pub fn wall_normal_rms(y_plus: f64) -> f64 {
    0.0116 * y_plus * y_plus / (1.0 + 0.203 * y_plus + 0.0014 * y_plus.powf(2.421))
}

/// Spanwise fluctuation `w+_rms(y+)` (Kallio & Reeks 1989 fit).
#[must_use]
pub fn spanwise_rms(y_plus: f64) -> f64 {
    0.19 * y_plus / (1.0 + 0.0361 * y_plus.powf(1.21))
}

/// A tangential fluctuation near a wall with no preferred direction along it, `t+_rms(y+)`:
/// the root mean square of the streamwise and spanwise fits, `sqrt((u+_rms^2 + w+_rms^2) / 2)`
/// (a room's near-wall air has no mean-flow direction; see the module doc).
#[must_use]
pub fn tangential_rms(y_plus: f64) -> f64 {
    let (u, w) = (streamwise_rms(y_plus), spanwise_rms(y_plus));
    (0.5 * (u * u + w * w)).sqrt()
}

/// The correlation coefficient `rho_uv = <u'v'> / (u_rms v_rms)` of the streamwise and
/// wall-normal fluctuations against `y / h` (the distance from the wall over the half-height),
/// from the wall to the centre: Moser, Kim & Mansour (1999), channel at `Re_tau = 178`,
/// `chan180.reystress` (`R_uv / sqrt(R_uu R_vv)`). Taken at `y / h` so that it vanishes at
/// the centre, as it must by symmetry; near the wall it is about -0.22, and -0.45 across most
/// of the channel.
pub const STRESS_CORRELATION: [(f64, f64); 64] = [
    (3.01180e-04, -0.2241),
    (1.20450e-03, -0.2320),
    (2.70950e-03, -0.2452),
    (4.81530e-03, -0.2640),
    (7.52050e-03, -0.2881),
    (1.08230e-02, -0.3164),
    (1.47220e-02, -0.3475),
    (1.92150e-02, -0.3789),
    (2.42980e-02, -0.4083),
    (2.99690e-02, -0.4337),
    (3.62240e-02, -0.4536),
    (4.30600e-02, -0.4676),
    (5.04720e-02, -0.4756),
    (5.84560e-02, -0.4784),
    (6.70070e-02, -0.4771),
    (7.61200e-02, -0.4731),
    (8.57900e-02, -0.4676),
    (9.60110e-02, -0.4616),
    (1.06780e-01, -0.4560),
    (1.18080e-01, -0.4514),
    (1.29910e-01, -0.4480),
    (1.42270e-01, -0.4459),
    (1.55150e-01, -0.4448),
    (1.68530e-01, -0.4446),
    (1.82420e-01, -0.4451),
    (1.96790e-01, -0.4462),
    (2.11650e-01, -0.4479),
    (2.26990e-01, -0.4500),
    (2.42790e-01, -0.4526),
    (2.59050e-01, -0.4554),
    (2.75750e-01, -0.4583),
    (2.92890e-01, -0.4612),
    (3.10460e-01, -0.4640),
    (3.28440e-01, -0.4663),
    (3.46830e-01, -0.4681),
    (3.65610e-01, -0.4695),
    (3.84770e-01, -0.4703),
    (4.04300e-01, -0.4703),
    (4.24190e-01, -0.4695),
    (4.44430e-01, -0.4677),
    (4.65000e-01, -0.4652),
    (4.85900e-01, -0.4617),
    (5.07100e-01, -0.4574),
    (5.28600e-01, -0.4524),
    (5.50390e-01, -0.4467),
    (5.72440e-01, -0.4403),
    (5.94760e-01, -0.4331),
    (6.17320e-01, -0.4249),
    (6.40100e-01, -0.4155),
    (6.63110e-01, -0.4046),
    (6.86320e-01, -0.3919),
    (7.09720e-01, -0.3771),
    (7.33290e-01, -0.3603),
    (7.57020e-01, -0.3414),
    (7.80900e-01, -0.3205),
    (8.04910e-01, -0.2972),
    (8.29040e-01, -0.2713),
    (8.53270e-01, -0.2418),
    (8.77590e-01, -0.2085),
    (9.01980e-01, -0.1717),
    (9.26440e-01, -0.1319),
    (9.50930e-01, -0.0895),
    (9.75460e-01, -0.0453),
    (1.00000e+00, 0.0000),
];

/// [`STRESS_CORRELATION`] at `y / h`, linear between its points and held at the ends.
#[must_use]
pub fn stress_correlation(y_over_h: f64) -> f64 {
    profile_at(&STRESS_CORRELATION, y_over_h)
}

/// A tabulated profile `(y, value)` (increasing `y`) at `y`: linear between its points, held at
/// the ends.
pub(crate) fn profile_at(points: &[(f64, f64)], y: f64) -> f64 {
    let (first, last) = (points[0], points[points.len() - 1]);
    if y <= first.0 {
        return first.1;
    }
    if y >= last.0 {
        return last.1;
    }
    let i = points.partition_point(|&(p, _)| p <= y);
    let ((y0, v0), (y1, v1)) = (points[i - 1], points[i]);
    v0 + (v1 - v0) * (y - y0) / (y1 - y0)
}

/// Lagrangian integral time `T_L+(y+)` (Kallio & Reeks 1989), held at its `y+ = 200` value
/// beyond the fit's range.
#[must_use]
pub fn lagrangian_time(y_plus: f64) -> f64 {
    let y = y_plus.min(FIT_MAX_Y_PLUS);
    if y < 5.0 {
        10.0
    } else {
        7.122 + 0.5731 * y - 0.00129 * y * y
    }
}
