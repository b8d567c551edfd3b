//! The catalogue statistics of an ensemble, on a synthetic catalogue with known answers: a
//! Gutenberg–Richter sample of b = 1, quasi-periodic main shocks among Poisson minor events,
//! moments, areas and durations on exact self-similar power laws.

use polars::prelude::*;
use stickslip_ensemble::catalogue::catalogue_stats;
use stickslip_store::schema::col;

/// SplitMix64 uniform in (0, 1).
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 + 0.5 / (1u64 << 53) as f64
    }
}

const SEEDS: u64 = 20;
const EVENTS_PER_SEED: usize = 500;
const MAINS_PER_SEED: usize = 25;
const PERIOD_S: f64 = 40.0;
const RUN_S: f64 = PERIOD_S * (MAINS_PER_SEED as f64 + 1.0);
/// Magnitudes are continuous above this, so the bin centred on 3.0 is complete.
const M_MIN: f64 = 2.95;

fn frames() -> (DataFrame, DataFrame, DataFrame, usize) {
    let mut rng = Rng(7);
    let (mut seed, mut start, mut kind, mut mw) = (vec![], vec![], vec![], vec![]);
    let mut after_first_main = 0;
    for s in 0..SEEDS {
        let mut events: Vec<(f64, bool)> =
            (1..=MAINS_PER_SEED).map(|k| (k as f64 * PERIOD_S * (1.0 + 0.001 * (rng.uniform() - 0.5)), true)).collect();
        events.extend((MAINS_PER_SEED..EVENTS_PER_SEED).map(|_| (rng.uniform() * RUN_S, false)));
        events.sort_by(|a, b| a.0.total_cmp(&b.0));
        after_first_main +=
            events.iter().filter(|(t, main)| !main && *t > events.iter().find(|e| e.1).unwrap().0).count();
        for (t, main) in events {
            seed.push(s);
            start.push(t);
            kind.push(if main { "main" } else { "minor" });
            // Gutenberg–Richter, b = 1: M = M_MIN − log10(U).
            mw.push(M_MIN - rng.uniform().log10());
        }
    }
    let m0: Vec<f64> = mw.iter().map(|m| 10f64.powf(1.5 * m + 16.1)).collect(); // dyne·cm
    let area: Vec<f64> = m0.iter().map(|m| 1e-6 * m.powf(2.0 / 3.0)).collect();
    let duration: Vec<f64> = m0.iter().map(|m| 1e-8 * m.cbrt()).collect();
    let drop: Vec<f64> = mw.iter().map(|_| 3e6).collect();
    let runs = df!(col::SEED => (0..SEEDS).collect::<Vec<u64>>(), col::SIMULATED_TIME_S => vec![RUN_S; SEEDS as usize])
        .unwrap();
    let events = df!(col::SEED => seed.clone(), col::START_S => start).unwrap();
    let similarity = df!(
        col::SEED => seed,
        col::KIND => kind,
        col::MW_CONSISTENT => mw.clone(),
        col::MW_PAPER => mw.clone(),
        col::M_RIERA_PAPER_INTERPLATE => mw.clone(),
        col::M_RIERA_CONSISTENT_INTERPLATE => mw,
        col::M0_CONSISTENT_DYNE_CM => m0,
        col::STRESS_DROP_PA => drop,
        col::PROTOTYPE_AREA_M2 => area,
        col::PROTOTYPE_DURATION_S => duration,
    )
    .unwrap();
    (runs, events, similarity, after_first_main)
}

