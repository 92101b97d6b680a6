//! The calibration of near-wall excursions' splitting by pilot runs. The excursions themselves
//! (what a scene asks for, and why) are [`crate::model::excursions`]; the tracking layer runs
//! them.

use crate::estimation::run::run;
use crate::model::error::SceneError;
use crate::model::excursions::{Excursions, MAX_LEVELS};
use crate::model::scene::{Injection, Scene};
use crate::model::settings::RunSettings;

/// Salt of the pilot runs' seed.
const PILOT_SALT: u64 = 0x3c6e_f372_fe94_f82b;

impl Excursions {
    /// These excursions with their splitting factors calibrated for `scene` run with `settings`
    /// (whose own excursions are left aside) and `injection`:
    /// `rounds` pilot runs of `count` particles, each with the factors the one before found
    /// ([`Splitting::calibrated`](crate::model::excursions::Splitting::calibrated), at most `max` per level). The pilots use their own seed, so
    /// the run that follows is as unbiased as with any fixed factors. Also the last pilot's
    /// share of weight given up at [`Excursions::max_duration`]
    /// ([`Run::truncated_share`](crate::Run::truncated_share)).
    pub fn calibrated(
        mut self,
        scene: &Scene,
        settings: &RunSettings,
        injection: &Injection,
        count: usize,
        rounds: usize,
        max: u32,
    ) -> Result<(Self, f64), SceneError> {
        let mut pilot = settings.clone();
        pilot.seed = settings.seed ^ PILOT_SALT;
        let injection = Injection { count, ..*injection };
        let mut truncated = 0.0;
        for _ in 0..rounds {
            pilot.excursions = Some(self.clone());
            let result = run(scene, &pilot, &injection)?;
            let mut arrivals = [0.0; MAX_LEVELS];
            let mut branches = [0u64; MAX_LEVELS];
            let mut started = 0.0;
            for p in &result.particles {
                started += f64::from(p.excursions);
                for k in 0..MAX_LEVELS {
                    arrivals[k] += p.arrivals[k];
                    branches[k] += p.branches[k];
                }
            }
            self.splitting = self.splitting.calibrated(started, &arrivals, &branches, max);
            truncated = result.truncated_share();
        }
        Ok((self, truncated))
    }
}
