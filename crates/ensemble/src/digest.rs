//! The closing diagnosis of a finished (or merged) run, read from its tables: a fault's ruptures
//! seed by seed, a block's statistics and what its base did, or why there is no event and what
//! to try. `stickslip pipeline` and `stickslip merge` print it ([`RunDigest`]'s `Display`).

use std::fmt;
use std::path::PathBuf;

use stickslip_analysis::SlipRegime;
use stickslip_config::Pipeline;
use stickslip_seismo::catalogue::compact;
use stickslip_solver::inspect::{Statics, spring_slider};
use stickslip_solver::{Channel, Model};
use stickslip_store::io::{any_part, read_parquet_if_present};
use stickslip_store::schema::{EVENTS_TABLE, RUNS, SERIES, SOURCE};
use stickslip_store::tables::events::Events;
use stickslip_store::tables::runs::Runs;
use stickslip_store::tables::series::largest_in_series;
use stickslip_store::tables::source::Sources;
use stickslip_store::{Folder, StoreError};

/// What a finished run says when it closes.
#[derive(Clone, Debug)]
pub struct RunDigest {
    /// What the base did in each finished seed.
    pub regimes: Regimes,
    /// The ruptures, the statistics, or why there is no event.
    pub outcome: Outcome,
}

/// The body of a [`RunDigest`].
#[derive(Clone, Debug)]
pub enum Outcome {
    /// A fault's ruptures, one per seed that ruptured (the `source` table).
    Ruptures(Box<Sources>),
    /// A block's statistics ([`crate::summary::digest`]) and, when seeds slid stably, the
    /// spring-slider verdict of `stickslip check`.
    Events {
        /// The statistics of the main shocks, as text.
        statistics: String,
        /// The spring-slider verdict, when some seed slid stably.
        slider: Option<String>,
    },
    /// No event (or no rupture): what the seeds recorded.
    NoEvents(Box<NoEvents>),
}

/// What a run without events recorded, and what its scene is, for the diagnosis.
#[derive(Clone, Debug)]
pub struct NoEvents {
    /// `events.v_on_m_s`.
    pub v_on_m_s: f64,
    /// Largest mean slip rate recorded, unsmoothed (m/s), if recorded.
    pub largest_slip_rate_m_s: Option<f64>,
    /// Largest shear stress recorded (Pa), with the static coefficient and the self-weight
    /// normal stress (Pa), if recorded.
    pub largest_shear: Option<(f64, f64, f64)>,
    /// Most base nodes lifted at once and the base's contact nodes, if recorded.
    pub lifted: Option<(f64, usize)>,
    /// Duration of the shear stage (s), the loading's displacement over it (m) and its velocity
    /// (m/s).
    pub shear: (f64, f64, f64),
    /// The spring-slider verdict of `stickslip check`.
    pub slider: String,
    /// The shear-stress figure when the report is written.
    pub figure: Option<PathBuf>,
    /// Whether the block is loaded through a loading plate.
    pub plate: bool,
}

impl RunDigest {
    /// The digest of the finished run of `pipeline` in `folder`: no part is read but the
    /// series' when there is no event; one model of the scene is built when the spring-slider
    /// verdict is asked for.
    pub fn of(pipeline: &Pipeline, folder: &Folder) -> Result<RunDigest, StoreError> {
        // Whether any seed has an event (the gathered table) or has run at all (a series part).
        let events =
            read_parquet_if_present(&folder.gathered(&EVENTS_TABLE))?.map(|df| Events::read(&df)).transpose()?;
        let ran = any_part(&folder.part_glob(&SERIES));
        let regimes = Regimes::of(folder)?;
        let outcome = if pipeline.scene.is_fault() {
            match read_parquet_if_present(&folder.gathered(&SOURCE))?.map(|df| Sources::read(&df)).transpose()? {
                Some(s) if !s.seed.is_empty() => Outcome::Ruptures(Box::new(s)),
                _ => Outcome::NoEvents(Box::new(NoEvents::of(pipeline, folder))),
            }
        } else if events.is_some_and(|e| !e.is_empty()) || !ran {
            let statistics = crate::summary::digest(folder)?;
            let slider = regimes.slid().then(|| slider_verdict(pipeline, &Model::new(pipeline.scene.clone())));
            Outcome::Events { statistics, slider }
        } else {
            Outcome::NoEvents(Box::new(NoEvents::of(pipeline, folder)))
        };
        Ok(RunDigest { regimes, outcome })
    }
}