#[test]
fn synthetic_catalogue_gives_its_known_statistics() {
    let (runs, events, similarity, after_first_main) = frames();
    let s = catalogue_stats(&runs, &events, &similarity).unwrap();

    // Gutenberg–Richter: 10,000 events of b = 1 give b within 2σ (σ ≈ 0.01) and Mc in the first bin
    // or the next.
    let gr = s.b_values.iter().find(|r| r.seed.is_none() && r.quantity == col::MW_CONSISTENT).unwrap();
    let fit = gr.fit.as_ref().unwrap();
    assert_eq!(gr.events, SEEDS * EVENTS_PER_SEED as u64);
    assert!((fit.b - 1.0).abs() < 2.0 * fit.b_sigma, "b = {} ± {}", fit.b, fit.b_sigma);
    assert!((2.95..=3.15).contains(&fit.mc), "Mc = {}", fit.mc);
    // Per seed, 500 events still fit (b = 1 ± ~0.05); the table has every seed.
    assert_eq!(s.b_values.iter().filter(|r| r.seed.is_some() && r.quantity == col::MW_CONSISTENT).count(), 20);
    // The cumulative distribution's first bin holds every event.
    let first =
        s.frequency.iter().find(|b| b.seed.is_none() && b.quantity == col::MW_CONSISTENT && b.centre > 2.9).unwrap();
    assert_eq!(first.cumulative, SEEDS * EVENTS_PER_SEED as u64);

    // Recurrence: main shocks jittered by ±0.05% of their period give CV ≈ 0; the minor events,
    // uniform in time, make the whole catalogue Poisson-like (CV ≈ 1).
    let main = s.recurrence.iter().find(|r| r.seed.is_none() && r.sequence == "main").unwrap();
    let all = s.recurrence.iter().find(|r| r.seed.is_none() && r.sequence == "all").unwrap();
    assert_eq!(main.intervals, SEEDS * (MAINS_PER_SEED as u64 - 1));
    let main_cv = main.stats.as_ref().unwrap().cv;
    assert!(main_cv < 0.01, "main CV {main_cv}");
    let mean = main.stats.as_ref().unwrap().mean;
    assert!((mean / PERIOD_S - 1.0).abs() < 1e-3, "main mean {mean}");
    let all_cv = all.stats.as_ref().unwrap().cv;
    assert!((0.85..1.1).contains(&all_cv), "all CV {all_cv}");
    // The BPT fits the periodic main shocks better than Poisson does.
    assert!(main.bpt.as_ref().unwrap().aic < main.exponential.as_ref().unwrap().aic);

    // Aftershocks: every event after a seed's first main shock falls in a window (windows run to
    // the next main shock or the run's end); the pooled stack holds them all.
    let om = s.omori.iter().find(|r| r.seed.is_none()).unwrap();
    assert_eq!(om.main_shocks, SEEDS * MAINS_PER_SEED as u64);
    assert_eq!(om.aftershocks as usize, after_first_main);
    let counted: u64 = s.aftershocks.iter().filter(|b| b.seed.is_none()).map(|b| b.bin.count as u64).sum();
    assert!(counted <= om.aftershocks && counted > om.aftershocks * 9 / 10, "{counted} of {}", om.aftershocks);

    // Scaling: exact power laws give their exponents, a constant stress drop the self-similar 0.
    let exponent = |relation: &str| {
        s.scaling
            .iter()
            .find(|r| r.seed.is_none() && r.relation == relation)
            .unwrap()
            .fit
            .as_ref()
            .map(|f| f.exponent())
    };
    assert!((exponent("moment_area").unwrap() - 1.5).abs() < 1e-9);
    assert!((exponent("moment_duration").unwrap() - 3.0).abs() < 1e-9);
    assert!(exponent("stress_drop_magnitude").unwrap().abs() < 1e-9);
}

#[test]
fn a_catalogue_too_small_says_why_for_every_statistic() {
    let (runs, events, similarity, _) = frames();
    let (events, similarity) = (events.head(Some(4)), similarity.head(Some(4)));
    let s = catalogue_stats(&runs, &events, &similarity).unwrap();
    for r in s.b_values.iter().filter(|r| r.seed.is_none()) {
        let why = r.fit.as_ref().unwrap_err();
        assert!(why.contains("4 usable, at least 50 needed"), "{why}");
    }
    for r in s.recurrence.iter().filter(|r| r.seed.is_none()) {
        assert!(r.stats.as_ref().is_err_and(|e| e.contains("at least 5 needed")), "{:?}", r.stats);
    }
    assert!(s.omori.iter().all(|r| r.fit.is_err()));
}
