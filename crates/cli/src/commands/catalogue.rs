//! `stickslip catalogue`: the statistics of an ensemble's event catalogue.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use stickslip_ensemble::catalogue::{CatalogueStats, GOF_LEVEL_PERCENT, MAGNITUDE_BIN, rewrite_catalogue};
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

fn or_reason<T>(o: &Outcome<T>, f: impl Fn(&T) -> String) -> String {
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
    for r in s.b_values.iter().filter(|r| r.seed == seed) {
        let fit = or_reason(&r.fit, |f| {
            format!("Mc {:.1}, {} events ≥ Mc, b = {:.2} ± {:.2} (Shi–Bolt), a = {:.2}", f.mc, f.n, f.b, f.b_sigma, f.a)
        });
        outln!("  {:<30} {:>7} events  {fit}", r.quantity, r.events);
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
