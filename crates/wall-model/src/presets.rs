//! The fitted constants of the paper's Table 1, by id.
//!
//! Each row has `p = 1` and `k1 = k2 = k`, `kappa1 = kappa2 = kappa` (Eq. 10). The paper's
//! text extraction shifted each row's `vc, q` into the next row; the values here are the
//! re-aligned ones. The table gives no friction coefficient, so every preset has `mu = 0`:
//! set one with [`LawParams::with_friction`] for oblique impacts.

use crate::params::LawParams;

/// One row of Table 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preset {
    /// Stable id, e.g. `"li1997-sio2"`.
    pub id: &'static str,
    /// Where the data come from.
    pub source: &'static str,
    /// Particle material and diameter.
    pub particle: &'static str,
    /// Surface material.
    pub surface: &'static str,
    /// The fitted constants (`mu = 0`).
    pub params: LawParams,
    /// The table's last column, where printed. It is `R(vc)` for every row but `sim-35um`,
    /// where it is `R(vc)^2` (see [`Preset::last_column_is_squared`]).
    pub last_column: Option<f64>,
    /// True where the last column equals `R(vc)^2` rather than `R(vc)`.
    pub last_column_is_squared: bool,
    /// True where constants were reconstructed rather than read (the copper row's `k`).
    pub reconstructed: bool,
}

const fn row(
    id: &'static str,
    source: &'static str,
    particle: &'static str,
    surface: &'static str,
    (k, kappa, vc, q): (f64, f64, f64, f64),
    last_column: Option<f64>,
) -> Preset {
    Preset {
        id,
        source,
        particle,
        surface,
        params: LawParams { k1: k, k2: k, kappa1: kappa, kappa2: kappa, p: 1.0, q, vc, mu: 0.0 },
        last_column,
        last_column_is_squared: false,
        reconstructed: false,
    }
}

/// Every preset, in the table's order.
pub const PRESETS: [Preset; 10] = [
    row(
        "dahneke1975-quartz",
        "Dahneke 1975",
        "polystyrene latex (1.27 um)",
        "polished quartz",
        (556.3, 0.273, 0.967, 1.0),
        Some(0.998),
    ),
    row(
        "wall1990-molybdenum",
        "Wall et al. 1990",
        "ammonium fluorescein (3-7 um)",
        "molybdenum",
        (55.7, 0.586, 1.47, 1.0),
        Some(0.974),
    ),
    row(
        "wall1990-mica",
        "Wall et al. 1990",
        "ammonium fluorescein (3-7 um)",
        "mica",
        (72.5, 1.333, 1.10, 1.0),
        Some(0.985),
    ),
    // k is illegible in the paper: R(vc) = k/(k + vc) = 0.993 at vc = 0.29 gives k = 41.1;
    // kappa = 1.610 is itself uncertain.
    Preset {
        reconstructed: true,
        ..row(
            "dunn1995-copper",
            "Dunn et al. 1995 (k reconstructed)",
            "Ag-coated glass (8.6 um)",
            "copper",
            (41.1, 1.610, 0.29, 1.0),
            Some(0.993),
        )
    },
    row("dunn1995-tedlar", "Dunn et al. 1995", "Ag-coated glass (8.6 um)", "tedlar", (51.7, 4.070, -0.44, 1.0), None),
    row(
        "dunn1995-stainless",
        "Dunn et al. 1995",
        "Ag-coated glass (8.6 um)",
        "stainless steel",
        (272.0, 1.740, -0.40, 0.5),
        None,
    ),
    row(
        "li1997-sio2",
        "Dunn et al. 1996 / Li et al. 1997",
        "stainless steel (64-76 um)",
        "SiO2",
        (12.5, 0.065, 0.074, 0.5),
        Some(0.994),
    ),
    Preset {
        last_column_is_squared: true,
        ..row(
            "sim-35um",
            "Brach & Dunn 1998 simulation",
            "stainless steel (35 um)",
            "SiO2",
            (12.7, 0.197, 0.212, 0.5),
            Some(0.966),
        )
    },
    row(
        "sim-70um",
        "Brach & Dunn 1998 simulation",
        "stainless steel (70 um)",
        "SiO2",
        (12.5, 0.065, 0.074, 0.5),
        Some(0.994),
    ),
    row(
        "sim-140um",
        "Brach & Dunn 1998 simulation",
        "stainless steel (140 um)",
        "SiO2",
        (11.8, 0.019, 0.026, 0.5),
        Some(0.998),
    ),
];

/// The preset with this id, if there is one.
#[must_use]
pub fn preset(id: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.id == id)
}

/// The ids of every preset, for error messages and listings.
pub fn ids() -> impl Iterator<Item = &'static str> {
    PRESETS.iter().map(|p| p.id)
}

/// No preset has this id.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownPreset(pub String);

impl core::fmt::Display for UnknownPreset {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "unknown wall-law preset '{}'; known presets: {}", self.0, ids().collect::<Vec<_>>().join(", "))
    }
}

impl std::error::Error for UnknownPreset {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_exactly_those_of_the_model_table() {
        let ids: Vec<_> = ids().collect();
        assert_eq!(
            ids,
            [
                "dahneke1975-quartz",
                "wall1990-molybdenum",
                "wall1990-mica",
                "dunn1995-copper",
                "dunn1995-tedlar",
                "dunn1995-stainless",
                "li1997-sio2",
                "sim-35um",
                "sim-70um",
                "sim-140um"
            ]
        );
        assert!(preset("dunn1995-copper").unwrap().reconstructed);
        assert_eq!(PRESETS.iter().filter(|p| p.reconstructed).count(), 1);
    }

    #[test]
    fn every_preset_is_valid_and_unknown_ids_list_the_known_ones() {
        for p in &PRESETS {
            p.params.validate().unwrap();
        }
        let msg = UnknownPreset("granite".into()).to_string();
        assert!(msg.contains("granite") && msg.contains("li1997-sio2"));
    }
}
