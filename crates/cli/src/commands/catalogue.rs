//! `stickslip catalogue`: the statistics of an ensemble's event catalogue.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use stickslip_ensemble::catalogue::{
    B_VALUE_MIN_RANGE, CatalogueStats, GOF_LEVEL_PERCENT, MAGNITUDE_BIN, magnitude_convention, rewrite_catalogue,
};
use stickslip_store::Folder;
use stickslip_store::io::read_parquet_if_present;
use stickslip_store::schema::RUNS;
use stickslip_store::tables::catalogue::Outcome;
use stickslip_store::tables::runs::Runs;

use crate::text::seed_list;

/// Arguments of `stickslip catalogue`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Output folder of an ensemble (its gathered events, similarity and runs tables).
    pub folder: PathBuf,
    /// Also print the rows of this seed (the tables hold every seed's).
    #[arg(long)]
    pub seed: Option<u64>,
}

/// `stickslip catalogue`: recomputes the catalogue tables from the gathered tables (so a folder
/// written before they existed gets them) and prints the pooled statistics.
pub fn run(a: Args) -> Result<()> {
    let folder = Folder::new(&a.folder);
    folder.require_output()?;
    // A seed that is not the folder's is refused before anything is rewritten.
    if let Some(seed) = a.seed {
        let runs = read_parquet_if_present(&folder.gathered(&RUNS))?.map(|df| Runs::read(&df)).transpose()?;
        let seeds = runs.map(|r| r.ok_seeds()).unwrap_or_default();
        if !seeds.contains(&seed) {
            bail!(
                "--seed {seed} is not a seed of {} (its finished seeds: {})",
                a.folder.display(),
                if seeds.is_empty() { "none".into() } else { seed_list(&seeds) }
            );
        }
        if seeds.len() == 1 {
            bail!("--seed {seed}: the folder has one seed, so its statistics are the pooled ones (run without --seed)");
        }
    }
    let Some(stats) = rewrite_catalogue(&folder).with_context(|| format!("{}", a.folder.display()))? else {
        bail!(
            "{} has no gathered events table yet: finish the ensemble (`stickslip pipeline` or `stickslip merge`) first",
            a.folder.display()
        );
    };
    print(&stats, None);
    if let Some(seed) = a.seed {
        outln!();
        if stats.b_values.iter().any(|r| r.seed == Some(seed)) {
            print(&stats, Some(seed));
        } else {
            outln!("seed {seed} has no events: no statistics of its own");
        }
    }
    outln!(
        "\ntables → {} (magnitude_frequency, b_values, recurrence_stats, aftershocks, omori, scaling)",
        folder.tables().display()
    );
    Ok(())
}

fn or_reason<T>(o: &Outcome<T>, mut f: impl FnMut(&T) -> String) -> String {
    match o {
        Ok(v) => f(v),
        Err(why) => format!("no fit: {why}"),
    }
}