impl NoEvents {
    fn of(pipeline: &Pipeline, folder: &Folder) -> NoEvents {
        let scene = &pipeline.scene;
        let sh = &scene.shear;
        let model = Model::new(scene.clone());
        let [rate, tau, lifted] = largest_in_series(
            &folder.part_glob(&SERIES),
            &[Channel::MeanSlipRate.name(), Channel::ShearStress.name(), Channel::LiftedNodes.name()],
        )[..] else {
            unreachable!("three channels asked")
        };
        let largest_shear = tau.map(|tau| {
            let sigma = model.total_mass() * scene.self_weight.gravity_m_s2 / model.lattice().contact_area();
            (tau, scene.friction.law.node(1.0).static_coefficient(), sigma)
        });
        NoEvents {
            v_on_m_s: pipeline.analysis.events.v_on_m_s,
            largest_slip_rate_m_s: rate,
            largest_shear,
            lifted: lifted.map(|l| (l, model.lattice().contact_nodes().len())),
            shear: (sh.duration_s, sh.driver_displacement(sh.duration_s), sh.velocity_m_s),
            slider: slider_verdict(pipeline, &model),
            figure: pipeline.report.enabled.then(|| folder.figures().join("shear_stress.png")),
            plate: scene.plate().is_some(),
        }
    }
}

/// What `stickslip check` expects of the scene, as a spring-slider.
fn slider_verdict(pipeline: &Pipeline, model: &Model) -> String {
    let statics = Statics::for_model(model);
    match spring_slider(model, pipeline.seeds[0], statics) {
        Ok(slider) => stickslip_config::keys::verdict(&slider, &pipeline.scene.friction.law),
        Err(e) => format!("not assessed ({e})"),
    }
}

/// What the base did in each finished seed, from the runs table (`slip_regime`).
#[derive(Clone, Debug)]
pub struct Regimes {
    /// Seeds of each regime.
    pub by: Vec<(SlipRegime, Vec<u64>)>,
    /// Start of the sliding that never stopped, per seed that ended sliding.
    pub sliding_from: Vec<(u64, f64)>,
    /// Finished seeds.
    pub seeds: usize,
}

impl Regimes {
    /// The regimes of the gathered runs table of `folder` (none without one).
    pub fn of(folder: &Folder) -> Result<Regimes, StoreError> {
        let runs = read_parquet_if_present(&folder.gathered(&RUNS))?.map(|df| Runs::read(&df)).transpose()?;
        let mut by: Vec<(SlipRegime, Vec<u64>)> = SlipRegime::ALL.iter().map(|&r| (r, Vec::new())).collect();
        let mut sliding_from = Vec::new();
        let mut seeds = 0;
        if let Some(r) = runs {
            for i in 0..r.seed.len() {
                let Some(regime) = SlipRegime::parse(&r.slip_regime[i]) else { continue };
                seeds += 1;
                by.iter_mut().find(|(g, _)| *g == regime).expect("every regime").1.push(r.seed[i]);
                if let Some(t) = r.sliding_from_s[i] {
                    sliding_from.push((r.seed[i], t));
                }
            }
        }
        Ok(Regimes { by, sliding_from, seeds })
    }

    /// Seeds of `regime`.
    pub fn seeds(&self, regime: SlipRegime) -> &[u64] {
        &self.by.iter().find(|(g, _)| *g == regime).expect("every regime").1
    }

    /// Whether some seed slid stably (to the end, or after stick-slip).
    pub fn slid(&self) -> bool {
        !self.seeds(SlipRegime::StableSliding).is_empty() || !self.seeds(SlipRegime::StickSlipThenSliding).is_empty()
    }