fn print(s: &CatalogueStats, seed: Option<u64>) {
    let who = seed.map_or("all seeds pooled".to_string(), |s| format!("seed {s}"));
    outln!(
        "Gutenberg–Richter ({who}; bins of {MAGNITUDE_BIN}, Mc by {GOF_LEVEL_PERCENT}% goodness of fit, else maximum curvature + 0.2)"
    );
    let mut narrow = Vec::new();
    let mut fitted = Vec::new();
    for r in s.b_values.iter().filter(|r| r.seed == seed) {
        // The magnitudes above Mc: from Mc to the largest bin holding events.
        let largest = |mc: f64| {
            s.frequency
                .iter()
                .filter(|b| b.seed == seed && b.quantity == r.quantity && b.incremental > 0 && b.centre >= mc - 1e-9)
                .map(|b| b.centre)
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let fit = or_reason(&r.fit, |f| {
            let top = largest(f.mc);
            let bins = ((top - f.mc) / MAGNITUDE_BIN).round() as i64 + 1;
            let range = bins as f64 * MAGNITUDE_BIN;
            if range < B_VALUE_MIN_RANGE - 1e-9 {
                narrow.push((r.quantity.clone(), bins, range));
            }
            fitted.push((r.quantity.clone(), f.b));
            format!(
                "Mc {:.1}, {} events ≥ Mc in {bins} bins (Mc to {top:.1}), b = {:.2} ± {:.2} (Shi–Bolt), a = {:.2}",
                f.mc, f.n, f.b, f.b_sigma, f.a
            )
        });
        outln!("  {:<30} {:>7} events  {fit}", r.quantity, r.events);
    }
    outln!("  (the magnitude columns of tables/similarity.parquet:");
    for r in s.b_values.iter().filter(|r| r.seed == seed) {
        outln!("    {}: {}", r.quantity, magnitude_convention(&r.quantity));
    }
    outln!("  )");
    for (quantity, bins, range) in &narrow {
        outln!(
            "  warning: {quantity}: b fitted from {bins} magnitude bin{} above Mc ({range:.1} units); a b-value reads as \
             the slope of a Gutenberg–Richter power law only over at least {B_VALUE_MIN_RANGE:.1} unit above Mc ({} \
             bins of {MAGNITUDE_BIN}): this one measures how closely the sizes cluster",
            if *bins == 1 { "" } else { "s" },
            (B_VALUE_MIN_RANGE / MAGNITUDE_BIN).round()
        );
    }
    let (lo, hi) = fitted.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (_, v)| (a.min(*v), b.max(*v)));
    if fitted.len() > 1 && hi > 1.2 * lo {
        outln!(
            "  warning: the {} conventions give b = {lo:.2} … {hi:.2} for the same events: the paper's moment is the \
             consistent one × λ (a shift of log10 λ) and Riera's M is 0.98 × Mw plus a constant, so a power law would \
             give b-values within 2% of each other; these follow where the bins fall, not the events' sizes",
            fitted.len()
        );
    }
    outln!("Recurrence ({who}; model-scale seconds, intervals within each seed)");
    for r in s.recurrence.iter().filter(|r| r.seed == seed) {
        let stats = or_reason(&r.stats, |st| {
            let ci = r.cv_ci95.map_or(String::new(), |(lo, hi)| format!(" [{lo:.2}, {hi:.2}]"));
            format!("mean {:.4} s, CV {:.2}{ci}", st.mean, st.cv)
        });
        let bpt = r
            .bpt
            .as_ref()
            .map_or(String::new(), |b| format!("; BPT μ {:.4} s α {:.2} (AIC {:.1})", b.mean, b.aperiodicity, b.aic));
        let wb = r
            .weibull
            .as_ref()
            .map_or(String::new(), |w| format!("; Weibull λ {:.4} s k {:.2} (AIC {:.1})", w.scale, w.shape, w.aic));
        let ex = r.exponential.as_ref().map_or(String::new(), |e| format!("; Poisson AIC {:.1}", e.aic));
        outln!("  {:<5} {:>7} intervals  {stats}{bpt}{wb}{ex}", r.sequence, r.intervals);
    }
    outln!("Aftershocks ({who}; every event until the next main shock or the end of the run)");
    for r in s.omori.iter().filter(|r| r.seed == seed) {
        let fit = or_reason(&r.fit, |f| {
            format!("Omori–Utsu p = {:.2} ± {:.2}, c = {:.3e} ± {:.1e} s, K = {:.3e}", f.p, f.p_se, f.c, f.c_se, f.k)
        });
        outln!("  {} main shocks, {} aftershocks: {fit}", r.main_shocks, r.aftershocks);
    }
    outln!("Scaling ({who}; prototype moment N·m, area m², duration s; stress drop Pa against Mw)");
    for r in s.scaling.iter().filter(|r| r.seed == seed) {
        let fit = or_reason(&r.fit, |f| {
            format!(
                "exponent {:.2} [{:.2}, {:.2}] over {} events (self-similar {})",
                f.line.exponent, f.exponent_ci95.0, f.exponent_ci95.1, f.n, r.self_similar
            )
        });
        outln!("  {:<22} {fit}", r.relation);
    }
    let equal_areas = s.scaling.iter().any(|r| {
        r.seed == seed && r.relation == "moment_area" && r.fit.as_ref().is_err_and(|e| e.contains("no spread"))
    });
    if equal_areas {
        outln!(
            "  every event has the same area (similarity.area = \"contact\"): moment is then stress drop × a \
             constant, so stress drop against Mw has slope 1.5 by construction; set similarity.area = \"rupture\" \
             (and record slipping_nodes) for per-event areas"
        );
    }
}