    /// "in 3 of 8 seeds (1, 4, 7)".
    fn among(&self, seeds: &[u64]) -> String {
        format!("in {} of {} ({})", seeds.len(), count(self.seeds, "seed", "seeds"), seed_list(seeds))
    }

    /// The range of the sliding onsets, "from t = 0.067 … 0.068 s".
    fn onset_text(&self, seeds: &[u64]) -> String {
        let t: Vec<f64> = self.sliding_from.iter().filter(|(s, _)| seeds.contains(s)).map(|p| p.1).collect();
        let (lo, hi) = t.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        let (a, b) = (format!("{lo:.3}"), format!("{hi:.3}"));
        match t.len() {
            0 => String::new(),
            _ if a == b => format!(" from t = {a} s"),
            _ => format!(" from t = {a} … {b} s"),
        }
    }

    /// What to say about seeds that slid stably, if any did.
    fn sliding_text(&self) -> Option<String> {
        let (sliding, then) = (self.seeds(SlipRegime::StableSliding), self.seeds(SlipRegime::StickSlipThenSliding));
        if sliding.is_empty() && then.is_empty() {
            return None;
        }
        let mut lines = vec![
            "stable sliding: the base slid along with its loading, without stopping — not an earthquake, so none of it \
             is in the catalogue (no main shock, no magnitude)"
                .to_string(),
        ];
        if !sliding.is_empty() {
            lines.push(format!("  sliding only {}{}", self.among(sliding), self.onset_text(sliding)));
        }
        if !then.is_empty() {
            lines.push(format!("  stick-slip, then sliding to the end {}{}", self.among(then), self.onset_text(then)));
        }
        Some(lines.join("\n"))
    }
}

impl fmt::Display for RunDigest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.outcome {
            Outcome::Ruptures(s) => f.write_str(&ruptures_text(s)),
            Outcome::Events { statistics, slider } => {
                f.write_str(statistics)?;
                if let (Some(text), Some(verdict)) = (self.regimes.sliding_text(), slider) {
                    write!(f, "\n{text}\n  as a spring-slider (stickslip check): {verdict}")?;
                }
                Ok(())
            }
            Outcome::NoEvents(n) => f.write_str(&self.no_events_text(n)),
        }
    }
}

/// The ruptures of a fault scene, seed by seed, from the `source` table.
fn ruptures_text(s: &Sources) -> String {
    let mut text = format!(
        "ruptures (the source table, from each seed's own slip; docs/model.md §15–16)\n{:>6} {:>6} {:>12} {:>10} \
         {:>18} {:>11} {:>18} {:>20}",
        "seed",
        "Mw",
        "stress drop",
        "mean slip",
        "median peak rate",
        "duration",
        "corner Brune/fit",
        "hypocentre (x, y)"
    );
    for i in 0..s.seed.len() {
        let corner = match s.fitted_corner_hz[i] {
            Some(f) => format!("{:.2}/{:.2} Hz", s.brune_corner_hz[i], f),
            None => format!("{:.2}/– Hz", s.brune_corner_hz[i]),
        };
        text.push_str(&format!(
            "\n{:>6} {:>6.2} {:>8.2} MPa {:>8.2} m {:>14.2} m/s {:>9.2} s {:>18} {:>9.1}, {:.1} km",
            s.seed[i],
            s.mw[i],
            s.stress_drop_pa[i] / 1e6,
            s.mean_slip_m[i],
            s.median_peak_slip_rate_m_s[i],
            s.rupture_duration_s[i],
            corner,
            s.hypocentre_m[i][0] / 1e3,
            s.hypocentre_m[i][1] / 1e3
        ));
    }
    text
}

impl RunDigest {
    /// Why a finished ensemble has no event, from what its seeds did and recorded, and what to try.
    fn no_events_text(&self, n: &NoEvents) -> String {
        let regimes = &self.regimes;
        let sliding = regimes.seeds(SlipRegime::StableSliding);
        let mut lines = Vec::new();
        if !sliding.is_empty() {
            lines.push(format!(
                "no events: the base slid stably {}{} — it kept up with its loading without stopping, so there is no \
                 stick-slip to catalogue (stable sliding is not an earthquake).",
                regimes.among(sliding),
                regimes.onset_text(sliding)
            ));
        }
        let held = regimes.seeds(SlipRegime::NoSlip);
        if !held.is_empty() || sliding.is_empty() {
            lines.push(format!(
                "no events{}: an event is a burst of slip of the base — the mean slip rate, smoothed over \
                 events.smoothing_s, must rise above events.v_on_m_s and τ must then drop by at least events.min_drop_pa.",
                if held.is_empty() { String::new() } else { format!(" {}", regimes.among(held)) }
            ));
            match n.largest_slip_rate_m_s {
                Some(v) => lines.push(format!(
                    "  largest mean slip rate recorded (unsmoothed): {v:.3e} m/s against v_on = {} m/s{}",
                    compact(n.v_on_m_s),
                    if v < n.v_on_m_s { ": the base never slipped fast enough" } else { "" }
                )),
                None => lines.push("  the slip rate is not recorded (add \"slip_rate\" to record.interface)".into()),
            }
            if let Some((tau, mu, sigma)) = n.largest_shear {
                lines.push(format!(
                    "  largest shear stress τ: {tau:.4e} Pa; sliding needs about μs·σ = {:.4e} Pa (μs = {}, self-weight σ = \
                     {sigma:.4e} Pa)",
                    mu * sigma,
                    compact(mu)
                ));
            }
            if let Some((lifted, contacts)) = n.lifted
                && lifted >= 0.5 * contacts as f64
            {
                lines.push(format!(
                    "  up to {lifted:.0} of {contacts} base nodes were lifted at once: the load tips the block over \
                     rather than sliding it"
                ));
            }
            let (duration, moved, velocity) = n.shear;
            lines.push(format!(
                "  the shear stage lasted {} s: the loading moved about {moved:.3e} m at {} m/s",
                compact(duration),
                compact(velocity)
            ));
        }
        lines.push(format!("  as a spring-slider (stickslip check): {}", n.slider));
        let look = match &n.figure {
            Some(figure) => format!("look at {} (written with the report below) and", figure.display()),
            None => "look at the series table and".to_string(),
        };
        if sliding.is_empty() {
            lines.push(format!(
                "  try: a longer [shear] duration_s (or a faster velocity_m_s) so τ reaches the strength; a lower \
                 [friction] mu_static; a lower [events] v_on_m_s or min_drop_pa for small events; and {look} \
                 `stickslip check` for what the scene builds"
            ));
        } else {
            let softer = if n.plate {
                "softer [loading_plate] springs"
            } else {
                "a [loading_plate] on springs instead of rigid driver nodes"
            };
            lines.push(format!(
                "  for stick-slip a slip must outrun its loading and stop again: {softer}, less [shear] damping_per_s, \
                 a larger μs − μd (the spring-slider reading above says which matters here); {look} `stickslip check`"
            ));
        }
        lines.join("\n")
    }
}

/// Seeds as a compact list: runs of consecutive seeds as ranges, "1–100, 123, 200".
pub fn seed_list(seeds: &[u64]) -> String {
    let mut v = seeds.to_vec();
    v.sort_unstable();
    v.dedup();
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < v.len() {
        let mut j = i;
        while j + 1 < v.len() && v[j + 1] == v[j] + 1 {
            j += 1;
        }
        parts.push(match j - i {
            0 => v[i].to_string(),
            1 => format!("{}, {}", v[i], v[j]),
            _ => format!("{}–{}", v[i], v[j]),
        });
        i = j + 1;
    }
    parts.join(", ")
}

/// `n` and the noun, singular or plural: "1 seed", "3 seeds".
pub fn count(n: usize, singular: &str, plural: &str) -> String {
    format!("{n} {}", if n == 1 { singular } else { plural })
}
